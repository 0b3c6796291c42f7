"""Kinematics bindings: Jacobians against central differences on the manifold, skinning,
poses, and calibration against the command line."""
import os

import numpy as np
import pytest

import mocapsolve
from conftest import data_file, run_cli


def numeric_jacobian(function, pose, size, step=1e-6):
    """Central differences of function(pose) along the pose's tangent (retract_pose)."""
    columns = []
    for k in range(size):
        d = np.zeros(size)
        d[k] = step
        plus = function(mocapsolve.retract_pose(pose, d))
        minus = function(mocapsolve.retract_pose(pose, -d))
        columns.append((plus - minus) / (2 * step))
    return np.stack(columns, axis=1)


def test_joint_position_jacobian_matches_differences():
    skeleton, motion = mocapsolve.read_motion(data_file("bvh/01_01.bvh"))
    pose = motion.pose(40)
    joint = skeleton.find_joint("LeftHand") if skeleton.find_joint("LeftHand") >= 0 else skeleton.num_joints - 1

    def position(p):
        clip = mocapsolve.Motion(skeleton, p.rotations[None], p.translations[None], 30.0)
        return mocapsolve.forward_kinematics(skeleton, clip)[0, joint]

    analytic = mocapsolve.joint_position_jacobian(skeleton, pose, joint)
    assert analytic.shape == (3, 3 + 3 * skeleton.num_joints)
    numeric = numeric_jacobian(position, pose, analytic.shape[1])
    # Central differences with step 1e-6 on positions of ~100 units: ~1e-6 relative.
    assert np.allclose(analytic, numeric, atol=1e-4 * max(1.0, np.abs(analytic).max()))


def test_skinning_and_skinned_jacobians():
    character = mocapsolve.read_character(data_file("gltf/CesiumMan.glb"))
    skeleton, motion = mocapsolve.read_motion(data_file("gltf/CesiumMan.glb"))
    assert skeleton.joint_names == character.skeleton.joint_names
    positions, normals = mocapsolve.skin(character, motion)
    assert positions.shape == (motion.num_frames, character.num_vertices, 3)
    assert normals.shape == positions.shape and positions.flags.c_contiguous
    pose = motion.pose(5)
    vertex = character.num_vertices // 2
    jp, jn = mocapsolve.skinned_vertex_jacobians(character, pose, vertex)

    def skinned(p, which):
        clip = mocapsolve.Motion(character.skeleton, p.rotations[None], p.translations[None], 30.0)
        return mocapsolve.skin(character, clip)[which][0, vertex]

    size = jp.shape[1]
    assert np.allclose(jp, numeric_jacobian(lambda p: skinned(p, 0), pose, size), atol=1e-6)
    assert np.allclose(jn, numeric_jacobian(lambda p: skinned(p, 1), pose, size), atol=1e-6)


def test_texcoords_where_the_file_has_them():
    """TEXCOORD_0 of every primitive, one (u, v) per vertex; none where the file has none
    (RobotExpressive), or a rigid part lacks them."""
    cesium = mocapsolve.read_character(data_file("gltf/CesiumMan.glb"))
    assert cesium.texcoords.shape == (cesium.num_vertices, 2)
    assert np.isfinite(cesium.texcoords).all() and np.ptp(cesium.texcoords[:, 0]) > 0.5
    robot = mocapsolve.read_character(data_file("gltf/RobotExpressive.glb"))
    assert robot.texcoords.shape == (0, 2)


def test_calibrate_writes_the_cli_subject(cmu02, tmp_path):
    subject, report = mocapsolve.calibrate(cmu02["amc"], cmu02["c3d"], skeleton=cmu02["asf"], axes="y,z,x")
    assert report["axes"] == "y,z,x" and report["rms_mm"] < 20
    os.makedirs(tmp_path / "py")
    os.makedirs(tmp_path / "cli")
    ours = str(tmp_path / "py" / "S.json")
    mocapsolve.write_subject(ours, subject)
    cli = str(tmp_path / "cli" / "S.json")
    run_cli("calibrate", "--motion=" + cmu02["amc"], "--skeleton=" + cmu02["asf"], "--markers=" + cmu02["c3d"],
            "--axes=y,z,x", "--out=" + str(tmp_path / "cli" / "set.json"), "--out_subject=" + cli)
    assert open(ours).read() == open(cli).read()
    assert mocapsolve.read_subject(ours).marker_labels == subject.marker_labels


def test_subject_from_files_equals_subject_file(cmu02):
    a = mocapsolve.subject(cmu02["asf"], cmu02["markerset"], axes="y,z,x")
    b = mocapsolve.read_subject(cmu02["subject"])
    assert a.marker_labels == b.marker_labels and a.axes == b.axes
    bad = mocapsolve.subject(cmu02["asf"], cmu02["markerset"], axes="y,y,x")
    code, output = run_cli("solve", "--skeleton=" + cmu02["asf"], "--markerset=" + cmu02["markerset"],
                           "--axes=y,y,x", "--markers=" + cmu02["c3d"], "--out=/tmp/never.bvh", expect=1)
    with pytest.raises(ValueError) as error:
        mocapsolve.load_take(bad, cmu02["c3d"])
    assert str(error.value) in output
