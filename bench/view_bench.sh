#!/usr/bin/env bash
# The viewer's size and speed (issue 13), and the README's screenshots.
#   bench/view_bench.sh [--screenshots | --screenshots_only]
# 1. A 10,000-frame take (the demo walk at 120 Hz), 53 markers (3 around each of the demo's
#    bones but the last 7, 0.5 mm noise), a subject calibrated on it, through `pipeline` onto Xbot
#    (28,312 vertices; ../shared/data/gltf/Xbot.glb, MOCAPSOLVE_DATA): the page's size,
#    the time from navigation until window.mocapsolveView.ready, and the frames drawn per
#    second while playing (requestAnimationFrame), in headless Chromium with software
#    WebGL (SwiftShader) at 1280x720, three runs (VIEW_BENCH_RUNS), each in a fresh browser.
#    Target: <= 20 MB, < 3 s, >= 30 frames/s. The last lines: one summary line (the runs'
#    medians, the page's size and the load average: the machine may be shared) and JSON.
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
# VIEW_BENCH_PAGE=FILE keeps a copy of the page (to profile it).
if [[ -n "${VIEW_BENCH_PAGE:-}" ]]; then cp take/view.html "$VIEW_BENCH_PAGE"; fi
cat > spec.json <<JSON
{"width": 1280, "height": 720,
 "pages": [{"path": "$work/take/view.html", "min_share": 0.01, "moving": [0, 5000], "bench": {"seconds": 5}}]}
JSON
# Three runs, each in a fresh browser (a new profile: no cached script or file), so
# that the open time is a cold open every time; the figures are the runs' medians.
runs=${VIEW_BENCH_RUNS:-3}
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
opens=() fpss=() medians=() p95s=()
for ((run = 1; run <= runs; ++run)); do
  result=$("$root/scripts/view_check.sh" spec.json)
  echo "$result"
  read -r open_s fps_value median_ms p95_ms <<<"$(echo "$result" | node -e '
    const r = JSON.parse(require("fs").readFileSync(0, "utf8").trim().split("\n").pop());
    if (r.failures.length) { console.error("view bench: " + r.failures.join("; ")); process.exit(1); }
    console.log(r.open_seconds, r.play.fps.toFixed(1), r.play.median_ms.toFixed(1), r.play.p95_ms.toFixed(1))')"
  printf 'run %d: opens in %.2f s, plays at %s frames/s (median frame %s ms, p95 %s ms)\n' \
    "$run" "$open_s" "$fps_value" "$median_ms" "$p95_ms"
  opens+=("$open_s") fpss+=("$fps_value") medians+=("$median_ms") p95s+=("$p95_ms")
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
open_median=$(median "${opens[@]}") fps_median=$(median "${fpss[@]}")
frame_median=$(median "${medians[@]}") p95_median=$(median "${p95s[@]}")
mb=$(echo "$bytes / 1000000" | bc -l)
printf 'view bench: 10000 frames, %s markers, Xbot; pipeline %.1f s; opens %s s; plays %s frames/s\n' \
  "$markers" "$pipeline_s" "${opens[*]}" "${fpss[*]}"
printf 'view bench summary: page %.1f MB (target <= 20), opens in %.2f s (median of %d; target < 3), plays at %s frames/s (median of %d, median frame %s ms, p95 %s ms; target >= 30); load average %s before, %s after (%s cores)\n' \
  "$mb" "$open_median" "$runs" "$fps_median" "$runs" "$frame_median" "$p95_median" "$load_before" "$load_after" "$(nproc)"
echo "{\"benchmark\": \"view\", \"frames\": 10000, \"markers\": $markers, \"page_bytes\": $bytes, \"runs\": $runs, \"open_seconds\": [$(IFS=,; echo "${opens[*]}")], \"play_fps\": [$(IFS=,; echo "${fpss[*]}")], \"open_seconds_median\": $open_median, \"play_fps_median\": $fps_median, \"median_frame_ms\": $frame_median, \"p95_frame_ms\": $p95_median, \"load_average_before\": \"$load_before\", \"load_average_after\": \"$load_after\"}"

fi

if [[ "${1:-}" == "--screenshots" || "${1:-}" == "--screenshots_only" ]]; then
  mkdir -p "$root/docs/images"
  "$ms" generate --demo_out=demo.bvh --frames=240 --fps=30 >/dev/null
  "$ms" markers --quiet --motion=demo.bvh --skeleton_units=cm --markerset=auto:3 --write_markerset=demo_set.json \
    --out=demo.c3d >/dev/null
  "$ms" corrupt --quiet --markers=demo.c3d --out=damaged.c3d --seed=4 --gaps=5 --cluster_gaps=1 >/dev/null
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
