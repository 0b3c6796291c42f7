#!/usr/bin/env bash
# The subjects the labelling benchmarks (bench/label_benchmarks.cc) label each take with:
# 02_01's calibrated on it (CMU subject 2), the other four fitted from it by fit_skeleton
# (as BENCHMARKS.md's leave-one-marker-out rows).
#   bench/label_subjects.sh OUTDIR [DATA_DIR]   then MOCAPSOLVE_LABEL_SUBJECTS=OUTDIR
set -euo pipefail
out=${1:?usage: $0 OUTDIR [DATA_DIR]}
data=${2:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
mkdir -p "$out"
$ms calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" --markers="$data/c3d/02_01.c3d" \
  --axes=y,z,x --out="$out/02_01_markerset.json" --out_subject="$out/02_01.json" >/dev/null
fit() { $ms fit_skeleton --quiet --solver=dls --template_subject="$out/02_01.json" --markers="$data/c3d/$1.c3d" \
  --out_subject="$out/$1.json" "${@:2}" >/dev/null; }
fit cmu_02_05 --axes=y,z,x
fit squat --fit_max_frames=600
fit JA1Gait35 --axes=y,z,x
fit nick_freeform_001 --fit_max_frames=600 --check=warn
echo "subjects in $out"
