#!/usr/bin/env python3
"""An independent damage model for marker takes (numpy only; not `mocapsolve corrupt`).

What it does to a clean take, seeded:
  * soft-tissue wobble: damped oscillations of a few mm (4-12 Hz, 0.1-0.3 s decay) started
    at random times on random markers. Wobble is the skin's real motion, so it is part of
    the ground truth, not of the damage the repair should undo;
  * occlusions by body part: every marker of one segment (a foot, a hand, the head, found
    by label) missing together for 30-90 frames;
  * swaps between two nearby markers of different bones: labels exchanged for 20-100 frames.
    "Different bones" is judged from the take itself: the distance between the two markers
    varies (its standard deviation over the take exceeds --rigid_std_mm), so no rigid body
    carries both. "Nearby": median distance below --swap_near_mm. A share of the swaps begins
    or ends inside a gap of one of the two markers (3-15 frames hiding the exchange).
Events on a marker keep --spacing frames from each other and from the take's ends.

The mask (frames x markers, int8), per marker (not label): 0 untouched, 1 occluded
(segment), 2 swapped (its sample present, under the other label), 3 lost around a swap
(its sample was under a label the gap hides), 4 wobble only (truth moved).

usage: damage.py --markers=take.c3d --out=bad.c3d --truth_out=truth.c3d --mask_out=mask.csv
                 [--seed=1 --occlusions=6 --swaps=6 --wobbles=20 --events_out=events.json]
The module functions (damage(), segment_groups(), cross_bone_pairs()) are used by
scripts/score_damage.py on arrays.
"""
import argparse
import json
import re
import sys

import numpy as np

CLEAN, OCCLUDED, SWAPPED, SWAP_GAP, WOBBLE = 0, 1, 2, 3, 4

# Segments by label (CMU's 41-marker set and the 53-marker Vicon set share these names).
SEGMENT_PATTERNS = {
    "left foot": r"^L(HEE|TOE|MT5|MT1|ANK|FOOT)$",
    "right foot": r"^R(HEE|TOE|MT5|MT1|ANK|FOOT)$",
    "left hand": r"^L(WRA|WRB|FIN|THMB|HAND|WRT)$",
    "right hand": r"^R(WRA|WRB|FIN|THMB|HAND|WRT)$",
    "head": r"^(LFHD|RFHD|LBHD|RBHD|ARIEL|HEAD)$",
}


def bare_label(label):
    return label.split(":")[-1].upper()


def segment_groups(labels):
    """{segment name: [marker indices]} for the segments with at least two markers."""
    groups = {}
    for name, pattern in SEGMENT_PATTERNS.items():
        members = [i for i, l in enumerate(labels) if re.match(pattern, bare_label(l))]
        if len(members) >= 2:
            groups[name] = members
    return groups


def cross_bone_pairs(positions, metres_per_unit, near_mm=250.0, rigid_std_mm=8.0):
    """Pairs (a, b), a < b, whose median distance is below near_mm and whose distance's
    standard deviation over the frames where both are present exceeds rigid_std_mm."""
    mm = metres_per_unit * 1000.0
    pairs = []
    m = positions.shape[1]
    for a in range(m):
        for b in range(a + 1, m):
            d = np.linalg.norm(positions[:, a] - positions[:, b], axis=1) * mm
            d = d[np.isfinite(d)]
            if len(d) > 10 and np.median(d) < near_mm and np.std(d) > rigid_std_mm:
                pairs.append((a, b))
    return pairs


def _free(busy, markers, first, last, spacing):
    lo, hi = max(0, first - spacing), min(busy.shape[0], last + spacing + 1)
    return not busy[lo:hi, markers].any()


def _wobble(rng, truth, mask, count, mm_per_unit, rate):
    frames = truth.shape[0]
    for _ in range(count):
        m = rng.integers(truth.shape[1])
        start = rng.integers(frames)
        amplitude = rng.uniform(2.0, 6.0) / mm_per_unit
        frequency = rng.uniform(4.0, 12.0)
        decay = rng.uniform(0.1, 0.3)
        t = np.arange(frames - start) / rate
        envelope = amplitude * np.exp(-t / decay) * np.sin(2 * np.pi * frequency * t)
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        length = min(len(t), int(5 * decay * rate) + 1)
        truth[start:start + length, m] += envelope[:length, None] * direction
        touched = mask[start:start + length, m] == CLEAN
        mask[start:start + length, m][touched] = WOBBLE


def damage(positions, labels, metres_per_unit, rate, seed=1, occlusions=6, swaps=6, wobbles=20,
           gap_min=30, gap_max=90, swap_min=20, swap_max=100, swap_in_gap=0.5, spacing=10,
           near_mm=250.0, rigid_std_mm=8.0):
    """Returns (truth, damaged, mask, events). positions: (frames, markers, 3), NaN = missing,
    in the take's unit. Truth is the take plus wobble, rounded to float32 (as a C3D stores it)
    so that a swapped sample restored bit for bit compares equal."""
    rng = np.random.default_rng(seed)
    mm_per_unit = metres_per_unit * 1000.0
    frames, num_markers, _ = positions.shape
    truth = positions.astype(np.float64).copy()
    mask = np.zeros((frames, num_markers), dtype=np.int8)
    _wobble(rng, truth, mask, wobbles, mm_per_unit, rate)
    truth = truth.astype(np.float32).astype(np.float64)
    damaged = truth.copy()
    busy = ~np.isfinite(truth[:, :, 0])  # Samples already missing or damaged.
    events = []
    groups = segment_groups(labels)
    names = sorted(groups)
    for _ in range(occlusions if names else 0):
        for _attempt in range(50):
            name = names[rng.integers(len(names))]
            members = groups[name]
            length = int(rng.integers(gap_min, gap_max + 1))
            if frames < length + 2 * spacing + 2:
                break
            first = int(rng.integers(spacing, frames - spacing - length))
            last = first + length - 1
            if _free(busy, members, first, last, spacing):
                damaged[first:last + 1, members] = np.nan
                mask[first:last + 1, members] = OCCLUDED
                busy[first:last + 1, members] = True
                events.append({"kind": "occlusion", "segment": name, "markers": [labels[i] for i in members],
                               "first_frame": first, "last_frame": last})
                break
    pairs = cross_bone_pairs(truth, metres_per_unit, near_mm, rigid_std_mm)
    for _ in range(swaps if pairs else 0):
        for _attempt in range(50):
            a, b = pairs[rng.integers(len(pairs))]
            length = int(rng.integers(swap_min, swap_max + 1))
            if frames < length + 2 * spacing + 40:
                break
            first = int(rng.integers(spacing + 20, frames - spacing - length - 20))
            last = first + length - 1
            hide = None
            if rng.uniform() < swap_in_gap:  # A gap of one marker hides the start or the end.
                who = (a, b)[rng.integers(2)]
                k = int(rng.integers(3, 16))
                at_start = rng.uniform() < 0.5
                edge = first if at_start else last
                lo = edge - int(rng.integers(1, k))
                hide = (who, lo, lo + k - 1, "start" if at_start else "end")
            lo = first if hide is None else min(first, hide[1])
            hi = last if hide is None else max(last, hide[2])
            if not _free(busy, [a, b], lo, hi, spacing):
                continue
            damaged[first:last + 1, a], damaged[first:last + 1, b] = (truth[first:last + 1, b].copy(),
                                                                      truth[first:last + 1, a].copy())
            mask[first:last + 1, [a, b]] = SWAPPED
            if hide is not None:  # Label `who` loses its samples: outside the swap its own
                who, g0, g1, _ = hide  # marker's, inside it the other marker's.
                other = b if who == a else a
                damaged[g0:g1 + 1, who] = np.nan
                for f in range(g0, g1 + 1):
                    mask[f, other if first <= f <= last else who] = SWAP_GAP
            busy[lo:hi + 1, [a, b]] = True
            event = {"kind": "swap", "markers": [labels[a], labels[b]], "first_frame": first, "last_frame": last}
            if hide is not None:
                event.update({"gap_marker": labels[hide[0]], "gap_first_frame": hide[1],
                              "gap_last_frame": hide[2], "gap_hides": hide[3]})
            events.append(event)
            break
    return truth, damaged, mask, events


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--markers", required=True)
    parser.add_argument("--out", required=True, help="damaged take (.c3d or .trc)")
    parser.add_argument("--truth_out", required=True, help="the take with its wobble: the ground truth")
    parser.add_argument("--mask_out", required=True, help="CSV, frames x markers, codes in the docstring")
    parser.add_argument("--events_out", default="")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--occlusions", type=int, default=6)
    parser.add_argument("--swaps", type=int, default=6)
    parser.add_argument("--wobbles", type=int, default=20)
    args = parser.parse_args()
    import mocapsolve
    markers = mocapsolve.read_markers(args.markers)
    truth, damaged, mask, events = damage(np.array(markers.positions), markers.labels, markers.metres_per_unit,
                                          markers.rate, seed=args.seed, occlusions=args.occlusions,
                                          swaps=args.swaps, wobbles=args.wobbles)
    for path, values in ((args.truth_out, truth), (args.out, damaged)):
        out = mocapsolve.Markers(values, markers.labels, markers.rate, markers.units)
        out.first_frame = markers.first_frame
        mocapsolve.write_markers(path, out)
    np.savetxt(args.mask_out, mask, fmt="%d", delimiter=",", header=",".join(markers.labels))
    if args.events_out:
        with open(args.events_out, "w") as f:
            json.dump(events, f, indent=1)
    print("%d occlusions, %d swaps, %d wobbled samples -> %s" % (
        sum(e["kind"] == "occlusion" for e in events), sum(e["kind"] == "swap" for e in events),
        int((mask == WOBBLE).sum()), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
