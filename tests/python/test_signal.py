"""Pyramids: filter, bands and blend against the command line; pyramid round trip."""
import numpy as np
import pytest

import mocapsolve
from conftest import data_file, run_cli


def test_filter_and_bands_match_the_cli(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh)
    for name, result, flags in [
            ("filter", mocapsolve.filter(motion, levels=2), ["--levels=2"]),
            ("bands", mocapsolve.bands(motion, [2.0, 1.5, 0.0, 1.0]), ["--weights=2,1.5,0,1"])]:
        ours = str(tmp_path / (name + "_py.bvh"))
        mocapsolve.write_motion(ours, skeleton, result)
        cli = str(tmp_path / (name + "_cli.bvh"))
        run_cli(name, "--motion=" + bvh, "--out=" + cli, *flags)
        assert open(ours).read() == open(cli).read(), name


def test_filter_markers_keeps_missing_samples():
    markers = mocapsolve.read_markers(data_file("c3d/02_01.c3d"))
    filtered = mocapsolve.filter(markers, levels=1)
    assert isinstance(filtered, mocapsolve.Markers)
    assert np.array_equal(np.isnan(filtered.positions), np.isnan(markers.positions))


def test_pyramid_round_trip_and_errors():
    t = np.linspace(0, 4 * np.pi, 257)
    signal = np.stack([np.sin(t), np.cos(3 * t)], axis=1)
    laplacian, gaussian = mocapsolve.laplacian_pyramid(signal, levels=4)
    assert len(laplacian) == 4 and len(gaussian) == 4 and laplacian[0].shape == signal.shape
    back = mocapsolve.reconstruct_signal(laplacian, gaussian[-1], [1, 1, 1, 1, 1])
    assert np.allclose(back, signal, atol=1e-12)
    with pytest.raises(ValueError, match="--kernel_a"):
        mocapsolve.laplacian_pyramid(signal, kernel_a=2.0)
    with pytest.raises(ValueError, match="--levels must be in"):
        mocapsolve.filter(mocapsolve.read_motion(data_file("bvh/16_15.bvh"))[1], levels=0)


def test_blend_two_clips(tmp_path):
    bvh = data_file("bvh/16_15.bvh")
    skeleton, motion = mocapsolve.read_motion(bvh)
    blended = mocapsolve.blend(motion, motion, b_offset=100, transition_start=120, transition_end=160)
    assert blended.num_frames > 0
    ours = str(tmp_path / "py.bvh")
    mocapsolve.write_motion(ours, skeleton, blended)
    cli = str(tmp_path / "cli.bvh")
    run_cli("blend", "--a=" + bvh, "--b=" + bvh, "--transition=120:160", "--b_start=100", "--out=" + cli)
    assert open(ours).read() == open(cli).read()
