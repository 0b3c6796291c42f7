"""The examples of examples/python run on the real data and write their plots."""
import importlib.util
import os

import pytest

from conftest import REPO, data_file, data_root


def load_example(name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(REPO, "examples", "python", name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name,needs", [
    ("ceres_vs_dls", ["amc/02.asf", "amc/02_01.amc", "c3d/02_01.c3d"]),
    ("repair_intervals", ["amc/02.asf", "amc/02_01.amc", "c3d/02_01.c3d"]),
    ("edit_falloff", ["bvh/16_15.bvh"]),
])
def test_example_writes_its_plot(tmp_path, name, needs):
    for relative in needs:
        data_file(relative)
    out = str(tmp_path / (name + ".png"))
    assert load_example(name).main(["--data=" + data_root(), "--out=" + out]) == 0
    assert os.path.getsize(out) > 10000
    with open(out, "rb") as png:
        assert png.read(8) == b"\x89PNG\r\n\x1a\n"
