"""Falloffs and edit propagation against the command line."""
import json
import os

import numpy as np
import pytest

import mocapsolve
from conftest import REPO, data_file, run_cli

EDIT = os.path.join(REPO, "examples", "edit_16_15_arm_up.json")


def test_green_falloff_matches_the_cli_distance(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh)
    falloff = mocapsolve.falloff(skeleton, motion, 200, "green", region="10:471")
    assert falloff["weight"].shape == (motion.num_frames,)
    assert falloff["weight"][200] == pytest.approx(1.0)
    csv = str(tmp_path / "falloff.csv")
    run_cli("distance", "--motion=" + bvh, "--frame=200", "--method=green", "--region=10:471", "--out=" + csv)
    rows = np.genfromtxt(csv, delimiter=",", names=True)
    assert np.allclose(rows["weight"], falloff["weight"], atol=1e-6)


def test_propagated_edit_matches_the_cli(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh, skeleton_units="cm")
    edits = mocapsolve.read_edits(EDIT, skeleton, motion)
    assert [e.frame for e in edits] == [200]
    weights = mocapsolve.falloff(skeleton, motion, 200, "green")["weight"]
    edited = mocapsolve.propagate(skeleton, motion, edits, [weights])
    cli = str(tmp_path / "cli.bvh")
    run_cli("propagate", "--motion=" + bvh, "--skeleton_units=cm", "--edit=" + EDIT, "--method=green",
            "--out=" + cli)
    _, expected = mocapsolve.read_motion(cli)
    a = mocapsolve.forward_kinematics(skeleton, edited)
    b = mocapsolve.forward_kinematics(skeleton, expected)
    assert np.abs(a - b).max() < 1e-3  # cm; the BVH holds 6 digits.


def test_falloff_errors():
    skeleton, motion = mocapsolve.read_motion(data_file("bvh/16_15.bvh"))
    with pytest.raises(ValueError, match="--region"):
        mocapsolve.falloff(skeleton, motion, 200, region="400:10")
    with pytest.raises(ValueError, match="--falloff_kernel"):
        mocapsolve.falloff(skeleton, motion, 200, falloff_kernel="huge")
    with pytest.raises(TypeError, match="sigmas"):
        mocapsolve.falloff(skeleton, motion, 200, sigmas=1.0)


@pytest.mark.parametrize("method", ["harmonic", "green", "spline"])
def test_ik_edit_and_weights_are_bit_identical_to_the_cli(tmp_path, method):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh, skeleton_units="cm")
    edit, ik = mocapsolve.ik_edit(skeleton, motion, 200, "lhand:32,105,50", solver="dls")
    assert edit.frame == 200 and ik["ik_max_target_error"] < 5.0  # cm; 1.8 (the hand's reach).
    weights, falloff = mocapsolve.edit_weights(skeleton, motion, [edit], method, region="20:471")
    assert len(weights) == 1 and weights[0].shape == (motion.num_frames,)
    assert weights[0][200] == pytest.approx(1.0) and weights[0][:20].max() == 0.0
    edited = mocapsolve.propagate(skeleton, motion, [edit], weights)
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, skeleton, edited)
    cli, csv, report = (str(tmp_path / n) for n in ("cli.bvh", "w.csv", "r.json"))
    run_cli("propagate", "--motion=" + bvh, "--skeleton_units=cm", "--frame=200", "--ik_target=lhand:32,105,50",
            "--solver=dls", "--method=" + method, "--region=20:471", "--out=" + cli, "--weights_csv=" + csv,
            "--report=" + report)
    assert open(ours, "rb").read() == open(cli, "rb").read()
    rows = np.genfromtxt(csv, delimiter=",", names=True)
    assert np.allclose(rows["weight"], weights[0], rtol=1e-8, atol=1e-12)  # The CSV holds 9 digits.
    expected = json.load(open(report))
    assert falloff.keys() == expected["falloff"].keys()
    assert expected["edit"]["ik_iterations"] == ik["ik_iterations"]
    assert expected["edit"]["ik_max_target_error"] == ik["ik_max_target_error"]


def test_ik_and_weight_errors_carry_the_cli_message(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh, skeleton_units="cm")
    edit, _ = mocapsolve.ik_edit(skeleton, motion, 200, "lhand:32,105,50", solver="dls", max_iterations=1)
    cases = [
        (lambda: mocapsolve.ik_edit(skeleton, motion, 200, "lhand:32,105"), ["--ik_target=lhand:32,105"]),
        (lambda: mocapsolve.ik_edit(skeleton, motion, 200, "nohand:1,2,3"), ["--ik_target=nohand:1,2,3"]),
        (lambda: mocapsolve.ik_edit(skeleton, motion, 200, "lhand:1,2,3", ik_root_weight=-1),
         ["--ik_target=lhand:1,2,3", "--ik_root_weight=-1"]),
        (lambda: mocapsolve.edit_weights(skeleton, motion, [edit], "spline", spline_width=0),
         ["--ik_target=lhand:1,2,3", "--method=spline", "--spline_width=0"]),
        (lambda: mocapsolve.edit_weights(skeleton, motion, [edit], "harmonic", sparse_library="mkl"),
         ["--ik_target=lhand:1,2,3", "--method=harmonic", "--sparse_library=mkl"]),
        (lambda: mocapsolve.edit_weights(skeleton, motion, [edit], "cubic"),
         ["--ik_target=lhand:1,2,3", "--method=cubic"]),
        (lambda: mocapsolve.edit_weights(skeleton, motion, [edit], region="300:400"),
         ["--ik_target=lhand:1,2,3", "--region=300:400"]),
    ]
    for call, flags in cases:
        with pytest.raises(ValueError) as error:
            call()
        _, output = run_cli("propagate", "--motion=" + bvh, "--skeleton_units=cm", "--frame=200",
                            "--out=" + str(tmp_path / "o.bvh"), *flags, expect=1)
        assert "mocapsolve propagate: " + str(error.value) in output, flags


def test_propagate_command_with_keep_contacts_matches_the_cli(tmp_path):
    # propagate(skeleton, motion, ik_target=..., keep_contacts=True) is `mocapsolve propagate`:
    # one task under both, so the motion is the CLI's bit for bit and the report its --report.
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh, skeleton_units="cm")
    edited, report = mocapsolve.propagate(skeleton, motion, ik_target="lhand:32,105,50", frame=200,
                                          keep_contacts=True, max_iterations=20)
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, skeleton, edited)
    cli, cli_report = str(tmp_path / "cli.bvh"), str(tmp_path / "cli.json")
    run_cli("propagate", "--motion=" + bvh, "--skeleton_units=cm", "--ik_target=lhand:32,105,50", "--frame=200",
            "--keep_contacts", "--max_iterations=20", "--out=" + cli, "--report=" + cli_report)
    assert open(ours).read() == open(cli).read()
    expected = json.load(open(cli_report))
    contacts = report["contacts"]
    assert contacts["max_drift_cm_with_keep"] < contacts["max_drift_cm_without_keep"]
    for key in ("max_drift_cm_without_keep", "max_drift_cm_with_keep", "contact_frames"):
        assert contacts[key] == expected["contacts"][key], key
    assert report["edit"]["ik_iterations"] == expected["edit"]["ik_iterations"]
    assert len(report["weights"]) == 1 and report["weights"][0].shape == (motion.num_frames,)
    with pytest.raises(ValueError, match="give exactly one of --edit"):
        mocapsolve.propagate(skeleton, motion)
    with pytest.raises(ValueError, match="--contact_prior_cm: expected a value >= 0"):
        mocapsolve.propagate(skeleton, motion, ik_target="lhand:32,105,50", frame=200, contact_prior_cm=-1)


def test_distance_is_the_cli_command(tmp_path):
    # distance() is `mocapsolve distance` (one task): the same curves and report.
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh, skeleton_units="cm")
    report = mocapsolve.distance(skeleton, motion, 200, "green,isomap", sweep="0.5")
    csv, cli_report = str(tmp_path / "d.csv"), str(tmp_path / "d.json")
    run_cli("distance", "--motion=" + bvh, "--skeleton_units=cm", "--frame=200", "--method=green,isomap",
            "--sweep=0.5", "--out=" + csv, "--report=" + cli_report)
    rows = np.genfromtxt(csv, delimiter=",", names=True)
    assert np.allclose(rows["weight"], report["weights"]["green"], rtol=1e-8, atol=1e-12)
    assert np.allclose(rows["weight_sigma_05"], report["sweep_weights"][0], rtol=1e-8, atol=1e-12)
    expected = json.load(open(cli_report))
    assert report["period_frames"] == expected["period_frames"]
    assert [m["end_after_0.05"] for m in report["methods"]] == [m["end_after_0.05"] for m in expected["methods"]]
    with pytest.raises(ValueError, match="mocapsolve distance: --method: expected green, diffusion or isomap"):
        mocapsolve.distance(skeleton, motion, 200, "cubic")
