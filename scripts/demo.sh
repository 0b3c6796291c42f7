#!/usr/bin/env bash
# The main job on the bundled default: generate the project's own demo clip, then
# inspect it, convert it, run forward kinematics and time the kinematic core.
# Outputs go to out/demo/ (override with MOCAPSOLVE_DEMO_OUT).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
out=${MOCAPSOLVE_DEMO_OUT:-out/demo}
mkdir -p "$out"
ms=build/bin/mocapsolve

echo; echo "== 1. generate: the bundled default clip (procedural walk, made by the project)"
$ms generate --demo_out="$out/walk.bvh" --frames=240 --fps=60

echo; echo "== 2. info"
$ms info "$out/walk.bvh" --report="$out/info.json"

echo; echo "== 3. convert: centimetres to metres, every joint to XYZ Euler order"
$ms convert "$out/walk.bvh" "$out/walk_m_xyz.bvh" --scale=0.01 --euler_order=XYZ

echo; echo "== 4. fk: global joint positions per frame"
$ms fk --motion="$out/walk.bvh" --out="$out/walk_positions.csv" --quiet
head -4 "$out/walk_positions.csv"

echo; echo "== 5. bench: forward kinematics throughput"
$ms bench --problem=fk --repeats=3 --json="$out/bench_fk.json" | grep -v '^JSON'

echo
echo "Done. Outputs in $out/:"
ls -1 "$out" | sed 's/^/  /'
echo "Real data: see README.md (\"Running on real files\")."
