"""Marker repair: the repaired markers, motion and report against the command line."""
import json

import numpy as np
import pytest

import mocapsolve
from conftest import data_file, run_cli


def test_repair_is_bit_identical_to_the_cli(cmu02, tmp_path):
    subject = mocapsolve.read_subject(cmu02["subject"])
    markers, motion, report = mocapsolve.repair(subject, cmu02["c3d"])
    cli_markers = str(tmp_path / "cli.c3d")
    cli_motion = str(tmp_path / "cli.bvh")
    cli_report = str(tmp_path / "cli.json")
    run_cli("repair", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"],
            "--out_markers=" + cli_markers, "--out_motion=" + cli_motion, "--report=" + cli_report)
    ours = str(tmp_path / "py.c3d")
    mocapsolve.write_markers(ours, markers)
    assert open(ours, "rb").read() == open(cli_markers, "rb").read()
    ours_bvh = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours_bvh, subject.skeleton, motion)
    assert open(ours_bvh).read() == open(cli_motion).read()
    expected = json.load(open(cli_report))
    for key in ("rms_naive_mm", "rms_reference_mm", "rms_repaired_mm", "resolved_frames", "frames"):
        assert report[key] == pytest.approx(expected[key], rel=1e-12), key
    simplify = lambda items: [(i["marker"], i["first_frame"], i["last_frame"], i["what"]) for i in items]
    assert simplify(report["filled"]) == simplify(expected["filled"])
    assert simplify(report["detected"]) == simplify(expected["detected"])
    assert markers.positions.shape[1] == len(markers.labels)


def test_repair_options_and_errors(cmu02):
    subject = mocapsolve.read_subject(cmu02["subject"])
    code, output = run_cli("repair", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"],
                           "--out_markers=/tmp/never.c3d", "--reference=magic", expect=1)
    with pytest.raises(ValueError) as error:
        mocapsolve.repair(subject, cmu02["c3d"], reference="magic")
    # The same one line, naming the command and the option.
    assert str(error.value) == output.strip()
    with pytest.raises(TypeError, match="dp_max"):
        mocapsolve.repair(subject, cmu02["c3d"], dp_max=3)
    s = mocapsolve.RepairSettings()
    assert s.dp_max_cm == 10.0 and s.reference == "tracker" and s.small_gap == 5


def test_evaluate_matches_the_cli_table(cmu02, tmp_path):
    # evaluate() returns what `mocapsolve evaluate --report` writes (one task under both).
    subject = mocapsolve.read_subject(cmu02["subject"])
    report = mocapsolve.evaluate(subject, cmu02["c3d"], trials=1, gaps=4)
    csv = str(tmp_path / "table.csv")
    cli_report = str(tmp_path / "cli.json")
    run_cli("evaluate", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"], "--trials=1", "--gaps=4",
            "--table_csv=" + csv, "--report=" + cli_report)
    rows = report["per_trial"]
    lines = open(csv).read().splitlines()
    header = lines[0].split(",")
    assert len(lines) - 1 == len(rows)
    for line, row in zip(lines[1:], rows):
        values = dict(zip(header, line.split(",")))
        assert values["method"] == row["method"]
        for key in ("joint_position_cm", "marker_rms_mm", "velocity_jump_mm_per_frame"):
            assert float(values[key]) == float("%.6g" % row[key]), (row["method"], key)
    expected = json.load(open(cli_report))
    for key in ("methods", "position_error_ratio_to_ours", "first_seed", "trials", "frames"):
        assert key in report and key in expected, key
    ours = lambda r: [m for m in r["methods"] if m["method"] == "ours"][0]
    assert ours(report)["joint_position_cm"] == pytest.approx(ours(expected)["joint_position_cm"], rel=1e-12)


def test_evaluate_has_every_method_of_the_cli(cmu02, tmp_path):
    subject = mocapsolve.read_subject(cmu02["subject"])
    loo = mocapsolve.evaluate(subject, cmu02["c3d"], method="leave_one_out", num_threads=2)
    cli_report = str(tmp_path / "loo.json")
    run_cli("evaluate", "--method=leave_one_out", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"],
            "--report=" + cli_report)
    expected = json.load(open(cli_report))
    assert loo["unit"] == "mm" and len(loo["per_marker"]) == len(subject.marker_labels)
    assert loo["all"]["median"] == pytest.approx(expected["all"]["median"], rel=1e-9)
    with pytest.raises(ValueError, match=r"--method: unknown .* \(repair, leave_one_out, small_errors, retarget\)"):
        mocapsolve.evaluate(subject, cmu02["c3d"], method="magic")
    with pytest.raises(ValueError, match="--trials"):
        mocapsolve.evaluate(subject, cmu02["c3d"], trials=0)


def test_corrupt_damages_markers():
    markers = mocapsolve.read_markers(data_file("c3d/02_01.c3d"))
    damaged, kinds = mocapsolve.corrupt(markers, gaps=5, seed=7)
    assert kinds.shape == markers.positions.shape[:2] and (kinds != 0).any()
    assert np.isnan(damaged.positions).sum() > np.isnan(markers.positions).sum()
    with pytest.raises(ValueError, match="--gap_min/--gap_max"):
        mocapsolve.corrupt(markers, gap_min=20, gap_max=10)


def test_repair_pulls_toward_the_subjects_mean_pose_as_the_cli(cmu02, tmp_path):
    # calibrate --out_subject stores each joint's mean pose; with a rest prior, the repair's
    # solves pull toward it in Python as on the command line.
    subject = mocapsolve.read_subject(cmu02["subject"])
    mean = subject.mean_pose
    assert mean.shape == (subject.skeleton.num_joints, 4)
    assert np.allclose(np.linalg.norm(mean, axis=1), 1.0)
    assert np.abs(mean[:, :3]).max() > 0.1  # Not the rest pose.
    bare = mocapsolve.subject(cmu02["asf"], cmu02["markerset"], axes="y,z,x")
    assert bare.mean_pose is None
    _, motion, _ = mocapsolve.repair(subject, cmu02["c3d"], rest_prior_weight=10)
    cli_motion = str(tmp_path / "cli.bvh")
    run_cli("repair", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"], "--rest_prior_weight=10",
            "--out_markers=" + str(tmp_path / "cli.c3d"), "--out_motion=" + cli_motion)
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, subject.skeleton, motion)
    assert open(ours).read() == open(cli_motion).read()


def test_repair_takes_the_markers_corrupt_returns(cmu02, tmp_path):
    # corrupt() returns Markers; repair() and solve() take them as they take a path, and the
    # result is the same as repairing the damaged copy written to a file and read back.
    subject = mocapsolve.read_subject(cmu02["subject"])
    damaged, _ = mocapsolve.corrupt(mocapsolve.read_markers(cmu02["c3d"]), gaps=3, seed=5)
    path = str(tmp_path / "damaged.c3d")
    mocapsolve.write_markers(path, damaged)
    from_memory = mocapsolve.repair(subject, mocapsolve.read_markers(path))
    from_file = mocapsolve.repair(subject, path)
    assert np.array_equal(from_memory[1].rotations, from_file[1].rotations)
    assert np.array_equal(from_memory[0].positions, from_file[0].positions, equal_nan=True)
    motion, _ = mocapsolve.solve(subject, damaged, solver="dls", max_frames=5)
    assert motion.num_frames == 5
    with pytest.raises(TypeError, match="expected a Take, Markers or a .c3d/.trc path"):
        mocapsolve.repair(subject, 42)


def test_label_matches_the_cli(tmp_path):
    """label() names a take's points as `mocapsolve label` does: the same file, the same
    report (timings aside), from a path or from the Markers read_markers() returns."""
    demo, markers, subject = (str(tmp_path / n) for n in ("walk.bvh", "walk.c3d", "S.json"))
    run_cli("generate", "--demo_out=" + demo, "--frames=40", "--fps=30")
    run_cli("markers", "--motion=" + demo, "--skeleton_units=cm", "--markerset=auto:3", "--noise_mm=0.5",
            "--out=" + markers)
    run_cli("calibrate", "--motion=" + demo, "--skeleton_units=cm", "--markers=" + markers, "--attach=auto",
            "--out_subject=" + subject)
    cli_out, cli_report = str(tmp_path / "cli.c3d"), str(tmp_path / "cli.json")
    run_cli("label", "--subject=" + subject, "--markers=" + markers, "--out=" + cli_out, "--report=" + cli_report)
    labelled, report = mocapsolve.label(mocapsolve.read_subject(subject), markers)
    ours = str(tmp_path / "py.c3d")
    mocapsolve.write_markers(ours, labelled)
    assert open(ours, "rb").read() == open(cli_out, "rb").read()
    expected = json.load(open(cli_report))
    for key, value in report.items():
        if key not in ("seconds", "frames_per_second"):
            assert expected[key] == value, key
    again, _ = mocapsolve.label(mocapsolve.read_subject(subject), mocapsolve.read_markers(markers))
    assert np.array_equal(np.nan_to_num(again.positions), np.nan_to_num(labelled.positions))
    with pytest.raises(TypeError, match="unexpected keyword"):
        mocapsolve.label(mocapsolve.read_subject(subject), markers, no_such_option=1)
