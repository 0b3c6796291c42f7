#!/usr/bin/env bash
# `pipeline --subject=auto` on the shared takes, as a new user runs it: a raw C3D and a
# character, no subject (issue 32). Each take as delivered and with its labels renamed to
# meaningless ones (scripts/rename_c3d_labels.py: a protocol nobody mapped). Prints one
# table row per run (BENCHMARKS.md, "A subject on the fly") and one JSON line.
#   bench/auto_subject.sh OUTDIR [DATA_DIR] [take ...]   (MOCAPSOLVE_CLI: the CLI to run;
#   VARIANTS="lab renamed" by default)
set -uo pipefail
out=${1:?usage: $0 OUTDIR [DATA_DIR] [take ...]}
data=${2:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
shift $(( $# >= 2 ? 2 : 1 ))
takes=("$@")
[ ${#takes[@]} -gt 0 ] || takes=(cmu_02_05 02_01 squat JA1Gait35 nick_freeform_001)
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
rename=$(dirname "$0")/../scripts/rename_c3d_labels.py
mkdir -p "$out"
echo "| take | labels | exit | method | fit frames | fit s | marker RMS mm | torso deg | gate | total s | error |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for take in "${takes[@]}"; do
  /usr/bin/python3 "$rename" "$data/c3d/$take.c3d" "$out/${take}_renamed.c3d" >"$out/${take}_renamed.map"
  for variant in ${VARIANTS:-lab renamed}; do
    markers=$data/c3d/$take.c3d
    [ "$variant" = renamed ] && markers=$out/${take}_renamed.c3d
    dir=$out/$take.$variant
    rm -rf "$dir"
    start=$(date +%s.%N)
    $ms pipeline --quiet --subject=auto --markers="$markers" --character="$data/gltf/Xbot.glb" --out_dir="$dir" \
      --view=off >"$out/$take.$variant.log" 2>&1
    code=$?
    total=$(echo "$(date +%s.%N) - $start" | bc)
    /usr/bin/python3 - "$dir/report.json" "$take" "$variant" "$code" "$total" "$out/$take.$variant.log" <<'PY'
import json, os, sys
path, take, variant, code, total, log = sys.argv[1:]
row = {"take": take, "labels": variant, "exit": int(code), "total_s": round(float(total), 1)}
if os.path.exists(path):
    r = json.load(open(path))
    f = r["subject_fit"]
    row.update(method=f["method"], fit_frames=f["frames"], fit_s=round(f["seconds"], 1),
               rms_mm=round(f["checks"]["rms_mm"], 2), torso_deg=round(f["checks"]["torso_error_mean_deg"], 1),
               gate="pass" if r["quality_gate"]["pass"] else "FAIL: " + "; ".join(r["quality_gate"]["failures"]))
else:
    lines = [l for l in open(log).read().splitlines() if l.strip()]
    row["error"] = lines[-1] if lines else ""
print("| %s | %s | %d | %s | %s | %s | %s | %s | %s | %.1f | %s |" % (
    take, variant, row["exit"], row.get("method", "-"), row.get("fit_frames", "-"), row.get("fit_s", "-"),
    row.get("rms_mm", "-"), row.get("torso_deg", "-"), row.get("gate", "-"), row["total_s"], row.get("error", "")))
print(json.dumps(row), file=sys.stderr)
PY
  done
done
