#!/usr/bin/env bash
# The viewer's size and speed (issue 13), and the README's screenshots.
#   bench/view_bench.sh [--screenshots | --screenshots_only]
# 1. A 10,000-frame take (the demo walk at 120 Hz), 53 markers (3 around each of the demo's
#    bones but the last 7, 0.5 mm noise), a subject calibrated on it, through `pipeline` onto Xbot
#    (28,312 vertices; ../shared/data/gltf/Xbot.glb, MOCAPSOLVE_DATA): the page's size,
#    the time from navigation until window.mocapsolveView.ready, and the frames drawn per
#    second while playing (requestAnimationFrame), in headless Chromium with software
#    WebGL (SwiftShader) at 1280x720. Target: <= 20 MB, < 3 s, >= 30 frames/s.
# 2. With --screenshots (--screenshots_only: without 1.): docs/images/view_repair.png (a damaged demo take after `repair`)
#    and docs/images/view_retarget.png (CMU 02_01 through the pipeline onto Xbot).
# Prints the figures and one JSON line. Needs build/bin/mocapsolve and the viewer tools.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ms="$root/build/bin/mocapsolve"
data="${MOCAPSOLVE_DATA:-$root/../shared/data}"
work="$(mktemp -d /tmp/view_bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"

if [[ "${1:-}" != "--screenshots_only" ]]; then
"$ms" generate --demo_out=walk.bvh --frames=10000 --fps=120 >/dev/null
# 53 markers: the auto:3 set of the demo's 20 joints (60) without the last 7.
"$ms" markers --quiet --motion=walk.bvh --skeleton_units=cm --markerset=auto:3 --write_markerset=set60.json \
  --out=walk60.c3d >/dev/null
node -e 'const fs=require("fs");const s=JSON.parse(fs.readFileSync("set60.json"));s.markers=s.markers.slice(0,53);
         s.skeleton="walk.bvh";fs.writeFileSync("set53.json",JSON.stringify(s,null,1))'
"$ms" markers --quiet --motion=walk.bvh --skeleton_units=cm --markerset=set53.json --noise_mm=0.5 --seed=3 \
  --out=walk.c3d >/dev/null
"$ms" calibrate --quiet --motion=walk.bvh --skeleton_units=cm --markers=walk.c3d --attach=auto \
  --out=set.json --out_subject=S.json >/dev/null
markers=$("$ms" info walk.c3d | sed -n 's/.*markers: *\([0-9]*\).*/\1/p' | head -1)
start=$(date +%s.%N)
"$ms" pipeline --quiet --subject=S.json --markers=walk.c3d --character="$data/gltf/Xbot.glb" --out_dir=take >/dev/null
pipeline_s=$(echo "$(date +%s.%N) - $start" | bc)
bytes=$(stat -c %s take/view.html)
cat > spec.json <<JSON
{"width": 1280, "height": 720,
 "pages": [{"path": "$work/take/view.html", "min_share": 0.01, "moving": [0, 5000], "bench": {"seconds": 5}}]}
JSON
result=$("$root/scripts/view_check.sh" spec.json)
echo "$result"
open_s=$(echo "$result" | node -e 'const r=JSON.parse(require("fs").readFileSync(0,"utf8").trim().split("\n").pop());console.log(r.open_seconds)')
fps=$(echo "$result" | node -e 'const r=JSON.parse(require("fs").readFileSync(0,"utf8").trim().split("\n").pop());console.log(r.play.fps.toFixed(1), r.play.median_ms.toFixed(1), r.play.p95_ms.toFixed(1))')
read -r fps_value median_ms p95_ms <<<"$fps"
printf 'view bench: 10000 frames, %s markers, Xbot; page %.1f MB (target <= 20), opens in %.2f s (target < 3), plays at %s frames/s (median %s ms, p95 %s ms; target >= 30); pipeline %.1f s\n' \
  "$markers" "$(echo "$bytes / 1000000" | bc -l)" "$open_s" "$fps_value" "$median_ms" "$p95_ms" "$pipeline_s"
echo "{\"benchmark\": \"view\", \"frames\": 10000, \"markers\": $markers, \"page_bytes\": $bytes, \"open_seconds\": $open_s, \"play_fps\": $fps_value, \"median_frame_ms\": $median_ms, \"p95_frame_ms\": $p95_ms}"

fi

if [[ "${1:-}" == "--screenshots" || "${1:-}" == "--screenshots_only" ]]; then
  mkdir -p "$root/docs/images"
  "$ms" generate --demo_out=demo.bvh --frames=240 --fps=30 >/dev/null
  "$ms" markers --quiet --motion=demo.bvh --skeleton_units=cm --markerset=auto:3 --write_markerset=demo_set.json \
    --out=demo.c3d >/dev/null
  "$ms" corrupt --quiet --markers=demo.c3d --out=damaged.c3d --corrupt_seed=4 --gaps=5 --cluster_gaps=1 >/dev/null
  "$ms" repair --quiet --skeleton=demo.bvh --skeleton_units=cm --markerset=demo_set.json --markers=damaged.c3d \
    --out_markers=repaired.c3d --report=repair.json --view=repair.html >/dev/null
  repair_frame=$(node -e 'const r=require("./repair.json");const f=r.filled[0];console.log(Math.round((f.first_frame+f.last_frame)/2))')
  "$ms" calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" --markers="$data/c3d/02_01.c3d" \
    --axes=y,z,x --out=02.json --out_subject=S02.json >/dev/null
  "$ms" pipeline --quiet --subject=S02.json --markers="$data/c3d/02_01.c3d" --character="$data/gltf/Xbot.glb" \
    --out_dir=cmu >/dev/null
  cat > shots.json <<JSON
{"width": 900, "height": 560,
 "pages": [{"path": "$work/repair.html", "screenshot": {"path": "$work/view_repair.png", "frame": $repair_frame}},
           {"path": "$work/cmu/view.html", "screenshot": {"path": "$work/view_retarget.png", "frame": 150}}]}
JSON
  "$root/scripts/view_check.sh" shots.json
  cp view_repair.png view_retarget.png "$root/docs/images/"
  echo "wrote docs/images/view_repair.png (frame $repair_frame) and docs/images/view_retarget.png"
fi
