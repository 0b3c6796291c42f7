"""Retargeting and the pipeline on one take, against the command line."""
import json
import os

import numpy as np
import pytest

import mocapsolve
from conftest import data_file, run_cli


def test_retarget_matches_the_cli(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    glb = data_file("gltf/Xbot.glb")
    ours = str(tmp_path / "py.bvh")
    character, motion, report = mocapsolve.retarget(bvh, glb, max_frames=8, out=ours)
    assert motion.num_frames == 8 and report["source_kind"] == "skeleton"
    assert character.num_vertices > 0
    cli = str(tmp_path / "cli.bvh")
    cli_report = str(tmp_path / "cli.json")
    run_cli("retarget", "--source=" + bvh, "--target=" + glb, "--max_frames=8", "--out=" + cli,
            "--report=" + cli_report)
    assert open(ours).read() == open(cli).read()
    # One task under both: the report is the --report's, less the envelope and output flags.
    expected = json.load(open(cli_report))
    timing = {"setup_seconds", "solve_seconds", "ms_per_frame"}
    for key, value in report.items():
        if key not in timing:
            assert expected[key] == value, key
    assert report["joint_map"] and report["per_frame_position_error"]
    with pytest.raises(ValueError, match="--source_skin: applies to a skinned glTF source only"):
        mocapsolve.retarget(bvh, glb, max_frames=2, source_skin="0")


def test_joint_map_is_the_clis(tmp_path):
    """joint_map() returns what `mocapsolve joint_map` prints, and its joints are the ones
    retarget() reports using."""
    bvh = data_file("bvh/16_15.bvh")
    glb = data_file("gltf/Xbot.glb")
    ours = mocapsolve.joint_map(bvh, glb)
    out = str(tmp_path / "map.json")
    run_cli("joint_map", "--source=" + bvh, "--target=" + glb, "--out=" + out)
    assert ours == json.load(open(out))
    assert 0.0 < ours["confidence"] <= 1.0 and ours["roles"]["pelvis"]["target"]
    with pytest.raises(ValueError, match="NoSuchJoint"):
        bad = tmp_path / "bad.json"
        bad.write_text('{"joints": {"NoSuchJoint": "mixamorig:Hips"}}')
        mocapsolve.joint_map(bvh, glb, joint_map=str(bad))


def test_pipeline_on_one_take_matches_the_cli(cmu02, tmp_path):
    subject = mocapsolve.read_subject(cmu02["subject"])
    out_py = str(tmp_path / "py")
    result = mocapsolve.pipeline(subject, cmu02["c3d"], out_dir=out_py)
    assert result["passed"], result["failures"]
    out_cli = str(tmp_path / "cli")
    run_cli("pipeline", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"], "--out_dir=" + out_cli)
    for name in ("solved.bvh", "repaired.c3d"):
        assert open(os.path.join(out_py, name), "rb").read() == open(os.path.join(out_cli, name), "rb").read(), name
    expected = json.load(open(os.path.join(out_cli, "report.json")))
    assert result["report"]["quality_gate"] == expected["quality_gate"]
    # The take's page as the CLI's --view=auto: written beside the outputs when the viewer's
    # runtime is installed, else a warning; the report says which.
    assert result["report"]["view"] == expected["view"]
    if expected["view"]:
        assert os.path.exists(os.path.join(out_py, "view.html"))
    # The gate's thresholds are declared keywords (QualityGate), as the CLI's flags.
    strict = mocapsolve.pipeline(subject, cmu02["c3d"], gate_repaired_rms_mm=0.001)
    assert not strict["passed"] and "repaired marker RMS" in strict["failures"][0]
    assert mocapsolve.QualityGate().gate_repaired_rms_mm == 20.0
    with pytest.raises(TypeError, match="gate_rms"):
        mocapsolve.pipeline(subject, cmu02["c3d"], gate_rms=3)


def test_retarget_animation_only_matches_the_cli(tmp_path):
    """animation_only=True writes the CLI's --animation_only file, byte for byte: Xbot's
    skeleton, skin and the new animation, without its 5 MB of meshes."""
    bvh = data_file("bvh/16_15.bvh")
    glb = data_file("gltf/Xbot.glb")
    ours = str(tmp_path / "py.glb")
    mocapsolve.retarget(bvh, glb, max_frames=8, out=ours, animation_only=True)
    cli = str(tmp_path / "cli.glb")
    run_cli("retarget", "--source=" + bvh, "--target=" + glb, "--max_frames=8", "--out=" + cli, "--animation_only")
    data = open(ours, "rb").read()
    assert data == open(cli, "rb").read()
    assert data[:4] == b"glTF" and len(data) < os.path.getsize(glb) / 20
    with pytest.raises(ValueError, match="animation_only"):
        mocapsolve.retarget(bvh, glb, max_frames=8, out=str(tmp_path / "x.bvh"), animation_only=True)
    # The delivery keywords, as the CLI's --frames/--out_fps: the returned and written clip.
    cut_out, cut_cli = str(tmp_path / "cut_py.bvh"), str(tmp_path / "cut_cli.bvh")
    _, motion, report = mocapsolve.retarget(bvh, glb, max_frames=8, out=cut_out, frames="2:5", out_fps=60)
    run_cli("retarget", "--source=" + bvh, "--target=" + glb, "--max_frames=8", "--out=" + cut_cli, "--frames=2:5",
            "--out_fps=60")
    assert open(cut_out, "rb").read() == open(cut_cli, "rb").read()
    assert report["delivered_frames"] == motion.num_frames == 2 and motion.rate == 60  # 4 frames at 120 fps.
    with pytest.raises(TypeError, match="formats"):
        mocapsolve.retarget(bvh, glb, max_frames=8, formats="fbx")


def test_batch_runs_the_cli_batch_task(cmu02, tmp_path):
    # batch() is `mocapsolve batch` (one task): the same take folders, summary and keys, so a
    # CLI re-run over the Python batch's folder skips the take as unchanged.
    import shutil
    takes = tmp_path / "takes"
    takes.mkdir()
    shutil.copy(cmu02["c3d"], str(takes / "walk.c3d"))
    out = str(tmp_path / "out")
    result = mocapsolve.batch(markers_glob=str(takes / "*.c3d"), subject=cmu02["subject"], out_dir=out, jobs=1)
    assert result["kind"] == "ran" and result["done"] == 1 and result["failed"] == 0, result
    assert result["summary"]["takes"][0]["take"] == "walk"
    assert os.path.exists(os.path.join(out, "walk", "solved.bvh"))
    assert json.load(open(os.path.join(out, "summary.json")))["takes"][0]["status"] == "done"
    _, output = run_cli("batch", "--markers_glob=" + str(takes / "*.c3d"), "--subject=" + cmu02["subject"],
                        "--out_dir=" + out, "--jobs=1")
    assert "1 skipped as unchanged" in output, output
    merged = mocapsolve.batch(merge=True, out_dir=out)
    assert merged["kind"] == "merged" and merged["done"] == 1
    with pytest.raises(ValueError, match="give either --manifest or --markers_glob"):
        mocapsolve.batch(out_dir=out)


def test_pipeline_formats_match_the_cli(tmp_path):
    """formats= is the CLI's --formats (the same declaration): the same character files, byte
    for byte; a bad list raises the CLI's message."""
    glb = data_file("gltf/Xbot.glb")
    demo, markers = str(tmp_path / "walk.bvh"), str(tmp_path / "walk.c3d")
    subject_path = str(tmp_path / "S.json")
    run_cli("generate", "--demo_out=" + demo, "--frames=20", "--fps=30")
    run_cli("markers", "--motion=" + demo, "--skeleton_units=cm", "--markerset=auto:3", "--noise_mm=0.5",
            "--seed=3", "--out=" + markers)
    run_cli("calibrate", "--motion=" + demo, "--skeleton_units=cm", "--markers=" + markers, "--attach=auto",
            "--out=" + str(tmp_path / "calibrated.json"), "--out_subject=" + subject_path)
    subject = mocapsolve.read_subject(subject_path)
    out_py, out_cli = str(tmp_path / "py"), str(tmp_path / "cli")
    mocapsolve.pipeline(subject, markers, characters=[glb], out_dir=out_py, view="off", formats="fbx,bvh",
                        animation_only=True)
    run_cli("pipeline", "--subject=" + subject_path, "--markers=" + markers, "--character=" + glb,
            "--out_dir=" + out_cli, "--view=off", "--formats=fbx,bvh", "--animation_only")
    assert not os.path.exists(os.path.join(out_py, "Xbot.glb"))
    for name in ("Xbot.fbx", "Xbot.bvh"):
        assert open(os.path.join(out_py, name), "rb").read() == open(os.path.join(out_cli, name), "rb").read(), name
    assert mocapsolve.DeliverySettings().formats == "glb"
    assert "formats='glb'" in mocapsolve.pipeline.__doc__
    with pytest.raises(ValueError, match=r"--formats: unknown 'obj' \(glb, fbx, bvh\)"):
        mocapsolve.pipeline(subject, markers, out_dir=str(tmp_path / "bad"), formats="glb,obj")
    assert not os.path.exists(str(tmp_path / "bad"))
    # The delivery keywords cut and resample the characters' clip, as the CLI's flags.
    cut = mocapsolve.pipeline(subject, markers, characters=[glb], frames="4:", out_fps=15)
    assert cut["characters"]["Xbot"].num_frames == 8 and cut["characters"]["Xbot"].rate == 15  # 4..18 of 20.
    with pytest.raises(ValueError, match=r"--frames=4:30: the clip has 20 frames, 0:19"):
        mocapsolve.pipeline(subject, markers, characters=[glb], frames="4:30")
    with pytest.raises(ValueError, match="--seconds: expected A:B"):
        mocapsolve.pipeline(subject, markers, seconds="1")
    # memory_mb, as the CLI's --memory_mb: a take over the limit is refused before any work.
    with pytest.raises(ValueError, match=r"--memory_mb=1: the pipeline's per-frame stages on .* over the limit"):
        mocapsolve.pipeline(subject, markers, out_dir=str(tmp_path / "small"), memory_mb=1)
    assert not os.path.exists(str(tmp_path / "small"))
    assert mocapsolve.MemorySettings().memory_mb == 0
    # batch(formats=) reaches every take's worker, as the CLI's batch --formats.
    out_batch = str(tmp_path / "batch")
    result = mocapsolve.batch(markers_glob=markers, subject=subject_path, characters=[glb], out_dir=out_batch,
                              jobs=1, formats="bvh")
    assert result["done"] == 1, result
    assert open(os.path.join(out_batch, "walk", "Xbot.bvh"), "rb").read() == \
        open(os.path.join(out_cli, "Xbot.bvh"), "rb").read()
    assert not os.path.exists(os.path.join(out_batch, "walk", "Xbot.glb"))
    with pytest.raises(ValueError, match="--formats: unknown 'obj'"):
        mocapsolve.batch(markers_glob=markers, subject=subject_path, out_dir=out_batch, formats="obj")


def test_pipeline_label_matches_the_cli(tmp_path):
    """label= is the CLI's --label (the same declaration): with label='always' the take's points
    are labelled first, and the repaired markers and the labelling report equal the CLI's; a bad
    value raises the CLI's message."""
    demo, markers = str(tmp_path / "walk.bvh"), str(tmp_path / "walk.c3d")
    subject_path = str(tmp_path / "S.json")
    run_cli("generate", "--demo_out=" + demo, "--frames=30", "--fps=30")
    run_cli("markers", "--motion=" + demo, "--skeleton_units=cm", "--markerset=auto:3", "--noise_mm=0.5",
            "--seed=3", "--out=" + markers)
    run_cli("calibrate", "--motion=" + demo, "--skeleton_units=cm", "--markers=" + markers, "--attach=auto",
            "--out=" + str(tmp_path / "calibrated.json"), "--out_subject=" + subject_path)
    subject = mocapsolve.read_subject(subject_path)
    out_py, out_cli = str(tmp_path / "py"), str(tmp_path / "cli")
    result = mocapsolve.pipeline(subject, markers, out_dir=out_py, view="off", label="always")
    run_cli("pipeline", "--subject=" + subject_path, "--markers=" + markers, "--out_dir=" + out_cli, "--view=off",
            "--label=always")
    labelling = result["report"]["labelling"]
    assert labelling["reason"] == "always"
    assert labelling["samples_labelled"] > 0.95 * labelling["points"]
    with open(os.path.join(out_cli, "report.json")) as f:
        assert json.load(f)["labelling"]["samples_labelled"] == labelling["samples_labelled"]
    py_markers = open(os.path.join(out_py, "repaired.c3d"), "rb").read()
    assert py_markers == open(os.path.join(out_cli, "repaired.c3d"), "rb").read()
    assert mocapsolve.pipeline(subject, markers)["report"]["labelling"] is None  # auto: the labels match.
    with pytest.raises(ValueError, match=r"--label: unknown 'sometimes' \(auto, never, always\)"):
        mocapsolve.pipeline(subject, markers, label="sometimes")


def test_pipeline_auto_subject_matches_the_cli(tmp_path):
    """subject='auto' is the CLI's --subject=auto (one task, tasks/auto_subject_task.h): the
    subject fitted from the take (02_01's CMU labels, a short fit) is the CLI's byte for byte,
    written as out_dir/subject.json, with the report's subject_fit; a bad word raises."""
    c3d = data_file("c3d/02_01.c3d")
    short = dict(fit_max_frames=60, fit_iterations=3, attach_rounds=1, attach_iterations=2)
    out_py, out_cli = str(tmp_path / "py"), str(tmp_path / "cli")
    result = mocapsolve.pipeline("auto", c3d, out_dir=out_py, view="off", **short)
    run_cli("pipeline", "--subject=auto", "--markers=" + c3d, "--out_dir=" + out_cli, "--view=off",
            *["--%s=%s" % item for item in short.items()])
    fit = result["report"]["subject_fit"]
    # At most 60 frames spread over the take's 343: every 6th, 58 of them.
    assert fit["method"] == "labels" and fit["frames"] == 58 and fit["frame_stride"] == 6 and fit["checks"]["passed"]
    assert isinstance(result["subject"], mocapsolve.Subject)
    py_subject = open(os.path.join(out_py, "subject.json"), "rb").read()
    assert py_subject == open(os.path.join(out_cli, "subject.json"), "rb").read()
    with pytest.raises(ValueError, match="subject: a Subject"):
        mocapsolve.pipeline("S.json", c3d)
