#!/usr/bin/env bash
# Repair a marker take that comes without a skeleton (issue 4: the natural-gap captures
# nick_freeform_001.c3d and squat.c3d, 53-marker Vicon set, Y-up mm).
#   scripts/repair_unskinned_take.sh TAKE.c3d OUTDIR [DATA_DIR]
# 1. The template subject: CMU subject 2 (02.asf) with its marker set calibrated on 02_01.
# 2. fit_skeleton: bone lengths and offsets fitted on the markers the take shares with the
#    template by name (after the shipped label map for the take's protocol,
#    examples/vicon53_to_cmu_labels.txt), then every marker of the take attached and fitted
#    again (the attach rounds run inside the command), on the whole take, checked: exit 1 if
#    the fit is implausible (FIT_FLAGS="--check=warn" to go on, "--fit_max_frames=600" for a
#    quicker fit on the first frames).
# 3. repair with the fitted subject.
set -euo pipefail
take=${1:?usage: $0 TAKE.c3d OUTDIR [DATA_DIR]}
out=${2:?usage: $0 TAKE.c3d OUTDIR [DATA_DIR]}
data=${3:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
name=$(basename "$take" .c3d)
mkdir -p "$out"
$ms calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" --markers="$data/c3d/02_01.c3d" \
  --axes=y,z,x --out="$out/template_markerset.json" --out_subject="$out/S02.json" >/dev/null
echo "== $name: fit the template subject to the take (attach rounds inside)"
$ms fit_skeleton --solver=dls --template_subject="$out/S02.json" --markers="$take" \
  --out_subject="$out/${name}_subject.json" --out="$out/${name}_fit.bvh" --report="$out/${name}_fit.json" \
  ${FIT_FLAGS:-}
echo "== $name: repair"
$ms repair --quiet --subject="$out/${name}_subject.json" --markers="$take" \
  --out_markers="$out/${name}_repaired.c3d" --out_motion="$out/${name}_repaired.bvh" --report="$out/${name}_repair.json"
