#!/usr/bin/env python3
"""A marker repair, its repaired intervals plotted per marker.

CMU 02_01's markers get gaps punched into them with numpy (NaN = missing; the damaged
take is written to a C3D and read back), then `mocapsolve.repair` finds the broken
intervals against its robust reference and refills them. The plot shows, per marker,
the intervals the repair filled over the frames, and one refilled trajectory beside
the original.

  PYTHONPATH=build/python /usr/bin/python3 examples/python/repair_intervals.py --out=out/repair.png
"""
import argparse
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mocapsolve  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get("MOCAPSOLVE_DATA", "../shared/data"))
    parser.add_argument("--out", default="repair_intervals.png")
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args(argv)
    d = args.data
    c3d = os.path.join(d, "c3d/02_01.c3d")
    subject, _ = mocapsolve.calibrate(os.path.join(d, "amc/02_01.amc"), c3d,
                                      skeleton=os.path.join(d, "amc/02.asf"), axes="y,z,x")
    original = mocapsolve.read_markers(c3d)
    damaged = original.positions.copy()
    rng = np.random.default_rng(args.seed)
    frames, markers = damaged.shape[:2]
    punched = []
    for _ in range(12):  # Gaps of 10-60 frames in random markers.
        m = int(rng.integers(markers))
        length = int(rng.integers(10, 60))
        first = int(rng.integers(0, frames - length))
        damaged[first:first + length, m] = np.nan
        punched.append((original.labels[m], first, first + length - 1))
    take = mocapsolve.Markers(damaged, original.labels, original.rate, original.units)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "02_01_damaged.c3d")
        mocapsolve.write_markers(path, take)
        repaired, motion, report = mocapsolve.repair(subject, path)

    labels = subject.marker_labels
    fig, (ax_bars, ax_track) = plt.subplots(2, 1, figsize=(10, 9), gridspec_kw={"height_ratios": [3, 1]})
    colours = {}
    for row, label in enumerate(labels):
        ax_bars.axhline(row, color="0.9", lw=0.5, zorder=0)
    for interval in report["filled"]:
        row = labels.index(interval["marker"])
        what = interval["what"]
        colour = colours.setdefault(what, "C%d" % len(colours))
        ax_bars.barh(row, interval["last_frame"] - interval["first_frame"] + 1, left=interval["first_frame"],
                     height=0.7, color=colour, label=what)
    ax_bars.set_yticks(range(len(labels)))
    ax_bars.set_yticklabels(labels, fontsize=6)
    ax_bars.set_xlim(0, frames)
    ax_bars.set_xlabel("frame")
    ax_bars.set_title("02_01 with 12 punched gaps: %d intervals filled; RMS marker residual naive %.2f mm, "
                      "repaired %.2f mm" % (len(report["filled"]), report["rms_naive_mm"],
                                            report["rms_repaired_mm"]), fontsize=9)
    for label, first, last in punched:  # The gaps we punched, outlined.
        name = label.split(":")[-1]  # The file's labels carry a subject prefix.
        if name in labels:
            ax_bars.barh(labels.index(name), last - first + 1, left=first, height=0.9, fill=False,
                         edgecolor="k", lw=1.2, label="punched gap")
    handles, names = ax_bars.get_legend_handles_labels()
    unique = dict(zip(names, handles))
    ax_bars.legend(unique.values(), unique.keys(), fontsize=8, loc="upper right")
    # The longest punched gap: the refilled coordinates beside the original ones.
    label, first, last = max(punched, key=lambda g: g[2] - g[1])
    m = original.labels.index(label)
    r = repaired.labels.index(label)
    for k, axis in enumerate("xyz"):
        ax_track.plot(original.positions[:, m, k], color="0.6", lw=3, label="original" if k == 0 else None)
        ax_track.plot(repaired.positions[:, r, k], lw=1, label="repaired %s" % axis)
    ax_track.axvspan(first, last, color="C3", alpha=0.15)
    ax_track.set_xlim(max(0, first - 60), min(frames - 1, last + 60))
    ax_track.set_title("%s: punched gap at frames %d-%d (shaded), refilled" % (label, first, last), fontsize=9)
    ax_track.set_xlabel("frame")
    ax_track.set_ylabel(repaired.units)
    ax_track.legend(fontsize=7, ncol=4)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print("filled %d intervals; wrote %s" % (len(report["filled"]), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
