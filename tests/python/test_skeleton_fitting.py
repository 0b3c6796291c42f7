"""Skeleton fitting (fit_skeleton) against the command line on a short real take."""
import json
import os

import pytest

import mocapsolve
from conftest import data_file, run_cli

# squat.c3d (53-marker Vicon set) from the CMU subject 2 template, kept short: 116 frames (at
# most 120, spread over the take),
# one attach round, few iterations (about a second); check='warn' since a fit this short
# need not pass the checks.
SHORT = {"fit_max_frames": 120, "attach_rounds": 1, "fit_iterations": 3, "attach_iterations": 2,
         "check": "warn", "solver": "dls"}


def cli_flags(options):
    return ["--%s=%s" % (k, v) for k, v in options.items()]


def without_seconds(report):
    """The fit's own members: not its time, nor the envelope every CLI report adds
    (status, version, command, options, inputs: docs/schemas/report.schema.json)."""
    report = dict(report)
    for key in ("seconds", "status", "version", "command", "options", "inputs"):
        report.pop(key, None)
    return report


def test_fit_skeleton_is_bit_identical_to_the_cli(cmu02, tmp_path):
    squat = data_file("c3d/squat.c3d")
    events = []
    subject, motion, report = mocapsolve.fit_skeleton(squat, cmu02["subject"], progress=events.append, **SHORT)
    ours = str(tmp_path / "py.json")
    mocapsolve.write_subject(ours, subject)
    ours_bvh = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours_bvh, subject.skeleton, motion)
    cli, cli_bvh, cli_report = (str(tmp_path / n) for n in ("cli.json", "cli.bvh", "cli_report.json"))
    run_cli("fit_skeleton", "--template_subject=" + cmu02["subject"], "--markers=" + squat,
            "--out_subject=" + cli, "--out=" + cli_bvh, "--report=" + cli_report, *cli_flags(SHORT))
    assert open(ours, "rb").read() == open(cli, "rb").read()
    assert open(ours_bvh, "rb").read() == open(cli_bvh, "rb").read()
    assert without_seconds(report) == without_seconds(json.load(open(cli_report)))
    assert motion.num_frames == 116  # At most 120 spread over the take's 2539 frames: every 22nd.
    # Progress: each round's start and end, each iteration, every frame of each pose solve;
    # then the second fit with the feet's locked roll freed, announced, reported the same way.
    kinds = [e["kind"] for e in events]
    assert kinds.count("freeing_axes") == 1
    second = kinds.index("freeing_axes")
    assert events[second]["text"] == "lfoot, rfoot"
    first, kinds = kinds[:second], kinds[second + 1:]
    for fit in (first, kinds):
        assert fit.count("round") == 2 and fit.count("round_done") == 2
        assert fit.count("frames") == 116 * (3 + 1 + 2 + 1)
    assert first.count("iteration") == 3 + 2
    assert "template_labels" not in kinds
    # The shipped map the default template_labels="auto" applies, announced first.
    assert events[0]["kind"] == "template_labels"
    assert events[0]["text"] == report["template_labels_map"] == "examples/vicon53_to_cmu_labels.txt"
    assert all(e["frames"] == 116 for e in events[1:] if e["kind"] != "freeing_axes")


def test_fit_skeleton_from_skeleton_and_markerset_files(cmu02):
    squat = data_file("c3d/squat.c3d")
    options = dict(SHORT, attach_rounds=0)
    subject, _, report = mocapsolve.fit_skeleton(squat, skeleton=cmu02["asf"], markerset=cmu02["markerset"],
                                                 axes="x,y,z", **options)
    assert report["template"] == cmu02["asf"] and report["attach_rounds"] == 0
    # The template's markers the take has: 26 by label, and those the shipped map renames.
    assert len(report["template_labels"]) == 8
    assert len(subject.marker_labels) == 26 + 8


def test_fit_skeleton_failing_its_checks_raises_the_cli_message(cmu02):
    squat = data_file("c3d/squat.c3d")
    options = dict(SHORT, check="fail", fit_iterations=1, attach_rounds=0)
    with pytest.raises(ValueError) as error:
        mocapsolve.fit_skeleton(squat, cmu02["subject"], **options)
    code, output = run_cli("fit_skeleton", "--template_subject=" + cmu02["subject"], "--markers=" + squat,
                           "--out_subject=" + os.devnull + ".json", *cli_flags(options), expect=1)
    assert str(error.value) in output


@pytest.mark.parametrize("keyword,flag", [
    ({"attach_rounds": 30}, "--attach_rounds=30"),
    ({"fit_frame_step": 0}, "--fit_frame_step=0"),
    ({"min_bone_scale": 1.5}, "--min_bone_scale=1.5"),
    ({"check": "maybe"}, "--check=maybe"),
    ({"solver": "newton"}, "--solver=newton"),
    ({"template_labels": "RFWT:RASI:X"}, "--template_labels=RFWT:RASI:X"),
    ({"template_labels": "RFWT:NOPE"}, "--template_labels=RFWT:NOPE"),
])
def test_bad_options_raise_the_cli_message(cmu02, tmp_path, keyword, flag):
    squat = data_file("c3d/squat.c3d")
    with pytest.raises(ValueError) as error:
        mocapsolve.fit_skeleton(squat, cmu02["subject"], **keyword)
    _, output = run_cli("fit_skeleton", "--template_subject=" + cmu02["subject"], "--markers=" + squat,
                        "--out_subject=" + str(tmp_path / "s.json"), flag, expect=1)
    assert output.strip() == str(error.value)


def test_template_labels_fit_a_take_of_another_protocol(cmu02, tmp_path):
    """JA1Gait35 (AIS marker set) through the shipped AIS-to-CMU map: round 0 fits the 5 shared
    labels and the 22 mapped markers under the take's labels, as the CLI does."""
    take = data_file("c3d/JA1Gait35.c3d")
    labels = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                          "examples", "ais_to_cmu_labels.txt")
    options = {"fit_max_frames": 40, "attach_rounds": 0, "fit_iterations": 1, "check": "warn", "solver": "dls",
               "template_labels": labels}
    subject, _, report = mocapsolve.fit_skeleton(take, cmu02["subject"], axes="y,z,x", **options)
    assert len(subject.marker_labels) == 27
    assert "RASI" in subject.marker_labels and "RFWT" not in subject.marker_labels
    assert "RWR" in subject.marker_labels and "LSH" not in subject.marker_labels
    assert report["template_labels"][0] == {"template": "LFWT", "take": "LASI"}
    assert len(report["template_labels"]) == 22
    cli, cli_report = str(tmp_path / "cli.json"), str(tmp_path / "cli_report.json")
    run_cli("fit_skeleton", "--template_subject=" + cmu02["subject"], "--markers=" + take, "--axes=y,z,x",
            "--out_subject=" + cli, "--report=" + cli_report, *cli_flags(options))
    ours = str(tmp_path / "py.json")
    mocapsolve.write_subject(ours, subject)
    assert open(ours, "rb").read() == open(cli, "rb").read()
    assert without_seconds(report) == without_seconds(json.load(open(cli_report)))


def test_bad_input_raises(cmu02, tmp_path):
    squat = data_file("c3d/squat.c3d")
    with pytest.raises(OSError, match="nothing.c3d"):
        mocapsolve.fit_skeleton(str(tmp_path / "nothing.c3d"), cmu02["subject"])
    with pytest.raises(OSError, match="nothing.json"):
        mocapsolve.fit_skeleton(squat, str(tmp_path / "nothing.json"))
    with pytest.raises(ValueError, match="both given"):
        mocapsolve.fit_skeleton(squat, cmu02["subject"], skeleton=cmu02["asf"])
    # No template at all is the shipped one; a skeleton without its marker set is an error.
    with pytest.raises(ValueError, match="required"):
        mocapsolve.fit_skeleton(squat, skeleton=cmu02["asf"])
    with pytest.raises(TypeError, match="fit_iteration"):
        mocapsolve.fit_skeleton(squat, cmu02["subject"], fit_iteration=3)


def test_settings_hold_the_cli_defaults():
    settings = mocapsolve.SkeletonFitSettings()
    assert (settings.fit_iterations, settings.attach_rounds, settings.attach_iterations) == (-1, -1, 6)
    assert (settings.min_bone_scale, settings.max_bone_scale, settings.max_skin_cm) == (0.8, 1.25, 12.0)
    assert settings.fit_outlier_mm == 200.0
    assert settings.check == "fail"
    settings.attach_rounds = 21
    with pytest.raises(ValueError, match=r"--attach_rounds: expected a value in \[-1, 20\], got 21"):
        settings.validate()
    for name in mocapsolve.SKELETON_FIT_OPTION_NAMES.split(","):
        assert name in mocapsolve.fit_skeleton.__doc__


def test_fit_skeleton_releases_the_gil(cmu02):
    """While a fit runs in another thread, this thread keeps running Python code: the longest
    pause between its ticks is a small part of the fit (with the GIL held it would be all of
    it). Without a progress callback, which takes the GIL for each event."""
    import concurrent.futures
    import time
    squat = data_file("c3d/squat.c3d")
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        start = time.perf_counter()
        future = pool.submit(mocapsolve.fit_skeleton, squat, cmu02["subject"], **SHORT)
        last, longest = start, 0.0
        while not future.done():
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        seconds = future.result()[2]["seconds"]
    assert longest < 0.5 * seconds, (longest, seconds)


def test_an_exception_in_the_progress_callback_reaches_the_caller(cmu02):
    squat = data_file("c3d/squat.c3d")

    def stop(event):
        if event["kind"] == "iteration":
            raise KeyboardInterrupt("stop")

    with pytest.raises(KeyboardInterrupt, match="stop"):
        mocapsolve.fit_skeleton(squat, cmu02["subject"], progress=stop, **SHORT)
