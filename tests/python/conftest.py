"""Shared fixtures of the Python module's tests.

Real data comes from MOCAPSOLVE_DATA (default ../shared/data beside the repository), as
tests/test_support.h finds it: a missing file skips the test, or fails it when
MOCAPSOLVE_REQUIRE_DATA=1. The command line (MOCAPSOLVE_CLI, default build/bin/mocapsolve)
gives the C++ results the bindings are compared with.
"""
import os
import subprocess

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def data_root():
    return os.environ.get("MOCAPSOLVE_DATA") or os.path.join(REPO, "..", "shared", "data")


def data_file(relative):
    """The path of a data file, or skip (fail under MOCAPSOLVE_REQUIRE_DATA=1)."""
    path = os.path.join(data_root(), relative)
    if os.path.isfile(path):
        return path
    if os.environ.get("MOCAPSOLVE_REQUIRE_DATA") == "1":
        pytest.fail("missing data file %s/%s (MOCAPSOLVE_REQUIRE_DATA=1)" % (data_root(), relative))
    pytest.skip("data file %s not found under %s (set MOCAPSOLVE_DATA)" % (relative, data_root()))


def cli_path():
    return os.environ.get("MOCAPSOLVE_CLI") or os.path.join(REPO, "build", "bin", "mocapsolve")


def run_cli(*arguments, expect=0):
    """Runs the command line; returns (exit code, stdout + stderr)."""
    result = subprocess.run([cli_path(), *arguments, "--quiet"], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    if expect is not None:
        assert result.returncode == expect, result.stdout
    return result.returncode, result.stdout


@pytest.fixture(scope="session")
def cmu02(tmp_path_factory):
    """CMU subject 2 calibrated on 02_01 by the CLI: dict of paths (subject, asf, c3d, ...)."""
    asf = data_file("amc/02.asf")
    amc = data_file("amc/02_01.amc")
    c3d = data_file("c3d/02_01.c3d")
    folder = tmp_path_factory.mktemp("cmu02")
    markerset = str(folder / "02.json")
    subject = str(folder / "S02.json")
    run_cli("calibrate", "--motion=" + amc, "--skeleton=" + asf, "--markers=" + c3d, "--axes=y,z,x",
            "--out=" + markerset, "--out_subject=" + subject)
    return {"asf": asf, "amc": amc, "c3d": c3d, "markerset": markerset, "subject": subject,
            "folder": folder}
