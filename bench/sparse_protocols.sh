#!/usr/bin/env bash
# Sparse gait-lab protocols (issue 32): each full-body shared capture cut to the markers of
# Plug-in Gait lower body (16) and of BTS DAVIS / Helen Hayes (18, BTS labels:
# bench/sparse_protocol.py), written as C3D by `mocapsolve convert` under OUTDIR (nothing
# goes into the repository). Per take: `fit_skeleton --fit_max_frames=600 --check=warn`
# (association or labels, as the data decide; the subject scored by
# bench/tools/score_sparse_protocol.py) and `pipeline --subject=auto --character=Xbot.glb`.
# Prints one table row per take (BENCHMARKS.md, "Sparse gait-lab protocols").
#   bench/sparse_protocols.sh OUTDIR [DATA_DIR] [take ...]   (MOCAPSOLVE_CLI: the CLI)
set -uo pipefail
out=${1:?usage: $0 OUTDIR [DATA_DIR] [take ...]}
data=${2:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
shift $(( $# >= 2 ? 2 : 1 ))
takes=("$@")
[ ${#takes[@]} -gt 0 ] || takes=(JA1Gait35 squat nick_freeform_001)
here=$(dirname "$0")
ms=${MOCAPSOLVE_CLI:-$here/../build/bin/mocapsolve}
mkdir -p "$out"
echo "| take | protocol | fit exit | fit RMS mm | checks | right/total | held | pipeline exit | pipeline |"
echo "|---|---|---|---|---|---|---|---|---|"
for take in "${takes[@]}"; do
  "$ms" convert --quiet "$data/c3d/$take.c3d" "$out/$take.trc" >/dev/null 2>&1
  for protocol in ${PROTOCOLS:-pig_lower davis_bts}; do
    name=${take}_$protocol
    /usr/bin/python3 "$here/sparse_protocol.py" "$out/$take.trc" "$out/$name.trc" --protocol="$protocol" >/dev/null
    "$ms" convert --quiet "$out/$name.trc" "$out/$name.c3d" >/dev/null 2>&1
    "$ms" fit_skeleton --quiet --markers="$out/$name.c3d" --fit_max_frames=600 --check=warn \
      --out_subject="$out/$name.subject.json" --report="$out/$name.fit.json" >"$out/$name.fit.log" 2>&1
    fit_code=$?
    rm -rf "$out/$name.pipeline"
    "$ms" pipeline --quiet --subject=auto --markers="$out/$name.c3d" --character="$data/gltf/Xbot.glb" \
      --out_dir="$out/$name.pipeline" --view=off >"$out/$name.pipeline.log" 2>&1
    code=$?
    score=$(/usr/bin/python3 "$here/tools/score_sparse_protocol.py" "$out/$name.subject.json" 2>/dev/null || echo "-")
    /usr/bin/python3 - "$out/$name.fit.json" "$take" "$protocol" "$fit_code" "$code" "$score" \
      "$out/$name.pipeline.log" "$out/$name.pipeline/report.json" <<'PY'
import json, os, sys
fit, take, protocol, fit_code, code, score, log, report = sys.argv[1:]
r = json.load(open(fit)) if os.path.exists(fit) else {}
checks = r.get("checks", {})
held = r.get("held_segments", {})
held_text = ", ".join(held.get("tops", [])) + (" (%d joints)" % held["joints"] if held.get("tops") else "")
if os.path.exists(report):
    p = json.load(open(report))
    piped = "gate " + ("pass" if p["quality_gate"]["pass"] else "FAIL: " + "; ".join(p["quality_gate"]["failures"]))
else:
    lines = [l for l in open(log).read().splitlines() if l.strip()]
    piped = lines[-1] if lines else ""
print("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
    take, protocol, fit_code, "%.2f" % r["rms_mm"] if "rms_mm" in r else "-",
    ("pass" if checks.get("passed", checks.get("ok")) else "FAIL") if checks else "-", score, held_text or "-",
    code, piped.replace("|", "/")))
PY
  done
done
