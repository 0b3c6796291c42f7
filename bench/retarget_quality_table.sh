#!/usr/bin/env bash
# The retarget quality table of BENCHMARKS.md ("Feet and rest poses"): CMU 131_02, 01_01
# (BVH) and 02_01 (ASF/AMC) onto the six shared humanoids through `evaluate --method=retarget`,
# one row per source and character (limb mean / p95, alignment, planted-foot skate,
# penetration, vertex error, tracked vertices on the least covered limb) and the count of
# pairs within each target (limbs 10 / 20 deg, skate <= 1 cm/s, penetration <= 1 cm). Extra
# arguments go to every evaluate call (e.g. --limb_direction_weight=0).
#
#   bench/retarget_quality_table.sh [WORK_DIR=/tmp/mocapsolve-retarget-quality] [-- FLAGS...]
# Environment: MOCAPSOLVE (binary, default build/bin/mocapsolve), MOCAPSOLVE_DATA (../shared/data).
set -euo pipefail
cd "$(dirname "$0")/.."
ms=${MOCAPSOLVE:-$PWD/build/bin/mocapsolve}
data=$(realpath "${MOCAPSOLVE_DATA:-../shared/data}")
work=$(realpath -m "${1:-/tmp/mocapsolve-retarget-quality}")
shift || true
if [ "${1:-}" = "--" ]; then shift; fi
g=$data/gltf
targets=$g/Xbot.glb,$g/Soldier.glb,$g/CesiumMan.glb,$g/Ely.glb,$g/RiggedFigure.glb,$g/RobotExpressive.glb
mkdir -p "$work"
run() {  # name, source flags...
  local name=$1; shift
  "$ms" evaluate --quiet --method=retarget "$@" --target="$targets" --table_csv="$work/$name.csv" "${extra[@]}" \
    >"$work/$name.log" 2>&1 || true
}
extra=("$@")
start=$(date +%s.%N)
run 131_02 --motion="$data/bvh/131_02.bvh"
run 01_01 --motion="$data/bvh/01_01.bvh"
run 02_01 --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf"
end=$(date +%s.%N)
/usr/bin/python3 - "$work" "$start" "$end" <<'PY'
import csv, json, sys
work, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows, met = [], {"limbs": 0, "skate": 0, "penetration": 0, "all": 0}
print("| source | character | limb mean (deg) | limb p95 (deg) | align (deg) | skate (cm/s) | penetration (cm) "
      "| vertex error (of height) | fewest limb vertices |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for take in ("131_02", "01_01", "02_01"):
    with open(f"{work}/{take}.csv") as f:
        for r in csv.DictReader(f):
            lm, lp = float(r["limb_mean_deg"]), float(r["limb_p95_deg"])
            sk, pe = float(r["foot_skate_cm_per_s"]), float(r["penetration_cm"])
            limbs, skate, pen = lm <= 10 and lp <= 20, sk <= 1.0, pe <= 1.0
            met["limbs"] += limbs; met["skate"] += skate; met["penetration"] += pen
            met["all"] += limbs and skate and pen
            print(f"| {take} | {r['character']} | {lm:.1f} | {lp:.1f} | {float(r['alignment_deg']):.1f} | "
                  f"{sk:.2f} | {pe:.1f} | {float(r['mean_vertex_error_fraction_of_height']):.4f} | "
                  f"{r['min_limb_vertices']} ({r['least_covered_limb']}) |")
            rows.append({"source": take, **r})
n = len(rows)
print(f"\nwithin: limbs 10/20 deg {met['limbs']}/{n}, skate <= 1 cm/s {met['skate']}/{n}, "
      f"penetration <= 1 cm {met['penetration']}/{n}, all three {met['all']}/{n}; {end - start:.1f} s")
with open(f"{work}/retarget_quality.jsonl", "w") as f:
    for r in rows: f.write(json.dumps(r) + "\n")
print(json.dumps({"benchmark": "retarget_quality_table", "pairs": n, **{k + "_met": v for k, v in met.items()}}))
PY
