"""Bad input to the module raises ValueError/TypeError with one line naming the argument:
the findings of an outside probe (heap corruption, out-of-bounds reads, NaN passed on,
unsafe sharing across threads), each checked over the kinds of input that caused it."""
import os
import threading

import numpy as np
import pytest

import mocapsolve as ms

GOOD = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data", "good")


@pytest.fixture(scope="module")
def subject():
    return ms.read_subject(os.path.join(GOOD, "subject.json"))


@pytest.fixture(scope="module")
def clip():
    return ms.read_motion(os.path.join(GOOD, "small.bvh"))


def one_line(excinfo, *words):
    message = str(excinfo.value)
    assert "\n" not in message, message
    for word in words:
        assert word in message, message


# reconstruct_signal: every band and the top must have the pyramid's sizes.
def test_reconstruct_signal_rejects_bands_of_the_wrong_size():
    signal = np.random.default_rng(0).normal(size=(100, 7))
    bands, gaussian = ms.laplacian_pyramid(signal, levels=3)
    top = gaussian[-1]
    np.testing.assert_allclose(ms.reconstruct_signal(bands, top, [1.0] * 4), signal, atol=1e-12)
    cases = {
        "top": (bands, np.zeros((25, 7))),              # Was upsampled to (100, 7) silently.
        "top ": (bands, np.zeros((13, 6))),             # Channels.
        "laplacian[1]": ([bands[0], np.zeros((49, 7)), bands[2]], top),  # Was heap corruption.
        "laplacian[0]": ([np.zeros((2, 7))] + bands[1:], top),
        "laplacian[2]": (bands[:2] + [np.full((25, 7), np.nan)], top),
        "laplacian": ([], top),
    }
    for word, (b, t) in cases.items():
        with pytest.raises(ValueError) as e:
            ms.reconstruct_signal(b, t, [1.0] * (len(b) + 1))
        one_line(e, word.strip())


# velocity_jumps and every function where a skeleton meets a motion: the joint counts.
def test_skeleton_and_motion_of_different_joint_counts_are_refused(clip, subject):
    skeleton, motion = clip
    other = ms.read_character(os.path.join(GOOD, "skinned.glb")).skeleton
    assert other.num_joints != skeleton.num_joints
    calls = {
        "velocity_jumps": lambda: ms.velocity_jumps(other, motion),
        "forward_kinematics": lambda: ms.forward_kinematics(other, motion),
        "joint_rotations_world": lambda: ms.joint_rotations_world(other, motion),
        "falloff": lambda: ms.falloff(other, motion, 0),
        "propagate": lambda: ms.propagate(other, motion, [], []),
        "ik_edit": lambda: ms.ik_edit(other, motion, 0, "x:0,0,0"),
        "edit_weights": lambda: ms.edit_weights(other, motion, []),
        "joint_position_jacobian": lambda: ms.joint_position_jacobian(other, motion.pose(0), 0),
    }
    for name, call in calls.items():
        with pytest.raises(ValueError) as e:
            call()
        one_line(e, "joint count")


def test_poses_and_tangents_must_be_finite(clip):
    skeleton, motion = clip
    pose = motion.pose(0)
    n = 3 + 3 * skeleton.num_joints
    assert np.isfinite(ms.retract_pose(pose, np.full(n, 0.01)).rotations).all()
    for bad in (np.nan, np.inf, -np.inf):
        tangent = np.zeros(n)
        tangent[5] = bad
        with pytest.raises(ValueError) as e:
            ms.retract_pose(pose, tangent)
        one_line(e, "tangent")
    rotations = np.tile([0.0, 0.0, 0.0, 1.0], (skeleton.num_joints, 1))
    for bad in (np.nan, 2.0):
        r = rotations.copy()
        r[1, 0] = bad
        with pytest.raises(ValueError) as e:
            ms.Pose(skeleton, r, np.zeros(3))
        one_line(e, "pose")
        with pytest.raises(ValueError) as e:
            pose.rotations = r
        one_line(e, "rotations")
    with pytest.raises(ValueError) as e:
        ms.Pose(skeleton, rotations, np.array([0.0, np.inf, 0.0]))
    one_line(e, "pose")
    translations = motion.root_translations
    translations[0, 0] = np.nan
    with pytest.raises(ValueError) as e:
        motion.root_translations = translations
    one_line(e, "root_translations")


@pytest.mark.parametrize("rate", [0.0, -30.0, float("nan"), float("inf")])
def test_frame_rates_must_be_positive_and_finite(rate, clip):
    positions = np.zeros((2, 1, 3))
    with pytest.raises(ValueError) as e:
        ms.Markers(positions, ["A"], rate)
    one_line(e, "rate", "is outside")
    markers = ms.Markers(positions, ["A"], 100.0)
    with pytest.raises(ValueError) as e:
        markers.rate = rate
    one_line(e, "rate")
    _, motion = clip
    with pytest.raises(ValueError) as e:
        motion.rate = rate
    one_line(e, "rate")


@pytest.mark.parametrize("value", [1e308, -1e308, 2e9])
@pytest.mark.parametrize("ext", [".c3d", ".trc"])
def test_write_markers_refuses_what_the_readers_refuse(value, ext, tmp_path):
    positions = np.zeros((2, 2, 3))
    markers = ms.Markers(positions, ["A", "B"], 100.0)
    markers.positions[1, 1, 2] = value  # Through the writable view.
    path = str(tmp_path / ("out" + ext))
    with pytest.raises(ValueError) as written:
        ms.write_markers(path, markers)
    one_line(written, "frame 1, marker 'B'", "is beyond +-1e+09")
    assert not os.path.exists(path)
    with pytest.raises(ValueError) as made:
        ms.Markers(markers.positions.copy(), ["A", "B"], 100.0)
    one_line(made, "positions", "is beyond +-1e+09")
    # The readers' own wording for the same value (the TRC reader names its column).
    markers.positions[1, 1, 2] = 1e8
    ms.write_markers(path, markers)
    with open(path, "rb") as f:
        data = f.read()
    if ext == ".trc":
        with open(path, "wb") as f:
            f.write(data.replace(b"1e+08", b"1e308", 1))
        with pytest.raises(ValueError) as read:
            ms.read_markers(path)
        one_line(read, "beyond +-1e9")


def test_a_take_without_frames_is_refused(subject, tmp_path):
    labels = subject.marker_labels
    empty = ms.Markers(np.zeros((0, len(labels), 3)), labels, 100.0)
    path = str(tmp_path / "empty.trc")
    try:
        ms.write_markers(path, empty)
    except ValueError:
        pytest.skip("the writers refuse an empty take")
    for call in (ms.repair, ms.evaluate):
        with pytest.raises(ValueError) as e:
            call(subject, path)
        one_line(e)


def test_one_frame_solver_shared_by_threads_gives_the_serial_results(subject):
    take = ms.load_take(subject, os.path.join(GOOD, "small.c3d"))
    observed = take.observed
    assert len(observed) >= 2
    solver = ms.FrameSolver(subject, solver="dls")
    chains = 4

    def run(chain, out):
        pose = solver.initial_pose(observed[0])
        result = []
        for f in range(len(observed)):
            solver.solve(observed[(f + chain) % len(observed)], pose)
            result.append((pose.rotations.copy(), pose.translations.copy()))
        out[chain] = result

    serial = {}
    for c in range(chains):
        run(c, serial)
    for _ in range(10):  # The unguarded solver differed in most rounds, not all.
        parallel = {}
        threads = [threading.Thread(target=run, args=(c, parallel)) for c in range(chains)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for c in range(chains):
            for (r, t), (rs, ts) in zip(parallel[c], serial[c]):
                np.testing.assert_array_equal(r, rs)
                np.testing.assert_array_equal(t, ts)


# A segment never observed in the whole take (here every segment but the one marker kept)
# cannot be solved: solve, repair and evaluate raise naming it, as the CLI refuses it.
def test_a_take_with_a_segment_never_observed_is_refused(subject):
    markers = ms.read_markers(os.path.join(GOOD, "small.c3d"))
    positions = np.array(markers.positions)
    positions[:, 1:, :] = np.nan
    one_seen = ms.Markers(positions, list(markers.labels), markers.rate, units=markers.units)
    assert ms.load_take(subject, one_seen) is not None  # Reading it is fine.
    for call in (ms.solve, ms.repair, ms.evaluate):
        with pytest.raises(ValueError) as e:
            call(subject, one_seen)
        one_line(e, "segments never observed")
