#!/usr/bin/env bash
# Repair a marker take that comes without a skeleton (issue 4: the natural-gap captures
# nick_freeform_001.c3d and squat.c3d, 53-marker Vicon set, Y-up mm).
#   scripts/repair_unskinned_take.sh TAKE.c3d OUTDIR [DATA_DIR]
# 1. The template: CMU subject 2 (02.asf, in cm) with its marker set calibrated on 02_01.
# 2. fit_skeleton: bone lengths + offsets of the template markers the take shares by name.
# 3. calibrate: every marker of the take attached to the fitted skeleton (auto attach).
# 4. fit_skeleton again with all of them, then repair.
set -euo pipefail
take=${1:?usage: $0 TAKE.c3d OUTDIR [DATA_DIR]}
out=${2:?usage: $0 TAKE.c3d OUTDIR [DATA_DIR]}
data=${3:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
name=$(basename "$take" .c3d)
mkdir -p "$out"
$ms convert "$data/amc/02_01.amc" "$out/template.bvh" --skeleton="$data/amc/02.asf" --scale=5.6444 >/dev/null
$ms calibrate --quiet --motion="$out/template.bvh" --skeleton_units=cm --markers="$data/c3d/02_01.c3d" \
  --axes=y,z,x --out="$out/template_markerset.json" >/dev/null
echo "== $name: fit the template's bones to the markers it shares with the take"
$ms fit_skeleton --quiet --solver=dls --fit_iterations=${FIT_ITERATIONS:-15} --skeleton="$out/template.bvh" \
  --skeleton_units=cm --markers="$take" --markerset="$out/template_markerset.json" \
  --out="$out/${name}_fit0.bvh" --out_markerset="$out/${name}_fit0.json" | head -1
echo "== $name: attach every marker of the take, fit again"
$ms calibrate --quiet --motion="$out/${name}_fit0.bvh" --skeleton_units=cm --markers="$take" \
  --out="$out/${name}_all.json" | tail -1
$ms fit_skeleton --quiet --solver=dls --fit_iterations=${FIT_ITERATIONS_ALL:-5} --skeleton="$out/${name}_fit0.bvh" \
  --skeleton_units=cm --markers="$take" --markerset="$out/${name}_all.json" \
  --out="$out/${name}_skeleton.bvh" --out_markerset="$out/${name}_markerset.json" | head -1
echo "== $name: repair"
$ms repair --quiet --skeleton="$out/${name}_skeleton.bvh" --skeleton_units=cm --markers="$take" \
  --markerset="$out/${name}_markerset.json" --out_markers="$out/${name}_repaired.c3d" \
  --out_motion="$out/${name}_repaired.bvh" --report="$out/${name}_repair.json"
