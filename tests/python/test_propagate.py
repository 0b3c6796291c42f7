"""Falloffs and edit propagation against the command line."""
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
