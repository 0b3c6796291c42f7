#!/usr/bin/env python3
"""Overheads of the Python module (issue 14), on CMU subject 2's takes:

1. per frame: 02_01 solved frame by frame from a Python loop (FrameSolver.solve, the pose
   warm-started and copied per frame as SolveSequence does) vs the C++ loop itself
   (SolveSequence's own timer, the same loop the CLI runs); target <= 1.3x;
2. whole take: the wall time of one mocapsolve.solve() call from Python vs the time
   spent in the C++ solve it wraps (measured inside the binding); target <= 1.05x;
3. threads: two takes (cmu_02_05, 1854 frames, twice) solved in 2 Python threads vs one
   after the other; target <= 0.6x.
DLS, default options, medians of --repeats runs. Prints one line per figure and a JSON line.
The machine may be shared: run it when `uptime` shows a low load and report the load.

  PYTHONPATH=build/python /usr/bin/python3 bench/python/python_overhead.py --repeats=7
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import sys
import time

import mocapsolve


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get("MOCAPSOLVE_DATA", "../shared/data"))
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--solver", default="dls")
    args = parser.parse_args()
    d = args.data
    load = os.getloadavg()
    subject, _ = mocapsolve.calibrate(os.path.join(d, "amc/02_01.amc"), os.path.join(d, "c3d/02_01.c3d"),
                                      skeleton=os.path.join(d, "amc/02.asf"), axes="y,z,x")
    take = mocapsolve.load_take(subject, os.path.join(d, "c3d/02_01.c3d"))
    observed = take.observed

    # 1. Per frame.
    def cpp_loop():
        return mocapsolve.solve(subject, take, solver=args.solver)[1]["per_frame"]["seconds"]

    def python_loop():
        solver = mocapsolve.FrameSolver(subject, solver=args.solver)
        pose = solver.initial_pose(observed[0])
        poses = []
        start = time.perf_counter()
        for frame in observed:
            solver.solve(frame, pose)
            poses.append(pose.copy())
        return time.perf_counter() - start

    cpp_loop(), python_loop()  # Warm up.
    # Interleaved, so that a change of the machine's load hits both alike.
    pairs = [(cpp_loop(), python_loop()) for _ in range(args.repeats)]
    cpp = statistics.median(c for c, _ in pairs)
    py = statistics.median(p for _, p in pairs)
    per_frame_ratio = statistics.median(p / c for c, p in pairs)
    frames = len(observed)
    print("per frame, 02_01 (%d frames, %s): C++ loop %.2f ms (%.0f frames/s), Python loop %.2f ms "
          "(%.0f frames/s): %.3fx (median of per-pair ratios; target <= 1.3x)"
          % (frames, args.solver, cpp * 1e3, frames / cpp, py * 1e3, frames / py, per_frame_ratio))

    # 2. Whole take.
    def whole_take():
        start = time.perf_counter()
        report = mocapsolve.solve(subject, take, solver=args.solver)[1]
        return time.perf_counter() - start, report["seconds_in_cpp"]

    runs = [whole_take() for _ in range(args.repeats)]
    ratios = sorted(wall / inside for wall, inside in runs)
    wall = statistics.median(r[0] for r in runs)
    inside = statistics.median(r[1] for r in runs)
    print("whole take, 02_01: call %.2f ms, C++ solve inside it %.2f ms: %.4fx (median of per-run ratios; "
          "target <= 1.05x)" % (wall * 1e3, inside * 1e3, ratios[len(ratios) // 2]))

    # 3. Two takes in two threads.
    take_05 = [mocapsolve.load_take(subject, os.path.join(d, "c3d/cmu_02_05.c3d")) for _ in range(2)]

    def sequential():
        start = time.perf_counter()
        for t in take_05:
            mocapsolve.solve(subject, t, solver=args.solver)
        return time.perf_counter() - start

    cpu_per_wall = []

    def threaded():
        start, cpu = time.perf_counter(), time.process_time()
        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            list(pool.map(lambda t: mocapsolve.solve(subject, t, solver=args.solver), take_05))
        wall = time.perf_counter() - start
        cpu_per_wall.append((time.process_time() - cpu) / wall)  # ~2 when both threads run at once.
        return wall

    runs = [(sequential(), threaded()) for _ in range(max(3, args.repeats // 2))]
    seq = statistics.median(a for a, _ in runs)
    par = statistics.median(b for _, b in runs)
    threads_ratio = statistics.median(b / a for a, b in runs)
    print("2 takes (cmu_02_05 x2, %d frames each): one after the other %.3f s, 2 threads %.3f s: %.3fx "
          "(median of per-pair ratios; target <= 0.6x); process CPU time / wall time in the threaded runs "
          "%.2f (2 = both cores busy)" % (take_05[0].num_frames, seq, par, threads_ratio,
                                         statistics.median(cpu_per_wall)))
    print("load average before: %.2f %.2f %.2f, after: %.2f %.2f %.2f" % (load + os.getloadavg()))
    print(json.dumps({"benchmark": "python_overhead", "solver": args.solver, "frames": frames,
                      "cpp_loop_s": cpp, "python_loop_s": py, "per_frame_ratio": per_frame_ratio,
                      "whole_take_call_s": wall, "whole_take_cpp_s": inside,
                      "whole_take_ratio": ratios[len(ratios) // 2], "two_takes_sequential_s": seq,
                      "two_takes_threads_s": par, "threads_ratio": threads_ratio,
                      "threads_cpu_per_wall": statistics.median(cpu_per_wall),
                      "load_before": load, "load_after": os.getloadavg()}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
