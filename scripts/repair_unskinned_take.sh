#!/usr/bin/env bash
# Repair a marker take that comes without a skeleton (issue 4: the natural-gap captures
# nick_freeform_001.c3d and squat.c3d, 53-marker Vicon set, Y-up mm).
#   scripts/repair_unskinned_take.sh TAKE.c3d OUTDIR [DATA_DIR]
# 1. The template: CMU subject 2 (02.asf, in cm) with its marker set calibrated on 02_01.
# 2. fit_skeleton: bone lengths + offsets of the template markers the take shares by name.
# 3. calibrate: every marker of the take attached to the fitted skeleton (auto attach),
#    then fit_skeleton again with all of them; three rounds (ATTACH_ROUNDS).
# 4. repair.
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
# Attach every marker (auto: the joint it moves least with) and fit again; each round's
# better motion gives better attachments (squat: 28.6 -> 10.5 -> ... mm).
prev="$out/${name}_fit0.bvh"
for round in $(seq 1 ${ATTACH_ROUNDS:-3}); do
  echo "== $name: attach every marker of the take, fit again (round $round)"
  $ms calibrate --quiet --motion="$prev" --skeleton_units=cm --markers="$take" \
    --out="$out/${name}_all$round.json" | tail -1
  $ms fit_skeleton --quiet --solver=dls --fit_iterations=${FIT_ITERATIONS_ALL:-6} --skeleton="$prev" \
    --skeleton_units=cm --markers="$take" --markerset="$out/${name}_all$round.json" \
    --out="$out/${name}_fit$round.bvh" --out_markerset="$out/${name}_fit$round.json" | head -1
  prev="$out/${name}_fit$round.bvh"
done
cp "$prev" "$out/${name}_skeleton.bvh"
cp "${prev%.bvh}.json" "$out/${name}_markerset.json"
echo "== $name: repair"
$ms repair --quiet --skeleton="$out/${name}_skeleton.bvh" --skeleton_units=cm --markers="$take" \
  --markerset="$out/${name}_markerset.json" --out_markers="$out/${name}_repaired.c3d" \
  --out_motion="$out/${name}_repaired.bvh" --report="$out/${name}_repair.json"
