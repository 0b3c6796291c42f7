#!/usr/bin/env python3
"""Ceres vs DLS on per-frame marker solving over every frame of a real take.

CMU subject 2: the marker set is calibrated on 02_01 (its AMC is CMU's own solve), then
every frame of the take is solved twice from Python, frame by frame and warm-started,
once through Ceres and once through the hand-written DLS path on the same residual
blocks. The plot shows each frame's solve time and RMS marker residual.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/ceres_vs_dls.py --out=out/ceres_vs_dls.png
"""
import argparse
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mocapsolve  # noqa: E402


def solve_frames(subject, observed, solver):
    """Per-frame (seconds, RMS residual in mm, iterations) of a warm-started loop."""
    frame_solver = mocapsolve.FrameSolver(subject, solver=solver)
    pose = frame_solver.initial_pose(observed[0])
    mm = subject.skeleton.metres_per_unit * 1000.0
    seconds, rms, iterations = [], [], []
    for frame in observed:
        start = time.perf_counter()
        report = frame_solver.solve(frame, pose)
        seconds.append(time.perf_counter() - start)
        rms.append(report.rms_marker_error * mm)
        iterations.append(report.iterations)
    return np.array(seconds), np.array(rms), np.array(iterations)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get("MOCAPSOLVE_DATA", "../shared/data"))
    parser.add_argument("--take", default="c3d/02_01.c3d", help="marker file under --data")
    parser.add_argument("--out", default="ceres_vs_dls.png")
    parser.add_argument("--max_frames", type=int, default=0, help="0 = every frame")
    args = parser.parse_args(argv)
    d = args.data
    subject, calibration = mocapsolve.calibrate(os.path.join(d, "amc/02_01.amc"), os.path.join(d, "c3d/02_01.c3d"),
                                                skeleton=os.path.join(d, "amc/02.asf"), axes="y,z,x")
    take = mocapsolve.load_take(subject, os.path.join(d, args.take))
    observed = take.observed if args.max_frames <= 0 else take.observed[:args.max_frames]
    results = {solver: solve_frames(subject, observed, solver) for solver in ("ceres", "dls")}

    fig, (ax_time, ax_rms) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    colours = {"ceres": "tab:blue", "dls": "tab:orange"}
    for solver, (seconds, rms, iterations) in results.items():
        label = "%s: %.0f frames/s, %.1f it/frame, RMS %.3f mm" % (
            solver, len(seconds) / seconds.sum(), iterations.mean(), np.sqrt(np.mean(rms ** 2)))
        print(label)
        ax_time.plot(seconds * 1e3, color=colours[solver], lw=1, label=label)
        ax_rms.plot(rms, color=colours[solver], lw=1, label=solver)
    ax_time.set_ylabel("solve time per frame (ms)")
    ax_time.set_yscale("log")
    ax_time.legend(fontsize=8)
    ax_time.set_title("Per-frame marker solve of %s (%d frames, %d markers), called from Python"
                      % (args.take, len(observed), observed.shape[1]))
    ax_rms.set_ylabel("RMS marker residual (mm)")
    ax_rms.set_xlabel("frame")
    ax_rms.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
