"""Every command's --report follows its documented schema (docs/schemas/, issue 17).

Each command runs once on small fixtures (the demo walk, its synthetic markers, CMU 02_01
for the commands that need a subject or a character) and once on bad input; the success
report must validate against docs/schemas/<command>.schema.json and the failure report
against docs/schemas/report.schema.json (the envelope every report shares: status,
version, command, options in force, inputs with their content hashes; a message on error).
"""
import json
import os

import jsonschema
import pytest

from conftest import REPO, data_file, run_cli

SCHEMAS = os.path.join(REPO, "docs", "schemas")


def schema(name):
    with open(os.path.join(SCHEMAS, name + ".schema.json")) as f:
        return json.load(f)


def validator(name):
    """A validator of docs/schemas/<name>.schema.json that resolves its $ref to the envelope."""
    resolver = jsonschema.RefResolver(base_uri="file://" + SCHEMAS + "/", referrer=schema(name))
    return jsonschema.Draft7Validator(schema(name), resolver=resolver)


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    folder = tmp_path_factory.mktemp("reports")
    walk, c3d, markerset = str(folder / "walk.bvh"), str(folder / "walk.c3d"), str(folder / "set.json")
    run_cli("generate", "--demo_out=" + walk, "--frames=40", "--fps=30")
    run_cli("markers", "--motion=" + walk, "--skeleton_units=cm", "--markerset=auto:3",
            "--write_markerset=" + markerset, "--out=" + c3d)
    edit = str(folder / "edit.json")
    with open(edit, "w") as f:
        json.dump({"frame": 10, "joints": {"Spine": {"rotation_offset_deg": [10, 0, 0]}}}, f)
    return {"folder": folder, "walk": walk, "c3d": c3d, "markerset": markerset, "edit": edit}


def marker_take(d):
    return ["--skeleton=" + d["walk"], "--skeleton_units=cm", "--markers=" + d["c3d"],
            "--markerset=" + d["markerset"]]


def demo_subject(d):
    """A subject file for the demo walk and its marker set (live reads only subjects)."""
    path = d["folder"] / "subject.json"
    with open(d["markerset"]) as f:
        markerset = json.load(f)
    with open(path, "w") as f:
        json.dump({"format": "mocapsolve.subject", "version": 1, "skeleton": os.path.abspath(d["walk"]),
                   "skeleton_units": "cm", "markerset": markerset}, f)
    return str(path)


# Each command's success run: the arguments after the command name (d: the demo fixture).
SUCCESS = {
    "info": lambda d: [d["walk"]],
    "convert": lambda d: [d["walk"], str(d["folder"] / "c.bvh")],
    "fk": lambda d: ["--motion=" + d["walk"], "--out=" + str(d["folder"] / "fk.csv")],
    "markers": lambda d: ["--motion=" + d["walk"], "--skeleton_units=cm", "--markerset=auto:2",
                          "--out=" + str(d["folder"] / "m.trc")],
    "solve": lambda d: marker_take(d) + ["--solver=dls", "--out=" + str(d["folder"] / "s.bvh")],
    "repair": lambda d: marker_take(d) + ["--out_markers=" + str(d["folder"] / "r.c3d")],
    "label": lambda d: marker_take(d) + ["--out=" + str(d["folder"] / "l.c3d")],
    "corrupt": lambda d: ["--markers=" + d["c3d"], "--out=" + str(d["folder"] / "x.c3d"),
                          "--cluster_radius_mm=0"],
    "evaluate": lambda d: marker_take(d) + ["--gaps=2", "--gap_min=5", "--gap_max=8", "--trim_max=5"],
    "calibrate": lambda d: ["--motion=" + d["walk"], "--skeleton_units=cm", "--markers=" + d["c3d"],
                            "--attach=" + d["markerset"], "--out=" + str(d["folder"] / "cal.json")],
    "fit_skeleton": lambda d: marker_take(d) + ["--solver=dls", "--fit_iterations=2",
                                                "--out=" + str(d["folder"] / "fit.bvh")],
    "filter": lambda d: ["--motion=" + d["walk"], "--levels=2", "--out=" + str(d["folder"] / "f.bvh")],
    "bands": lambda d: ["--motion=" + d["walk"], "--weights=1,1,1,1", "--out=" + str(d["folder"] / "b.bvh")],
    "blend": lambda d: ["--a=" + d["walk"], "--b=" + d["walk"], "--transition=10:20",
                        "--out=" + str(d["folder"] / "bl.bvh")],
    "distance": lambda d: ["--motion=" + d["walk"], "--frame=10", "--out=" + str(d["folder"] / "d.csv")],
    "propagate": lambda d: ["--motion=" + d["walk"], "--frame=10", "--edit=" + d["edit"],
                            "--out=" + str(d["folder"] / "p.bvh")],
    "bench": lambda d: ["--problem=fk", "--repeats=1", "--bench_motion=" + d["walk"]],
    "live": lambda d: ["--subject=" + demo_subject(d), "--input=replay:" + d["c3d"], "--replay_speed=0"],
}

# The commands that need real data: a subject (CMU 02 calibrated on 02_01) or characters.
def real_cases(d, cmu02):
    g = lambda name: data_file("gltf/" + name)
    return {
        "retarget": ["--source=" + g("CesiumMan.glb"), "--target=" + g("RiggedFigure.glb"), "--max_frames=3",
                     "--out=" + str(d["folder"] / "rf.glb")],
        "pipeline": ["--subject=" + cmu02["subject"], "--markers=" + cmu02["c3d"],
                     "--out_dir=" + str(d["folder"] / "take")],
    }


# Bad input for each: a missing file or a bad value, exit code 1.
FAILURE = {
    "info": lambda d: ["/nonexistent/file.bvh"],
    "solve": lambda d: marker_take(d) + ["--solver=nope", "--out=" + str(d["folder"] / "s2.bvh")],
    "repair": lambda d: marker_take(d) + ["--trim_max=-1", "--out_markers=" + str(d["folder"] / "r2.c3d")],
    "fk": lambda d: ["--motion=/nonexistent.bvh", "--out=" + str(d["folder"] / "fk2.csv")],
    "evaluate": lambda d: marker_take(d) + ["--method=guess"],
    "label": lambda d: marker_take(d) + ["--min_confidence=2", "--out=" + str(d["folder"] / "l2.c3d")],
    "distance": lambda d: ["--motion=" + d["walk"], "--frame=999", "--out=" + str(d["folder"] / "d2.csv")],
}


@pytest.mark.parametrize("command", sorted(SUCCESS))
def test_success_report_follows_the_command_schema(demo, command):
    report = str(demo["folder"] / (command + ".json"))
    run_cli(command, *SUCCESS[command](demo), "--report=" + report)
    with open(report) as f:
        document = json.load(f)
    validator(command).validate(document)
    assert document["status"] == "ok" and document["command"] == command
    # Its options block: every flag the command declares, typed as declared
    # (docs/schemas/options/, made from the declarations by scripts/make_command_docs.py).
    jsonschema.Draft7Validator(schema("options/" + command)).validate(document["options"])
    # The inputs it read, with their sizes and hashes.
    for entry in document["inputs"]:
        assert os.path.getsize(os.path.join(os.getcwd(), entry["path"])) == entry["bytes"]


@pytest.mark.parametrize("command", ["retarget", "pipeline"])
def test_success_report_of_real_data_commands(demo, cmu02, command):
    report = str(demo["folder"] / (command + ".json"))
    run_cli(command, *real_cases(demo, cmu02)[command], "--report=" + report)
    with open(report) as f:
        document = json.load(f)
    validator(command).validate(document)
    assert document["status"] == "ok" and document["command"] == command
    options = schema("options/" + command)
    if command == "pipeline":  # Its options block is its config file: the option flags only.
        options["required"] = sorted(document["options"])
    jsonschema.Draft7Validator(options).validate(document["options"])


def test_evaluate_retarget_report_follows_the_schema(demo, cmu02):
    """evaluate --method=retarget: a row per character, each with its quality block."""
    report = str(demo["folder"] / "evaluate_retarget.json")
    characters = ",".join(data_file("gltf/" + name) for name in ("CesiumMan.glb", "RiggedFigure.glb"))
    run_cli("evaluate", "--method=retarget", "--motion=" + cmu02["amc"], "--skeleton=" + cmu02["asf"],
            "--target=" + characters, "--max_frames=30", "--report=" + report)
    with open(report) as f:
        document = json.load(f)
    validator("evaluate").validate(document)
    assert [c["character"] for c in document["characters"]] == ["CesiumMan", "RiggedFigure"]
    for c in document["characters"]:
        assert len(c["quality"]["limbs"]) == 8 and c["quality"]["pass"] == (not c["quality"]["failures"])
    jsonschema.Draft7Validator(schema("options/evaluate")).validate(document["options"])


@pytest.mark.parametrize("command", sorted(FAILURE))
def test_failure_report_follows_the_envelope(demo, command):
    report = str(demo["folder"] / (command + "_error.json"))
    run_cli(command, *FAILURE[command](demo), "--report=" + report, expect=1)
    with open(report) as f:
        document = json.load(f)
    validator("report").validate(document)
    assert document["status"] == "error" and document["message"]


def test_every_command_with_a_report_has_a_schema_and_a_test():
    _, listing = run_cli("--help", expect=None)
    commands = [line.split()[0] for line in listing.split("commands:")[1].strip().splitlines() if line.startswith("  ")]
    reporting = [c for c in commands if "  --report (" in run_cli(c, "--help", expect=None)[1]]
    assert len(reporting) >= 15, reporting
    missing = [c for c in reporting if not os.path.exists(os.path.join(SCHEMAS, c + ".schema.json"))]
    assert not missing, missing
    untested = [c for c in reporting if c not in SUCCESS and c not in ("retarget", "pipeline")]
    assert not untested, untested


def test_a_command_without_report_writes_none(demo):
    report = str(demo["folder"] / "view_error.json")
    run_cli("view", "--markers=" + demo["c3d"], "--out=" + str(demo["folder"] / "p.html"), "--report=" + report,
            expect=1)
    assert not os.path.exists(report)


def test_a_report_missing_its_envelope_is_refused():
    with pytest.raises(jsonschema.ValidationError):
        validator("report").validate({"status": "ok", "command": "solve"})
    with pytest.raises(jsonschema.ValidationError):
        validator("report").validate({"status": "error", "version": "1", "command": "solve",
                                      "options": {}, "inputs": []})  # No message.
