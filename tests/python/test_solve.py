"""Marker solving: per frame and whole clip, Ceres and DLS, against the command line."""
import concurrent.futures

import numpy as np
import pytest

import mocapsolve
from conftest import run_cli

FRAMES = 40  # Seconds of test time, not minutes.


@pytest.mark.parametrize("solver", ["dls", "ceres"])
def test_per_frame_solve_is_bit_identical_to_the_cli(cmu02, tmp_path, solver):
    subject = mocapsolve.read_subject(cmu02["subject"])
    motion, report = mocapsolve.solve(subject, cmu02["c3d"], solver=solver, max_frames=FRAMES)
    assert motion.num_frames == FRAMES
    assert report["per_frame"]["frame_rms"].shape == (FRAMES,)
    assert report["per_frame"]["rms_marker_residual"] < 10.0  # mm; 3.9 over the whole take.
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, subject.skeleton, motion)
    cli = str(tmp_path / "cli.bvh")
    run_cli("solve", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"], "--solver=" + solver,
            "--max_frames=%d" % FRAMES, "--out=" + cli)
    assert open(ours).read() == open(cli).read()


@pytest.mark.parametrize("clip_solver", ["ceres", "dls"])
def test_clip_solve_matches_the_cli(cmu02, tmp_path, clip_solver):
    subject = mocapsolve.read_subject(cmu02["subject"])
    motion, report = mocapsolve.solve(subject, cmu02["c3d"], mode="clip", solver="dls", max_frames=20,
                                      num_threads=1, clip_solver=clip_solver)
    assert "clip" in report and report["clip"]["final_cost"] <= report["clip"]["initial_cost"]
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, subject.skeleton, motion)
    cli = str(tmp_path / "cli.bvh")
    run_cli("solve", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"], "--mode=clip",
            "--solver=dls", "--max_frames=20", "--num_threads=1", "--clip_solver=" + clip_solver,
            "--out=" + cli)
    assert open(ours).read() == open(cli).read()


def test_clip_solvers_reach_the_same_cost(cmu02):
    subject = mocapsolve.read_subject(cmu02["subject"])
    costs = {}
    for clip_solver in ["ceres", "dls"]:
        _, report = mocapsolve.solve(subject, cmu02["c3d"], mode="clip", solver="dls", max_frames=20,
                                     clip_solver=clip_solver, clip_function_tolerance=1e-10)
        costs[clip_solver] = report["clip"]["final_cost"]
    assert costs["dls"] == pytest.approx(costs["ceres"], rel=1e-6)


def test_frame_solver_loop_equals_solve(cmu02):
    subject = mocapsolve.read_subject(cmu02["subject"])
    take = mocapsolve.load_take(subject, cmu02["c3d"])
    observed = take.observed
    assert observed.shape == (take.num_frames, len(subject.marker_labels), 3)
    solver = mocapsolve.FrameSolver(subject, solver="dls")
    pose = solver.initial_pose(observed[0])
    rotations, residuals = [], []
    for f in range(10):
        report = solver.solve(observed[f], pose)
        assert report.usable
        rotations.append(pose.rotations)
        residuals.append(report.rms_marker_residual)
    motion, summary = mocapsolve.solve(subject, take, solver="dls", max_frames=10)
    assert np.array_equal(np.array(rotations), motion.rotations)
    # The loop's residuals are solve()'s, in the same unit under the same name (mm).
    assert report.residual_unit == summary["per_frame"]["residual_unit"] == "mm"
    assert np.allclose(residuals, summary["per_frame"]["frame_rms"], rtol=1e-9)
    assert report.rms_marker_residual == pytest.approx(report.rms_marker_error * 1000 * 0.0254 / 0.45, rel=1e-9)


def test_bad_options_raise_the_cli_message(cmu02):
    subject = mocapsolve.read_subject(cmu02["subject"])
    for keyword, flag in [({"solver": "newton"}, "--solver=newton"),
                          ({"loss": "tukey"}, "--loss=tukey"),
                          ({"dls_damping": "none"}, "--dls_damping=none"),
                          ({"max_iterations": -1}, "--max_iterations=-1")]:
        code, output = run_cli("solve", "--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"],
                               "--out=/tmp/never_written.bvh", flag, expect=1)
        with pytest.raises(ValueError) as error:
            mocapsolve.solve(subject, cmu02["c3d"], **keyword)
        assert str(error.value) in output, (str(error.value), output)
    with pytest.raises(TypeError, match="solvr"):
        mocapsolve.solve(subject, cmu02["c3d"], solvr="dls")
    with pytest.raises(OSError, match="nothing.c3d"):
        mocapsolve.solve(subject, "nothing.c3d")


def test_settings_defaults_are_the_cli_defaults():
    s = mocapsolve.SolverSettings()
    assert s.solver == "dls" and s.max_iterations == 50 and s.prior_weight == 20.0
    assert list(s.as_dict()) == mocapsolve.SOLVER_OPTION_NAMES.split(",")
    s.solver = "bogus"
    with pytest.raises(ValueError, match="--solver: unknown 'bogus'"):
        s.validate()


def test_two_takes_in_two_threads_give_the_same_motions(cmu02):
    subject = mocapsolve.read_subject(cmu02["subject"])
    take = mocapsolve.load_take(subject, cmu02["c3d"])
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        runs = list(pool.map(lambda _: mocapsolve.solve(subject, take, solver="dls", max_frames=30)[0], range(2)))
    single, _ = mocapsolve.solve(subject, take, solver="dls", max_frames=30)
    for motion in runs:
        assert np.array_equal(motion.rotations, single.rotations)


def test_solve_releases_the_gil(cmu02):
    """While a take is solved in another thread, this thread keeps running Python code: the
    longest pause between its ticks is a small part of the solve (with the GIL held it would
    be the whole solve). Independent of the machine's load, unlike a timing of two threads."""
    import time
    subject = mocapsolve.read_subject(cmu02["subject"])
    take = mocapsolve.load_take(subject, cmu02["c3d"])
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        future = pool.submit(mocapsolve.solve, subject, take, solver="ceres")
        last, longest = time.perf_counter(), 0.0
        while not future.done():
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        seconds = future.result()[1]["seconds_in_cpp"]
    assert longest < 0.5 * seconds, (longest, seconds)


def test_load_take_without_a_subject_object(cmu02):
    # load_take(None, ..., skeleton=, markerset=) assembles the subject as the CLI's flags do.
    by_files = mocapsolve.load_take(None, cmu02["c3d"], skeleton=cmu02["asf"], markerset=cmu02["markerset"],
                                    axes="y,z,x")
    subject = mocapsolve.subject(cmu02["asf"], cmu02["markerset"], axes="y,z,x")
    by_subject = mocapsolve.load_take(subject, mocapsolve.read_markers(cmu02["c3d"]))
    assert np.array_equal(by_files.observed, by_subject.observed, equal_nan=True)
