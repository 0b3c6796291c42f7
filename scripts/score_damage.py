#!/usr/bin/env python3
"""Scores `mocapsolve.repair` on the independent damage of scripts/damage.py.

Per take and seed: damage the clean take, repair it through the Python module, and compare
with the ground truth (the take plus its wobble), in mm:
  * occlusions: the refilled markers' error per segment kind (mean, 95th percentile, max),
    beside a naive fill (each marker's gap a cubic Hermite between its edge samples, edge
    velocities by one-sided differences);
  * swaps: the share of swapped samples restored bit for bit (equal to the truth in all
    three coordinates), and their mean error;
  * overall: mean error over every damaged sample, repair against naive (which leaves the
    swapped samples as they are), and the ratio; also over the occluded samples alone.

With --misses, every swapped sample not restored bit for bit is listed, in runs per seed and
marker: the swap (labels, frames, the gap that hides its start or end), where the run lies
in it, and what the repair did: "left swapped" (the sample stayed under the other label),
"relabelled, then cut" (the repair moved it back, then cut and refilled it, with the cause
of the detected interval) or "cut" (refilled without having been relabelled).

usage: score_damage.py --subject=S02.json --markers=02_01.c3d[,cmu_02_05.c3d] [--seeds=1,2,3]
                       [--max_frames=N] [--repair key=value ...] [--json_out=scores.json] [--misses]
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import damage as damage_model  # noqa: E402

SWAPPED_CODE = damage_model.SWAPPED


def hermite_fill(x):
    """Each marker's interior gaps filled by a cubic Hermite, ends held; x: (frames, markers, 3)."""
    out = x.copy()
    frames = x.shape[0]
    for m in range(x.shape[1]):
        valid = np.isfinite(x[:, m, 0])
        if not valid.any():
            continue
        f = 0
        while f < frames:
            if valid[f]:
                f += 1
                continue
            g = f
            while g < frames and not valid[g]:
                g += 1
            a, b = f - 1, g  # Last valid before, first valid after.
            if a < 0 or b >= frames:
                out[f:g, m] = x[b if a < 0 else a, m]
            else:
                p0, p1 = x[a, m], x[b, m]
                v0 = p0 - x[a - 1, m] if a >= 1 and valid[a - 1] else p1 - p0
                v1 = x[b + 1, m] - p1 if b + 1 < frames and valid[b + 1] else p1 - p0
                n = b - a
                v0, v1 = v0 * n, v1 * n
                if a < 1 or not valid[a - 1]:
                    v0 = p1 - p0
                if b + 1 >= frames or not valid[b + 1]:
                    v1 = p1 - p0
                for k in range(f, g):
                    t = (k - a) / n
                    h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
                    h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
                    out[k, m] = h00 * p0 + h10 * v0 + h01 * p1 + h11 * v1
            f = g
    return out


def stats(errors):
    if len(errors) == 0:
        return {"n": 0}
    return {"n": int(len(errors)), "mean": float(np.mean(errors)), "p95": float(np.percentile(errors, 95)),
            "max": float(np.max(errors))}


def score_one(subject, markers, seed, options, repair_kwargs):
    import mocapsolve
    clean = np.array(markers.positions)
    truth, damaged, mask, events = damage_model.damage(clean, markers.labels, markers.metres_per_unit, markers.rate,
                                                       seed=seed, **options)
    bad = mocapsolve.Markers(damaged, markers.labels, markers.rate, markers.units)
    repaired_markers, _, report = mocapsolve.repair(subject, bad, **repair_kwargs)
    repaired = np.array(repaired_markers.positions)
    naive = hermite_fill(damaged)
    mm = markers.metres_per_unit * 1000.0
    err = np.linalg.norm(repaired - truth, axis=2) * mm
    naive_err = np.linalg.norm(naive - truth, axis=2) * mm
    result = {"seed": seed, "events": events, "segments": {}}
    for e in events:
        if e["kind"] != "occlusion":
            continue
        idx = [markers.labels.index(l) for l in e["markers"]]
        sl = slice(e["first_frame"], e["last_frame"] + 1)
        seg = result["segments"].setdefault(e["segment"], {"repair": [], "naive": []})
        seg["repair"] += list(err[sl, idx].ravel())
        seg["naive"] += list(naive_err[sl, idx].ravel())
    swapped = mask == damage_model.SWAPPED
    exact = np.all(repaired == truth, axis=2)
    result["swapped_samples"] = int(swapped.sum())
    result["swapped_exact"] = int((exact & swapped).sum())
    result["swapped_close"] = int((swapped & (err < 1e-3)).sum())
    result["swap_err"] = list(err[swapped])
    damaged_any = np.isin(mask, [damage_model.OCCLUDED, damage_model.SWAPPED, damage_model.SWAP_GAP])
    occluded = mask == damage_model.OCCLUDED
    result["all"] = (list(err[damaged_any]), list(naive_err[damaged_any]))
    result["occluded"] = (list(err[occluded]), list(naive_err[occluded]))
    result["carried"] = report.get("carried_joints", [])
    result["misses"] = swap_misses(markers.labels, events, mask, damaged, repaired, truth, err, report)
    return result


def _covering(intervals, label, f):
    label = label.split(":")[-1]
    return sorted({i["what"] for i in intervals
                   if i["marker"].split(":")[-1] == label and i["first_frame"] <= f <= i["last_frame"]})


def swap_misses(labels, events, mask, damaged, repaired, truth, err, report):
    """Runs of swapped samples not restored bit for bit, per marker, with what the repair did."""
    relabelled = {}  # (frame, label) -> label it was renamed from.
    for swap in report.get("swaps", []):
        for pair in swap["markers_renamed_from_to"]:
            for f in range(swap["first_frame"], swap["last_frame"] + 1):
                relabelled[(f, pair["to"].split(":")[-1])] = pair["from"]
    runs = []
    for e in events:
        if e["kind"] != "swap":
            continue
        a, b = (labels.index(l) for l in e["markers"])
        for col, other in ((a, b), (b, a)):
            current = None
            for f in range(e["first_frame"], e["last_frame"] + 1):
                if mask[f, col] != SWAPPED_CODE or np.all(repaired[f, col] == truth[f, col]):
                    current = None
                    continue
                if np.all(repaired[f, col] == damaged[f, col]):
                    what = "left swapped"
                elif (f, labels[col].split(":")[-1]) in relabelled:
                    what = "relabelled, then cut: " + "+".join(_covering(report.get("detected", []), labels[col], f))
                else:
                    what = "cut: " + "+".join(_covering(report.get("detected", []), labels[col], f))
                if current is not None and current["what"] == what and current["last"] == f - 1:
                    current["last"] = f
                    current["err"].append(float(err[f, col]))
                    continue
                current = {"marker": labels[col], "other": labels[other], "first": f, "last": f, "what": what,
                           "err": [float(err[f, col])], "swap": [e["first_frame"], e["last_frame"]],
                           "gap": [e.get("gap_marker"), e.get("gap_first_frame"), e.get("gap_last_frame")]}
                runs.append(current)
    for r in runs:
        r["mean_err_mm"] = float(np.mean(r.pop("err")))
    return runs


def print_misses(results):
    for r in results:
        for m in r["misses"]:
            gap = "" if m["gap"][0] is None else ", gap of %s %d-%d" % tuple(m["gap"])
            print("  seed %d: %s (swapped with %s over %d-%d%s): frames %d-%d (%d), %s; error %.1f mm" % (
                r["seed"], m["marker"], m["other"], m["swap"][0], m["swap"][1], gap, m["first"], m["last"],
                m["last"] - m["first"] + 1, m["what"], m["mean_err_mm"]))


def summarize(name, results):
    out = {"take": name}
    segs = {}
    for r in results:
        for s, v in r["segments"].items():
            d = segs.setdefault(s, {"repair": [], "naive": []})
            d["repair"] += v["repair"]
            d["naive"] += v["naive"]
    out["segments"] = {s: {"repair": stats(np.array(v["repair"])), "naive": stats(np.array(v["naive"]))}
                       for s, v in sorted(segs.items())}
    swapped = sum(r["swapped_samples"] for r in results)
    exact = sum(r["swapped_exact"] for r in results)
    close = sum(r["swapped_close"] for r in results)
    out["swaps"] = {"events": sum(sum(e["kind"] == "swap" for e in r["events"]) for r in results),
                    "samples": swapped, "exact": exact, "exact_share": exact / swapped if swapped else None,
                    "within_1um_share": close / swapped if swapped else None,
                    "error": stats(np.concatenate([np.array(r["swap_err"]) for r in results]))}
    for key in ("all", "occluded"):
        rep = np.concatenate([np.array(r[key][0]) for r in results])
        nai = np.concatenate([np.array(r[key][1]) for r in results])
        out[key] = {"repair_mean_mm": float(rep.mean()), "naive_mean_mm": float(nai.mean()),
                    "ratio": float(nai.mean() / rep.mean()) if rep.mean() > 0 else None}
    return out


def print_summary(s):
    print("== %s" % s["take"])
    for seg, v in s["segments"].items():
        print("  occluded %-10s repair mean %6.2f p95 %6.2f max %6.2f mm | naive mean %6.2f mm (%d samples)" % (
            seg, v["repair"]["mean"], v["repair"]["p95"], v["repair"]["max"], v["naive"]["mean"], v["repair"]["n"]))
    w = s["swaps"]
    if w["samples"]:
        print("  swaps: %d events, %d/%d swapped samples restored bit for bit (%.2f %%; within 1 um %.2f %%), "
              "mean error %.2f mm" % (w["events"], w["exact"], w["samples"], 100.0 * w["exact_share"],
                                      100.0 * w["within_1um_share"], w["error"]["mean"]))
    for key in ("occluded", "all"):
        v = s[key]
        print("  %-8s repair %.2f mm, naive %.2f mm: %.2fx" % (key, v["repair_mean_mm"], v["naive_mean_mm"],
                                                             v["ratio"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--subject", required=True)
    parser.add_argument("--markers", required=True, help="comma-separated takes")
    parser.add_argument("--seeds", default="1,2,3")
    parser.add_argument("--max_frames", type=int, default=0)
    parser.add_argument("--occlusions", type=int, default=6)
    parser.add_argument("--swaps", type=int, default=6)
    parser.add_argument("--wobbles", type=int, default=20)
    parser.add_argument("--repair", nargs="*", default=[], help="repair keywords, key=value")
    parser.add_argument("--json_out", default="")
    parser.add_argument("--misses", action="store_true", help="list the swapped samples not restored")
    args = parser.parse_args()
    import mocapsolve
    subject = mocapsolve.read_subject(args.subject)
    kwargs = {}
    for kv in args.repair:
        k, v = kv.split("=", 1)
        kwargs[k] = {"true": True, "false": False}.get(v.lower(), v)
        try:
            kwargs[k] = float(v) if "." in v else int(v)
        except ValueError:
            pass
    options = {"occlusions": args.occlusions, "swaps": args.swaps, "wobbles": args.wobbles}
    summaries = []
    for path in args.markers.split(","):
        markers = mocapsolve.read_markers(path)
        if args.max_frames and markers.num_frames > args.max_frames:
            markers = mocapsolve.Markers(np.array(markers.positions)[:args.max_frames], markers.labels,
                                         markers.rate, markers.units)
        results = [score_one(subject, markers, int(s), options, kwargs) for s in args.seeds.split(",")]
        summary = summarize(os.path.basename(path), results)
        print_summary(summary)
        if args.misses:
            print_misses(results)
        summaries.append(summary)
    if args.json_out:
        with open(args.json_out, "w") as f:
            json.dump(summaries, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
