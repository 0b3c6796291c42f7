#!/usr/bin/env bash
# Do Ceres and DLS end each frame of a real take at the same cost? For the five real takes
# (02_01 on CMU subject 2 calibrated on it; cmu_02_05, squat, JA1Gait35 and nick_freeform_001
# on subjects fitted from it by fit_skeleton, as BENCHMARKS.md's leave-one-marker-out rows),
# `solve --compare_solvers` (defaults otherwise) and one line per take: frames whose final
# costs agree within 1 %, the worst frames, each solver's ms per frame and RMS.
#   bench/solver_agreement.sh OUTDIR [DATA_DIR]     (subjects are reused when OUTDIR has them)
set -euo pipefail
out=${1:?usage: $0 OUTDIR [DATA_DIR]}
data=${2:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
mkdir -p "$out"
if [ ! -f "$out/02_01.json" ]; then
  $ms calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" --markers="$data/c3d/02_01.c3d" \
    --axes=y,z,x --out_subject="$out/02_01.json" >/dev/null
fi
fit() {
  [ -f "$out/$1.json" ] && return 0
  $ms fit_skeleton --quiet --solver=dls --template_subject="$out/02_01.json" --markers="$data/c3d/$1.c3d" \
    --out_subject="$out/$1.json" "${@:2}" >/dev/null
}
fit cmu_02_05
fit squat
fit JA1Gait35 --axes=y,z,x
fit nick_freeform_001
echo "take | frames | within 1 % | worst frames (relative difference) | DLS ms/frame | Ceres ms/frame | RMS DLS / Ceres (mm)"
for take in 02_01 cmu_02_05 squat JA1Gait35 nick_freeform_001; do
  $ms solve --quiet --subject="$out/$take.json" --markers="$data/c3d/$take.c3d" --compare_solvers \
    --out="$out/$take.bvh" --report="$out/$take.agreement.json" >/dev/null
  /usr/bin/python3 - "$take" "$out/$take.agreement.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[2]))["solver_agreement"]
worst = ", ".join("%d (%.3g)" % (f["frame"], f["relative_difference"]) for f in a["worst_frames"][:5]) or "-"
print("%s | %d | %d (%.2f %%) | %s | %.4f | %.4f | %.3f / %.3f" % (
    sys.argv[1], a["frames_compared"], a["frames_within"], 100 * a["fraction_within"], worst,
    a["dls_ms_per_frame"], a["ceres_ms_per_frame"], a["dls_rms_marker_residual"], a["ceres_rms_marker_residual"]))
PY
done
