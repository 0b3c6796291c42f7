#!/usr/bin/env python3
"""Fuzz target for the Python module's array entry points.

Calls every function, constructor and property setter of mocapsolve that takes a numpy
array with random arrays: wrong shapes and ranks, empty arrays, other dtypes (float32,
ints, bool, complex, object, str), NaN/inf/1e308 values, non-contiguous and Fortran-order
views, and non-arrays (None, lists, scalars, strings). It asserts only that each call
returns or raises an ordinary Python exception: a crash (segfault, abort, heap corruption),
a hang, or SystemError/RuntimeError is a finding, reported with the call that caused it.

Reproducible: call i of seed s draws everything from its own generator (s, i), so
  fuzz_arrays.py --seed S --only I
repeats one reported call in this process (under gdb if need be). The driver runs the
calls in worker subprocesses with faulthandler on; a worker that dies is reported with
its last announced call and the driver carries on after it.

  fuzz_arrays.py [--seed 1] [--budget 20] [--max_calls N]   (exit status 1 on a finding)
The worker needs `import mocapsolve` (PYTHONPATH=build/python) and numpy.
"""
import argparse
import faulthandler
import os
import random
import subprocess
import sys
import tempfile
import time
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
GOOD = os.path.join(os.path.dirname(HERE), "data", "good")

# Exceptions a bad argument may raise; anything else (SystemError, RuntimeError, ...) is a
# binding that let a C++ error or a pybind11 cast failure through unchecked.
ACCEPTED = (TypeError, ValueError, IndexError, OSError, OverflowError)

DTYPES = ["float64", "float64", "float64", "float32", "int32", "int64", "bool", "complex128", "object", "U3"]
SPECIALS = [float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 0.0, 1e-308, 1e9, 1e10]


class Fixtures:
    """The valid objects the calls start from (tests/data/good), built once per worker."""

    def __init__(self, ms, np):
        self.ms, self.np = ms, np
        self.tmp = tempfile.mkdtemp(prefix="fuzz_arrays_")
        self.subject = ms.read_subject(os.path.join(GOOD, "subject.json"))
        self.skeleton = self.subject.skeleton
        self.motion = ms.read_motion(os.path.join(GOOD, "small.bvh"))[1]
        self.markers = ms.read_markers(os.path.join(GOOD, "small.c3d"))
        self.take = ms.load_take(self.subject, os.path.join(GOOD, "small.c3d"))
        self.solver = ms.FrameSolver(self.subject, solver="dls", max_iterations=5)
        self.character = ms.read_character(os.path.join(GOOD, "skinned.glb"))
        self.edit = ms.make_edit(self.motion, 0, {1: np.array([0.1, 0.0, 0.0])})
        self.joints = self.skeleton.num_joints
        self.frames = self.motion.num_frames


class Draw:
    """Random arguments of one call, from its own generator."""

    def __init__(self, np, seed, index):
        self.np = np
        self.rng = random.Random("%d:%d" % (seed, index))
        self.nrng = np.random.default_rng([seed, index])

    def chance(self, p):
        return self.rng.random() < p

    def shape_near(self, shape):
        """shape itself, or one dimension changed, dropped, added or zeroed, or any shape."""
        shape = list(shape)
        kind = self.rng.randrange(7)
        if kind <= 1 or not shape:
            return shape
        i = self.rng.randrange(len(shape))
        if kind == 2:
            shape[i] = max(0, shape[i] + self.rng.choice([-1, 1, 2, 7]))
        elif kind == 3:
            shape[i] = 0
        elif kind == 4:
            del shape[i]
        elif kind == 5:
            shape.insert(i, self.rng.randrange(4))
        else:
            shape = [self.rng.randrange(6) for _ in range(self.rng.randrange(5))]
        return shape

    def values(self, shape):
        np = self.np
        a = self.nrng.normal(size=shape)
        if a.size and self.chance(0.4):  # A few special values.
            flat = a.reshape(-1)
            for _ in range(self.rng.randrange(1, 4)):
                flat[self.rng.randrange(flat.size)] = self.rng.choice(SPECIALS)
        if a.size and self.chance(0.1):
            a[...] = self.rng.choice(SPECIALS)
        return np.asarray(a)

    def array(self, shape, valid=None):
        """An array meant for a parameter of shape `shape` (valid: a correct value to vary)."""
        np = self.np
        roll = self.rng.random()
        if roll < 0.06:
            return self.rng.choice([None, 0, 1.5, "abc", [], [1.0, 2.0, 3.0], {"a": 1}, b"\x00"])
        if valid is not None and roll < 0.3:
            a = np.array(valid, dtype=float, copy=True)
            if a.size and self.chance(0.6):
                a.reshape(-1)[self.rng.randrange(a.size)] = self.rng.choice(SPECIALS)
        else:
            a = self.values(self.shape_near(shape))
        if self.chance(0.15):
            dtype = self.rng.choice(DTYPES)
            try:
                a = a.astype(dtype)
            except (ValueError, OverflowError):
                pass
        layout = self.rng.randrange(6)
        if layout == 0 and a.ndim >= 1:  # Non-contiguous: every other row of a doubled array.
            big = np.repeat(a, 2, axis=0)
            a = big[::2]
        elif layout == 1 and a.ndim >= 2:
            a = np.asfortranarray(a)
        elif layout == 2 and a.ndim >= 2:
            a = a.T.copy().T  # Transposed strides, same shape.
        elif layout == 3 and self.chance(0.3):
            a = a.tolist()
        return a

    def number(self):
        return self.rng.choice([30.0, 120.0, 0.0, -1.0, float("nan"), float("inf"), 1e308, 1, 2, 3, -5])


def _signal_bands(ms, np, draw):
    n = draw.rng.choice([1, 2, 3, 5, 17, 100])
    c = draw.rng.choice([1, 3, 7])
    levels = draw.rng.choice([0, 1, 2, 3])
    try:
        bands, gaussian = ms.laplacian_pyramid(np.random.default_rng(n).normal(size=(n, c)), levels=levels)
    except ValueError:
        bands, gaussian = [np.zeros((n, c))], [np.zeros(((n + 1) // 2, c))]
    return bands, gaussian


def target_table(fx):
    """name -> function(draw) making one call. Each name is the callable it exercises."""
    ms, np = fx.ms, fx.np
    J, F, M = fx.joints, fx.frames, len(fx.subject.marker_labels)
    K = fx.markers.num_markers
    rest = fx.skeleton.rest_pose()
    quats = np.tile([0.0, 0.0, 0.0, 1.0], (J, 1))

    def markers_positions(d):
        m = ms.Markers(fx.markers.positions.copy(), fx.markers.labels, fx.markers.rate)
        value = d.array([fx.markers.num_frames, K, 3])
        try:
            m.positions[...] = value
        except (ValueError, TypeError):
            pass
        return m

    def reconstruct(d):
        bands, gaussian = _signal_bands(ms, np, d)
        bands = [d.array(b.shape, b) if d.chance(0.3) else b for b in bands]
        if d.chance(0.3) and bands:
            del bands[d.rng.randrange(len(bands))]
        top = gaussian[-1] if gaussian else np.zeros((1, 1))
        top = d.array(top.shape, top) if d.chance(0.5) else top
        weights = [1.0] * (len(bands) + 1) if d.chance(0.7) else [d.number() for _ in range(d.rng.randrange(5))]
        return ms.reconstruct_signal(bands, top, weights)

    def motion_from(d):
        rot = d.array([F, J, 4], np.tile(quats, (F, 1, 1)))
        trans = d.array([F, 3] if d.chance(0.5) else [F, J, 3])
        return ms.Motion(fx.skeleton, rot, trans, d.number() if d.chance(0.3) else 30.0)

    def set_attr(obj, name, value):
        setattr(obj, name, value)

    return {
        "Markers.__init__": lambda d: ms.Markers(d.array([d.rng.randrange(4), 2, 3]), ["A", "B"],
                                                 d.number() if d.chance(0.4) else 100.0),
        "Markers.positions": lambda d: ms.write_markers(
            os.path.join(fx.tmp, "m" + d.rng.choice([".c3d", ".trc"])), markers_positions(d)),
        "filter": lambda d: ms.filter(markers_positions(d) if d.chance(0.5) else motion_from(d),
                                      levels=d.rng.choice([1, 2, 3])),
        "bands": lambda d: ms.bands(markers_positions(d), [d.number() for _ in range(d.rng.randrange(4))]),
        "corrupt": lambda d: ms.corrupt(markers_positions(d), seed=d.rng.randrange(100)),
        "Pose.__init__": lambda d: ms.Pose(fx.skeleton, d.array([J, 4], quats),
                                           d.array([3] if d.chance(0.5) else [J, 3])),
        "Pose.rotations": lambda d: set_attr(rest.copy(), "rotations", d.array([J, 4], quats)),
        "Motion.__init__": motion_from,
        "Motion.rotations": lambda d: set_attr(fx.motion, "rotations", d.array([F, J, 4], fx.motion.rotations)),
        "Motion.translations": lambda d: set_attr(fx.motion, "translations",
                                                  d.array([F, J, 3], fx.motion.translations)),
        "Motion.root_translations": lambda d: set_attr(fx.motion, "root_translations",
                                                       d.array([F, 3], fx.motion.root_translations)),
        "retract_pose": lambda d: ms.retract_pose(rest, d.array([3 + 3 * J], np.zeros(3 + 3 * J))),
        "forward_kinematics": lambda d: ms.forward_kinematics(fx.skeleton, motion_from(d)),
        "velocity_jumps": lambda d: ms.velocity_jumps(fx.skeleton, motion_from(d)),
        "laplacian_pyramid": lambda d: ms.laplacian_pyramid(d.array([d.rng.randrange(12), 2]),
                                                             levels=d.rng.choice([0, 1, 2, 5, -1])),
        "reconstruct_signal": reconstruct,
        "FrameSolver.solve": lambda d: fx.solver.solve(d.array([M, 3], fx.take.observed[0]), rest.copy()),
        "FrameSolver.initial_pose": lambda d: fx.solver.initial_pose(d.array([M, 3], fx.take.observed[0])),
        "make_edit": lambda d: ms.make_edit(fx.motion, d.rng.choice([0, 1, F - 1, F, -1]),
                                            {d.rng.choice([0, 1, J, -1]): d.array([3], np.zeros(3))},
                                            d.array([3], np.zeros(3)) if d.chance(0.5) else None),
        "propagate": lambda d: ms.propagate(fx.skeleton, fx.motion, [fx.edit],
                                            [d.array([F], np.ones(F)) for _ in range(d.rng.choice([0, 1, 1, 2]))]),
        "skinned_vertex_jacobians": lambda d: ms.skinned_vertex_jacobians(
            fx.character, ms.Pose(fx.character.skeleton, d.array([fx.character.skeleton.num_joints, 4],
                                                                  np.tile(quats[:1], (fx.character.skeleton.num_joints, 1))),
                                  d.array([3], np.zeros(3))), d.rng.choice([0, 1, -1, 10 ** 6])),
    }


def array_callables(ms):
    """Names of every callable whose signature takes an ndarray (functions, methods,
    constructors, property setters): the table above must cover them all."""
    names = set()

    def takes_array(doc):
        return doc is not None and "numpy.ndarray" in doc.split("->")[0]

    for name in dir(ms):
        obj = getattr(ms, name)
        if isinstance(obj, type):
            for attr, member in vars(obj).items():
                if isinstance(member, property):
                    if member.fset is not None and takes_array(member.fset.__doc__):
                        names.add("%s.%s" % (name, attr))
                elif callable(member) and takes_array(getattr(member, "__doc__", None)):
                    names.add("%s.%s" % (name, attr))
        elif callable(obj) and takes_array(getattr(obj, "__doc__", None)):
            names.add(name)
    return names


def run_worker(seed, start, count, deadline):
    faulthandler.enable()
    warnings.simplefilter("ignore")  # numpy's ComplexWarning etc. on the casts asked for.
    import numpy as np
    import mocapsolve as ms
    fx = Fixtures(ms, np)
    table = target_table(fx)
    names = sorted(table)
    findings = 0
    for i in range(start, start + count):
        if time.time() > deadline:
            break
        name = names[i % len(names)]
        print("CALL %d %s" % (i, name), flush=True)
        try:
            table[name](Draw(np, seed, i))
        except ACCEPTED:
            pass
        except Exception as e:  # noqa: BLE001 - the finding is the exception's type.
            findings += 1
            print("FINDING %d %s: %s: %s" % (i, name, type(e).__name__, str(e).splitlines()[0] if str(e) else ""),
                  flush=True)
    print("DONE %d" % i, flush=True)
    return 1 if findings else 0


def run_driver(seed, budget, max_calls):
    import mocapsolve as ms
    import numpy as np
    missing = array_callables(ms) - set(target_table(Fixtures(ms, np)))
    failures = []
    if missing:
        failures.append("array entry points with no fuzz target: " + ", ".join(sorted(missing)))
    deadline = time.time() + budget
    start, calls = 0, 0
    while time.time() < deadline and calls < max_calls:
        count = min(2000, max_calls - calls)
        cmd = [sys.executable, os.path.abspath(__file__), "--worker", "--seed", str(seed), "--start", str(start),
               "--count", str(count), "--deadline", str(deadline)]
        try:
            result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                    timeout=max(5.0, deadline - time.time() + 30.0))
            output, code = result.stdout, result.returncode
        except subprocess.TimeoutExpired as e:
            output, code = (e.stdout or b"").decode() if isinstance(e.stdout, bytes) else (e.stdout or ""), "hang"
        lines = output.splitlines()
        calls_seen = [l for l in lines if l.startswith("CALL ")]
        for l in lines:
            if l.startswith("FINDING "):
                failures.append(l[len("FINDING "):] + "  (repeat: --seed %d --only %s)" % (seed, l.split()[1]))
        last = int(calls_seen[-1].split()[1]) if calls_seen else start
        if code != 0 and not any(l.startswith("DONE") for l in lines):
            tail = "\n    ".join(lines[-12:])
            failures.append("%s in %s (exit %s; repeat: --seed %d --only %d)\n    %s" % (
                "crash" if code != "hang" else "hang", calls_seen[-1] if calls_seen else "startup", code,
                seed, last, tail))
        calls += last - start + 1
        start = last + 1
    print("fuzz_arrays: seed %d, %d calls, %d findings" % (seed, calls, len(failures)))
    for f in failures:
        print("  " + f)
    return 1 if failures else 0


def run_one(seed, index):
    faulthandler.enable()
    import numpy as np
    import mocapsolve as ms
    fx = Fixtures(ms, np)
    table = target_table(fx)
    name = sorted(table)[index % len(table)]
    print("CALL %d %s" % (index, name), flush=True)
    table[name](Draw(np, seed, index))
    print("returned", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--budget", type=float, default=20.0, help="seconds")
    parser.add_argument("--max_calls", type=int, default=10 ** 9)
    parser.add_argument("--only", type=int, help="run call ONLY in this process and show what it raises")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--start", type=int, default=0, help=argparse.SUPPRESS)
    parser.add_argument("--count", type=int, default=0, help=argparse.SUPPRESS)
    parser.add_argument("--deadline", type=float, default=0.0, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.only is not None:
        return run_one(args.seed, args.only)
    if args.worker:
        return run_worker(args.seed, args.start, args.count, args.deadline)
    return run_driver(args.seed, args.budget, args.max_calls)


if __name__ == "__main__":
    sys.exit(main())
