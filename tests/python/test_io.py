"""io bindings: markers and motions read and written, against the command line."""
import math
import os

import numpy as np
import pytest

import mocapsolve
from conftest import data_file, run_cli


def test_read_markers_shapes_and_missing_samples():
    markers = mocapsolve.read_markers(data_file("c3d/02_01.c3d"))
    p = markers.positions
    assert p.dtype == np.float64 and p.ndim == 3 and p.shape[2] == 3
    assert p.shape == (markers.num_frames, len(markers.labels), 3)
    assert p.flags.c_contiguous
    assert markers.rate == pytest.approx(120.0)
    assert markers.units == "mm"
    valid = markers.valid
    assert valid.shape == p.shape[:2] and valid.dtype == bool
    # Missing samples are NaN in all three coordinates, present ones finite.
    assert np.array_equal(np.isnan(p).all(axis=2), ~valid)
    assert np.isfinite(p[valid]).all()


def test_positions_is_a_view_without_copy():
    markers = mocapsolve.read_markers(data_file("c3d/02_01.c3d"))
    a = markers.positions
    b = markers.positions
    assert np.shares_memory(a, b)
    a[0, 0, :] = np.nan  # Setting NaN makes the sample missing.
    assert not markers.valid[0, 0]


def test_nan_round_trip_of_missing_markers(tmp_path):
    markers = mocapsolve.read_markers(data_file("c3d/02_01.c3d"))
    positions = markers.positions.copy()
    positions[5:9, 3, :] = np.nan
    made = mocapsolve.Markers(positions, markers.labels, markers.rate, "mm")
    for ext in (".c3d", ".trc"):
        path = str(tmp_path / ("round" + ext))
        mocapsolve.write_markers(path, made)
        back = mocapsolve.read_markers(path)
        assert back.labels == markers.labels
        assert np.array_equal(np.isnan(back.positions), np.isnan(positions))
        ok = ~np.isnan(positions)
        assert np.allclose(back.positions[ok], positions[ok], atol=1e-3)


def test_read_motion_amc_and_fk_match_the_cli(tmp_path):
    asf, amc = data_file("amc/02.asf"), data_file("amc/02_01.amc")
    skeleton, motion = mocapsolve.read_motion(amc, skeleton=asf)
    assert len(skeleton.joint_names) == skeleton.num_joints
    r = motion.rotations
    assert r.shape == (motion.num_frames, skeleton.num_joints, 4) and r.dtype == np.float64
    assert np.allclose(np.linalg.norm(r, axis=2), 1.0)
    assert motion.root_translations.shape == (motion.num_frames, 3)
    positions = mocapsolve.forward_kinematics(skeleton, motion)
    assert positions.shape == (motion.num_frames, skeleton.num_joints, 3)
    assert positions.flags.c_contiguous
    csv = str(tmp_path / "fk.csv")
    run_cli("fk", "--motion=" + amc, "--skeleton=" + asf, "--out=" + csv)
    lines = open(csv).read().splitlines()[1:]
    assert len(lines) == positions.shape[0] * positions.shape[1]
    names = skeleton.joint_names
    for i in range(0, len(lines), 97):  # A sample of the rows; same code path: same digits.
        f, j = divmod(i, skeleton.num_joints)
        p = positions[f, j]
        assert lines[i] == "%d,%s,%.9g,%.9g,%.9g" % (f, names[j], p[0], p[1], p[2])


def test_motion_round_trip_through_bvh(tmp_path):
    skeleton, motion = mocapsolve.read_motion(data_file("bvh/01_01.bvh"))
    path = str(tmp_path / "out.bvh")
    mocapsolve.write_motion(path, skeleton, motion, precision=9)
    skeleton2, motion2 = mocapsolve.read_motion(path)
    assert skeleton2.joint_names == skeleton.joint_names
    a = mocapsolve.forward_kinematics(skeleton, motion)
    b = mocapsolve.forward_kinematics(skeleton2, motion2)
    assert np.allclose(a, b, atol=1e-5)
    # The CLI's convert writes the same file.
    cli = str(tmp_path / "cli.bvh")
    run_cli("convert", data_file("bvh/01_01.bvh"), cli, "--precision=9")
    assert open(cli).read() == open(path).read()


def test_motion_from_arrays_and_setters():
    skeleton, motion = mocapsolve.read_motion(data_file("bvh/01_01.bvh"))
    made = mocapsolve.Motion(skeleton, motion.rotations, motion.translations, motion.rate)
    assert np.array_equal(mocapsolve.forward_kinematics(skeleton, made),
                          mocapsolve.forward_kinematics(skeleton, motion))
    root = motion.root_translations + np.array([1.0, 0.0, 0.0])
    motion.root_translations = root
    assert np.array_equal(motion.root_translations, root)
    with pytest.raises(ValueError, match="rotations: expected shape"):
        motion.rotations = np.zeros((3, 4))


def test_bad_input_raises():
    with pytest.raises(OSError, match="no_such_file.c3d"):
        mocapsolve.read_markers("no_such_file.c3d")
    with pytest.raises(OSError, match="missing.bvh"):
        mocapsolve.read_motion("missing.bvh")


def test_bad_file_raises_value_error_naming_it(tmp_path):
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFSET 0 0 0\n")
    with pytest.raises(ValueError, match="bad.bvh"):
        mocapsolve.read_motion(str(bad))
    code, output = run_cli("info", str(bad), expect=1)
    with pytest.raises(ValueError) as error:
        mocapsolve.read_motion(str(bad))
    assert str(error.value) in output


def test_gltf_animation_round_trip(tmp_path):
    glb = data_file("gltf/CesiumMan.glb")
    skeleton, motion = mocapsolve.read_motion(glb)
    out = str(tmp_path / "with_clip.glb")
    mocapsolve.write_gltf(out, glb, motion, "again")
    skeleton2, motion2 = mocapsolve.read_motion(out, animation="again")
    assert skeleton2.joint_names == skeleton.joint_names
    a = mocapsolve.forward_kinematics(skeleton, motion)
    b = mocapsolve.forward_kinematics(skeleton2, motion2)
    assert a.shape == b.shape and np.abs(a - b).max() < 1e-5  # Metres; floats in the file.


def _vendor_c3d(tmp_path, labels):
    """A small C3D with these labels (fuzz/c3d_min.py), point i at x = 1000 + i."""
    import sys
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "fuzz"))
    import c3d_min
    frames = [[(1000.0 + i, 0.0, 0.0) for i in range(len(labels))] for _ in range(3)]
    path = tmp_path / "vendor.c3d"
    path.write_bytes(c3d_min.c3d_bytes(labels, frames))
    return str(path)


def test_read_markers_picks_a_subject_and_numbers_duplicates(tmp_path):
    path = _vendor_c3d(tmp_path, ["Daphnee:LASI", "boite:M1", "Daphnee:RASI", "Daphnee:LASI"])
    # Two subjects and no choice: the one with the most points, a warning listing them.
    with pytest.warns(UserWarning, match="2 subjects .* reading 'Daphnee:'"):
        largest = mocapsolve.read_markers(path)
    assert list(largest.labels) == ["LASI", "RASI", "LASI#2"]
    with pytest.warns(UserWarning, match="LASI"):
        markers = mocapsolve.read_markers(path, subject_prefix="Daphnee")
    assert list(markers.labels) == ["LASI", "RASI", "LASI#2"]
    assert markers.positions[0, :, 0].tolist() == [1000.0, 1002.0, 1003.0]  # The file's points 0, 2, 3.
    with pytest.raises(ValueError, match="nobody"):
        mocapsolve.read_markers(path, subject_prefix="nobody")


def test_markers_matches_the_cli_and_its_subject_solves_back(tmp_path):
    # markers() is `mocapsolve markers` (one task): the same file, and a subject to solve with.
    walk = str(tmp_path / "walk.bvh")
    run_cli("generate", "--demo_out=" + walk, "--frames=30", "--fps=30")
    skeleton, motion = mocapsolve.read_motion(walk, skeleton_units="cm")
    markers, subject, report = mocapsolve.markers(skeleton, motion, "auto:3", noise_mm=0.5, seed=4)
    ours = str(tmp_path / "py.c3d")
    mocapsolve.write_markers(ours, markers)
    cli = str(tmp_path / "cli.c3d")
    run_cli("markers", "--motion=" + walk, "--skeleton_units=cm", "--markerset=auto:3", "--noise_mm=0.5",
            "--seed=4", "--out=" + cli)
    assert open(ours, "rb").read() == open(cli, "rb").read()
    assert report["markers"] == len(subject.marker_labels) and report["noise_mm"] == 0.5
    solved, summary = mocapsolve.solve(subject, markers)
    assert summary["per_frame"]["rms_marker_residual"] < 2.0  # mm: the noise, not the model.
    with pytest.raises(ValueError, match="mocapsolve markers: --units: unknown 'furlong'"):
        mocapsolve.markers(skeleton, motion, units="furlong")


def _joint_positions(skeleton, motion):
    """{joint name: (frames, 3) world positions}."""
    positions = mocapsolve.forward_kinematics(skeleton, motion)
    return {name: positions[:, j, :] for j, name in enumerate(skeleton.joint_names)}


def test_write_fbx_is_convert_and_reads_back(tmp_path):
    """write_fbx(path, skeleton, motion) writes `convert IN OUT.fbx`'s bytes; assimp reads it
    back to the same joint positions."""
    demo = str(tmp_path / "walk.bvh")
    run_cli("generate", "--demo_out=" + demo, "--frames=30", "--fps=30")
    skeleton, motion = mocapsolve.read_motion(demo)
    ours = str(tmp_path / "py.fbx")
    mocapsolve.write_fbx(ours, skeleton, motion, clip_name="walk")
    cli = str(tmp_path / "cli.fbx")
    run_cli("convert", demo, cli, "--clip_name=walk")
    assert open(ours, "rb").read() == open(cli, "rb").read()
    back_skeleton, back = mocapsolve.read_motion(ours)
    assert back.num_frames == motion.num_frames and back.rate == pytest.approx(30.0)
    a, b = _joint_positions(skeleton, motion), _joint_positions(back_skeleton, back)
    shared = set(a) & set(b)
    assert len(shared) >= 15
    worst = max(np.abs(a[name] - b[name]).max() for name in shared)
    assert worst < 1e-3  # cm (a BVH without a unit is written as cm): 0.01 mm.
    mocapsolve.write_fbx(str(tmp_path / "zyx.fbx"), skeleton, motion, euler_order="ZYX")
    with pytest.raises(ValueError, match="euler_order: 'XYY'"):
        mocapsolve.write_fbx(str(tmp_path / "bad.fbx"), skeleton, motion, euler_order="XYY")
    with pytest.raises(ValueError, match="expected a .fbx output"):
        mocapsolve.write_fbx(str(tmp_path / "walk.glb"), skeleton, motion)
    assert not os.path.exists(str(tmp_path / "bad.fbx"))


def test_write_fbx_of_a_character(tmp_path):
    """write_fbx(path, target, motion): the glTF character with the clip (as `convert
    --target`, which first maps its input's motion onto the character); animation_only
    leaves the mesh out."""
    glb = data_file("gltf/Xbot.glb")
    skeleton, motion = mocapsolve.read_motion(glb)
    full, slim = str(tmp_path / "xbot.fbx"), str(tmp_path / "xbot_anim.fbx")
    mocapsolve.write_fbx(full, glb, motion, clip_name="clip")
    mocapsolve.write_fbx(slim, glb, motion, clip_name="clip", animation_only=True)
    assert os.path.getsize(slim) < os.path.getsize(full) / 2
    a = _joint_positions(skeleton, motion)
    for path in (full, slim):
        back_skeleton, back = mocapsolve.read_motion(path)
        b = _joint_positions(back_skeleton, back)
        shared = set(a) & set(b)
        assert len(shared) > 10
        assert max(np.abs(a[name] - b[name]).max() for name in shared) < 1e-5  # Metres: 0.01 mm.
