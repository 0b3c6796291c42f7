"""None for any argument of any callable of the module raises an exception, never crashes.

pybind11 loads None into a parameter of a bound class's pointer or holder type as null
(solve(None, ...) used to segfault), so each such parameter goes through Required(). This
test enumerates the module's functions, methods, constructors and property setters from
their signatures, so a new entry point is covered without editing it: every parameter
without a None default gets None, the others a valid value of their annotated type. The
calls run in a subprocess with faulthandler on, so a crash names the call that caused it.
"""
import os
import subprocess
import sys
import textwrap

HERE = os.path.dirname(os.path.abspath(__file__))

PROBE = textwrap.dedent(r'''
    import faulthandler, os, re, sys, tempfile
    faulthandler.enable()
    import numpy as np
    import mocapsolve as ms

    GOOD = sys.argv[1]
    tmp = tempfile.mkdtemp(prefix="none_args_")
    subject = ms.read_subject(os.path.join(GOOD, "subject.json"))
    skeleton, motion = ms.read_motion(os.path.join(GOOD, "small.bvh"))
    markers = ms.read_markers(os.path.join(GOOD, "small.c3d"))
    take = ms.load_take(subject, os.path.join(GOOD, "small.c3d"))
    character = ms.read_character(os.path.join(GOOD, "skinned.glb"))
    edit = ms.make_edit(motion, 0, {1: np.array([0.1, 0.0, 0.0])})
    SAMPLES = {  # Annotation (last dotted part) -> a valid value.
        "Subject": subject, "Skeleton": skeleton, "Motion": motion, "Pose": motion.pose(0),
        "Markers": markers, "Take": take, "Character": character, "PoseEdit": edit,
        "SolverSettings": ms.SolverSettings(), "int": 0, "float": 1.0, "bool": False,
        "str": os.path.join(tmp, "out.json"), "object": os.path.join(GOOD, "small.c3d"),
        "dict": {}, "numpy.ndarray[numpy.float64]": np.zeros(3),
    }

    def split_top(text):
        parts, depth, item, quote = [], 0, "", None
        for c in text:
            if quote:
                quote = None if c == quote else quote
            elif c in "'\"":
                quote = c
            else:
                depth += c in "[({" ; depth -= c in "])}"
            if c == "," and depth == 0 and not quote:
                parts.append(item.strip()); item = ""
            else:
                item += c
        if item.strip():
            parts.append(item.strip())
        return parts

    def signatures(doc):
        """(params, ...) of each overload: [(name, annotation, has_none_default, kw_only)]."""
        out = []
        for line in (doc or "").splitlines():
            if not re.match(r"^(\d+\. )?\w+\(.*\) -> ", line):
                continue
            head = line[line.index("(") + 1:line.rindex(")")]
            params, kw_only = [], False
            for part in split_top(head):
                if part == "*":
                    kw_only = True; continue
                if part.startswith("*"):
                    continue
                name, _, rest = part.partition(":")
                annotation, _, default = rest.partition("=")
                params.append((name.strip(), annotation.strip(), default.strip(), kw_only))
            out.append(params)
        return out

    def sample(annotation):
        if annotation.startswith("List["):
            return [sample(annotation[5:-1])]
        if annotation.startswith("numpy.ndarray"):
            return np.zeros(3)
        return SAMPLES.get(annotation.split(".")[-1], SAMPLES.get(annotation, 0))

    def entry_points():
        for name in sorted(dir(ms)):
            obj = getattr(ms, name)
            if isinstance(obj, type):
                for attr, member in sorted(vars(obj).items()):
                    if isinstance(member, property) and member.fset is not None:
                        yield "%s.%s (setter)" % (name, attr), member.fset
                    elif attr == "__init__":
                        yield "%s.__init__" % name, obj  # Called as the class (a new instance).
                    elif callable(member) and not attr.startswith("_"):
                        yield "%s.%s" % (name, attr), getattr(obj, attr)
            elif callable(obj) and not name.startswith("_"):
                yield name, obj

    SELF = {"Subject": subject, "Skeleton": skeleton, "Motion": motion, "Pose": motion.pose(0),
            "Markers": markers, "Take": take, "Character": character}
    calls = 0
    for label, fn in entry_points():
        owner = label.split(".")[0]
        for params in signatures(fn.__doc__):
            for k, (pname, annotation, default, kw_only) in enumerate(params):
                if default == "None" or pname == "self" or annotation == "bool":
                    continue  # pybind11 converts None to False for a bool, by design.
                constructor = label.endswith(".__init__")
                args, kwargs = [], {}
                for j, (qname, qann, qdefault, qkw) in enumerate(params):
                    value = None if j == k else sample(qann)
                    if qname == "self" and constructor:
                        continue
                    if qname == "self":
                        value = SELF.get(owner) or (ms.FrameSolver(subject, solver="dls")
                                                    if owner == "FrameSolver" else getattr(ms, owner)())
                    if j != k and qdefault:
                        continue  # Keep the default.
                    if qkw:
                        kwargs[qname] = value
                    else:
                        args.append(value)
                call = "%s(%s=None)" % (label, pname)
                print("CALL " + call, flush=True)
                try:
                    fn(*args, **kwargs)
                    print("RETURNED " + call, flush=True)
                except (TypeError, ValueError, OSError, IndexError) as e:
                    lines = str(e).splitlines()
                    if len(lines) == 1 and pname not in lines[0] and type(e) is TypeError and "setter" not in label:
                        print("UNNAMED %s: %s" % (call, lines[0]), flush=True)
                except Exception as e:
                    print("BAD %s: %s: %s" % (call, type(e).__name__, e), flush=True)
                calls += 1
    print("CALLS %d" % calls, flush=True)
''')


def test_none_for_any_argument_raises_and_never_crashes():
    good = os.path.join(os.path.dirname(HERE), "data", "good")
    result = subprocess.run([sys.executable, "-c", PROBE, good], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, timeout=300)
    lines = result.stdout.splitlines()
    assert result.returncode == 0, "crashed on %s:\n%s" % (
        ([l for l in lines if l.startswith("CALL ")] or ["startup"])[-1], "\n".join(lines[-20:]))
    calls = int([l for l in lines if l.startswith("CALLS ")][0].split()[1])
    assert calls > 50, result.stdout  # The enumeration found the module's entry points.
    problems = [l for l in lines if l.startswith(("RETURNED", "BAD", "UNNAMED"))]
    assert not problems, "\n".join(problems)


def test_subject_none_names_the_argument():
    import mocapsolve as ms
    import pytest
    for call in (lambda: ms.solve(None, "x.c3d"), lambda: ms.repair(None, "x.c3d"),
                 lambda: ms.evaluate(None, "x.c3d"), lambda: ms.load_take(None, "x.c3d"),
                 lambda: ms.FrameSolver(None)):
        with pytest.raises(TypeError, match=r"^subject: expected a Subject, got None$"):
            call()
