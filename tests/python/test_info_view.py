"""info() and view() are `mocapsolve info` and `mocapsolve view` (one task under both front
ends, tasks/info_task.h and tasks/view_task.h): the same report, the same page bytes."""
import json
import os

import pytest

import mocapsolve
from conftest import REPO, data_file, run_cli

GOOD = os.path.join(REPO, "tests", "data", "good")
# What the CLI's --report adds around every command's own figures.
ENVELOPE = {"status", "version", "command", "options", "inputs"}


def cli_report(tmp_path, *arguments):
    report = str(tmp_path / "cli.json")
    run_cli("info", *arguments, "--report=" + report)
    return {key: value for key, value in json.load(open(report)).items() if key not in ENVELOPE}


@pytest.mark.filterwarnings("ignore:.*no normals")
@pytest.mark.parametrize("name, keywords", [
    ("small.bvh", {}), ("small.bvh", {"skeleton_units": "cm"}), ("small.asf", {}), ("small.c3d", {}),
    ("small.trc", {}), ("skinned.gltf", {}), ("small.fbx", {}),
    ("small.amc", {"skeleton": os.path.join(GOOD, "small.asf"), "amc_fps": 60.0}),
])
def test_info_is_the_cli_report(tmp_path, name, keywords):
    path = os.path.join(GOOD, name)
    flags = ["--%s=%s" % (key, value) for key, value in keywords.items()]
    assert mocapsolve.info(path, **keywords) == cli_report(tmp_path, path, *flags)


def test_info_of_characters_and_their_warnings(tmp_path):
    glb = os.path.join(GOOD, "skinned.glb")
    with pytest.warns(UserWarning, match="no normals"):
        report = mocapsolve.info(glb)
    assert report == cli_report(tmp_path, glb)
    assert report["skins"] == 1 and report["joint_levels"][0] == [report["root"]]
    fox = data_file("gltf/Fox.glb")
    with pytest.warns(UserWarning):
        report = mocapsolve.info(fox, animation="Walk", sample_fps=10)
    assert report == cli_report(tmp_path, fox, "--animation=Walk", "--sample_fps=10")
    assert report["animations"] == ["Survey", "Walk", "Run"] and report["frame_rate"] == 10


def test_info_errors_are_the_clis():
    with pytest.raises(OSError, match="missing.bvh"):
        mocapsolve.info(os.path.join(GOOD, "missing.bvh"))
    with pytest.raises(ValueError, match=r"^mocapsolve info: .*small.amc: an AMC needs its skeleton"):
        mocapsolve.info(os.path.join(GOOD, "small.amc"))
    with pytest.raises(ValueError, match="--skeleton_units='furlong'"):
        mocapsolve.info(os.path.join(GOOD, "small.bvh"), skeleton_units="furlong")


def viewer_installed():
    tools = os.environ.get("MOCAPSOLVE_VIEWER_TOOLS", "")
    return bool(tools) and os.path.exists(os.path.join(tools, "three.bundle.js"))


def same_page(tmp_path, name, cli_flags, **keywords):
    """view(**keywords) and `mocapsolve view cli_flags` write the same bytes; the summary."""
    ours, theirs = str(tmp_path / (name + "_py.html")), str(tmp_path / (name + "_cli.html"))
    summary = mocapsolve.view(ours, **keywords)
    run_cli("view", *cli_flags, "--out=" + theirs)
    assert open(ours, "rb").read() == open(theirs, "rb").read(), name
    return summary


@pytest.mark.skipif(not viewer_installed(), reason="viewer runtime not installed (scripts/viewer_tools.sh)")
def test_view_writes_the_cli_page(tmp_path):
    c3d, bvh, glb = (os.path.join(GOOD, n) for n in ("small.c3d", "small.bvh", "skinned.glb"))
    subject_path = os.path.join(GOOD, "subject.json")
    subject = mocapsolve.read_subject(subject_path)
    # Each file in its own world, with a title and an up axis.
    summary = same_page(tmp_path, "own", ["--markers=" + c3d, "--motion=" + bvh, "--up=y", "--title=Small"],
                        markers=c3d, motion=bvh, up="y", title="Small")
    assert (summary["frames"], summary["marker_sets"], summary["skeletons"]) == (3, 1, 1)
    assert summary["title"] == "Small" and summary["marker_rms_mm"] is None
    # The markers mapped onto the subject, with the motion's residual, compared with themselves.
    summary = same_page(tmp_path, "subject", ["--subject=" + subject_path, "--markers=" + c3d, "--motion=" + bvh,
                                              "--compare=" + c3d],
                        subject=subject, markers=c3d, motion=bvh, compare=c3d)
    assert summary["marker_sets"] == 2 and summary["marker_rms_mm"] > 0
    # A character alone.
    summary = same_page(tmp_path, "character", ["--character=" + glb], characters=[glb])
    assert summary["characters"] == 1 and summary["title"] == "skinned"


@pytest.mark.skipif(not viewer_installed(), reason="viewer runtime not installed (scripts/viewer_tools.sh)")
def test_view_errors_are_the_clis(tmp_path):
    page = str(tmp_path / "p.html")
    with pytest.raises(ValueError, match="^mocapsolve view: nothing to show: give --markers"):
        mocapsolve.view(page)
    with pytest.raises(ValueError, match="expected an .html page"):
        mocapsolve.view(str(tmp_path / "p.txt"), motion=os.path.join(GOOD, "small.bvh"))
    with pytest.raises(ValueError, match="--up=w: expected auto, x, y or z"):
        mocapsolve.view(page, motion=os.path.join(GOOD, "small.bvh"), up="w")
    with pytest.raises(OSError, match="missing.c3d"):
        mocapsolve.view(page, markers=str(tmp_path / "missing.c3d"))
    assert not os.path.exists(page)
