"""help() explains each argument: every public function, class and method of the module has
a docstring that names each of its parameters (issue 14, item 4)."""
import inspect
import re

import mocapsolve

# pybind11's signature lines: "name(a: int, b: str = 'x,y') -> T", numbered when overloaded.
SIGNATURE = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\)( -> .*)?$")
IMPLICIT = {"self", "args", "kwargs"}


def split_arguments(text):
    """Top-level comma-separated items of a signature (quotes and brackets respected)."""
    items, current, depth, quote = [], "", 0, None
    for c in text:
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            items.append(current)
            current = ""
            continue
        current += c
    if current.strip():
        items.append(current)
    return items


def parameters_and_text(doc):
    parameters, text = [], []
    for line in (doc or "").splitlines():
        match = SIGNATURE.match(line.strip())
        if not match:
            text.append(line)
            continue
        for item in split_arguments(match.group(2)):
            name = item.split(":")[0].split("=")[0].strip().lstrip("*")
            if name and name not in IMPLICIT and name not in ("/",) and name not in parameters:
                parameters.append(name)
    return parameters, "\n".join(text)


def public_callables():
    for name in sorted(dir(mocapsolve)):
        if name.startswith("_"):
            continue
        obj = getattr(mocapsolve, name)
        if inspect.isclass(obj):
            yield name, obj
            for member_name, member in vars(obj).items():
                if (member_name.startswith("_") and member_name != "__init__") or isinstance(member, property):
                    continue
                if callable(member):
                    yield name + "." + member_name, member
        elif callable(obj):
            yield name, obj


def test_every_public_callable_documents_each_parameter():
    missing = []
    checked = 0
    for name, obj in public_callables():
        parameters, text = parameters_and_text(obj.__doc__)
        checked += 1
        if not text.strip():
            missing.append("%s: no description" % name)
        for parameter in parameters:
            if not re.search(r"\b%s\b" % re.escape(parameter), text):
                missing.append("%s: parameter '%s' not explained" % (name, parameter))
    assert checked > 60  # The walk saw the module.
    assert not missing, "\n".join(missing)


def test_the_walk_finds_parameters():
    parameters, text = parameters_and_text(mocapsolve.fit_skeleton.__doc__)
    assert {"markers", "template_subject", "skeleton", "axes", "progress"} <= set(parameters)
    assert "attach_rounds (default -1)" in text  # From the library's help table.


def test_keyword_lists_are_the_settings_defaults():
    """The keyword lists are generated from the settings objects: each name=default is there."""
    ms = mocapsolve
    solver = ms.SolverSettings()
    dls = ms.SolverSettings()
    dls.solver = "dls"
    cases = [
        (ms.solve, [(solver, None)]),
        (ms.ik_edit, [(solver, None)]),
        (ms.fit_skeleton, [(solver, None), (ms.SkeletonFitSettings(), None)]),
        (ms.repair, [(ms.RepairSettings(), None), (dls, None)]),
        (ms.evaluate, [(ms.RepairSettings(), None), (dls, None), (ms.CorruptionSettings(), None)]),
        (ms.falloff, [(ms.FalloffSettings(), None)]),
        (ms.edit_weights, [(ms.FalloffSettings(), None)]),
        (ms.retarget, [(ms.RetargetSettings(), None)]),
        (ms.pipeline, [(ms.RepairSettings(), None), (dls, None), (ms.RetargetSettings(), None)]),
    ]
    names = {ms.RepairSettings: ms.REPAIR_OPTION_NAMES, ms.CorruptionSettings: ms.CORRUPTION_OPTION_NAMES,
             ms.FalloffSettings: ms.FALLOFF_OPTION_NAMES, ms.SkeletonFitSettings: ms.SKELETON_FIT_OPTION_NAMES,
             ms.SolverSettings: ms.SOLVER_OPTION_NAMES}
    for function, settings_list in cases:
        doc = " ".join(function.__doc__.split())
        for settings, _ in settings_list:
            keys = names.get(type(settings), "").split(",")
            if isinstance(settings, ms.RetargetSettings):
                keys = ms.RETARGET_OPTION_NAMES.split(",")
                if function is ms.pipeline:
                    keys = keys[2:]  # solver and limit_weight come from SolverSettings there.
            assert len(keys) > 1
            for key in keys:
                value = getattr(settings, key)
                if isinstance(settings, ms.SkeletonFitSettings):
                    assert "%s (default %r)" % (key, value) in doc, (function.__name__, key)
                else:
                    assert "%s=%r" % (key, value) in doc, (function.__name__, key)
