#!/usr/bin/env bash
# Peak memory and throughput of `mocapsolve pipeline` against the length of the take: CMU
# 02_05 (1,854 frames, 41 markers, 120 Hz) repeated N times (build/bin/loop_markers, from
# bench/tools/loop_markers.cc) onto Xbot, with the subject calibrated once on 02_01 as the
# demo does; default outputs (repaired.c3d, solved.bvh, Xbot.glb, report.json, view.html).
#
#   bench/pipeline_memory.sh [REPEATS="1 4 16"] [WORK_DIR=/tmp/mocapsolve-memory-bench]
# Environment: MOCAPSOLVE (binary, default build/bin/mocapsolve), PIPELINE_FLAGS (more flags,
# e.g. --window_frames=N --num_threads=1; the JSON lines record --num_threads), LOOP_MARKERS
# (build/bin/loop_markers), MOCAPSOLVE_DATA (../shared/data).
# Prints per run: frames, peak RSS (/usr/bin/time -v, "Maximum resident set size"), KB per
# frame above the smallest run, frames/s (the report's, reading included, writing not),
# the process' user and wall seconds and the load average; and a JSON line per run to
# WORK_DIR/pipeline_memory.jsonl.
set -euo pipefail
cd "$(dirname "$0")/.."
ms=${MOCAPSOLVE:-$PWD/build/bin/mocapsolve}
loop=${LOOP_MARKERS:-$PWD/build/bin/loop_markers}
data=$(realpath "${MOCAPSOLVE_DATA:-../shared/data}")
repeats=${1:-1 4 16}
work=$(realpath -m "${2:-/tmp/mocapsolve-memory-bench}")
mkdir -p "$work"
"$ms" calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" \
  --markers="$data/c3d/02_01.c3d" --axes=y,z,x --out="$work/markerset.json" \
  --out_subject="$work/S02.json" >/dev/null
base_frames=""; base_kb=""
# --num_threads as PIPELINE_FLAGS give it (2, the default, retargets a windowed take's windows on
# a second thread and runs repair's solves side by side).
threads=2
if [[ "${PIPELINE_FLAGS:-}" =~ --num_threads=([0-9]+) ]]; then threads=${BASH_REMATCH[1]}; fi
printf '%8s %12s %14s %10s %8s %8s  %s\n' frames "peak RSS MB" "KB/frame above" frames/s "user s" "wall s" load
for n in $repeats; do
  "$loop" "$data/c3d/cmu_02_05.c3d" "$n" "$work/take_x$n.c3d"
  rm -rf "$work/out_x$n"
  /usr/bin/time -v "$ms" pipeline --quiet --subject="$work/S02.json" --markers="$work/take_x$n.c3d" \
    --character="$data/gltf/Xbot.glb" --out_dir="$work/out_x$n" ${PIPELINE_FLAGS:-} >/dev/null 2>"$work/time_x$n.txt"
  kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time_x$n.txt")
  user=$(awk -F': ' '/User time/ {print $2}' "$work/time_x$n.txt")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$work/time_x$n.txt")
  read -r frames fps < <(/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(r['frames'], round(r['frames_per_second']))" "$work/out_x$n/report.json")
  if [ -z "$base_frames" ]; then base_frames=$frames; base_kb=$kb; fi
  per=$(/usr/bin/python3 -c "import sys; f,b,k,bk=map(float,sys.argv[1:]); print('%.1f' % ((k-bk)/(f-b)) if f>b else '-')" "$frames" "$base_frames" "$kb" "$base_kb")
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  printf '%8d %12.0f %14s %10d %8s %8s  %s\n' "$frames" "$(echo "$kb/1024" | bc -l)" "$per" "$fps" "$user" "$wall" "$load"
  echo "{\"frames\": $frames, \"peak_rss_kb\": $kb, \"kb_per_frame_above_first\": \"$per\", \"frames_per_second\": $fps, \"user_s\": $user, \"wall\": \"$wall\", \"num_threads\": $threads, \"load\": \"$load\"}" >> "$work/pipeline_memory.jsonl"
  rm -f "$work/take_x$n.c3d"
done
