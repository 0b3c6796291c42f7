#!/usr/bin/env bash
# The batch's own figures (issue 12), measured as whole processes on real takes:
#   1. throughput: N takes (CMU 02_05 and 02_01, looped, onto Xbot) with --jobs=1 and --jobs=2,
#      wall time and the speedup;
#   2. a re-run with nothing to do over the same takes (the cost of keys and records);
#   3. memory: a long run of SMALL takes (the first 30 frames of 02_01, no character), the batch
#      process's resident memory sampled from /proc while records appear, at take ~100 and at
#      the end.
#
#   bench/batch_throughput.sh [N=100] [SMALL=1000] [WORK_DIR=/tmp/mocapsolve-batch-bench]
# Environment: MOCAPSOLVE (binary, default build/bin/mocapsolve), MOCAPSOLVE_DATA (../shared/data),
# BATCH_FLAGS (more batch flags for the throughput runs, e.g. --take_threads=1).
# Prints one line per figure and writes WORK_DIR/batch_throughput.json.
set -euo pipefail
cd "$(dirname "$0")/.."
ms=${MOCAPSOLVE:-$PWD/build/bin/mocapsolve}
data=$(realpath "${MOCAPSOLVE_DATA:-../shared/data}")
takes=${1:-100}
small=${2:-1000}
work=$(realpath -m "${3:-/tmp/mocapsolve-batch-bench}")
rm -rf "$work"; mkdir -p "$work"
now() { date +%s.%N; }

# The subject: calibrated once on 02_01 with its AMC (as the demo does).
"$ms" calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" \
  --markers="$data/c3d/02_01.c3d" --axes=y,z,x --out="$work/markerset.json" \
  --out_subject="$work/S02.json" >/dev/null

/usr/bin/python3 - "$work" "$data" "$takes" "$small" <<'PY'
import json, sys
work, data, n, small = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
real = [f"{data}/c3d/cmu_02_05.c3d", f"{data}/c3d/02_01.c3d"]
json.dump({"defaults": {"subject": "S02.json", "characters": [f"{data}/gltf/Xbot.glb"]},
           "takes": [{"name": f"take{i:04d}", "markers": real[i % 2]} for i in range(n)]},
          open(f"{work}/big.json", "w"), indent=1)
# Small takes: the same 30-frame file under many names (the records and keys are per take).
json.dump({"defaults": {"subject": "small_subject.json"},
           "takes": [{"name": f"small{i:05d}", "markers": "small.c3d"} for i in range(small)]},
          open(f"{work}/small.json", "w"), indent=1)
PY
# Small takes: a generated 30-frame walk, its markers and its calibrated subject.
"$ms" generate --demo_out="$work/small.bvh" --frames=30 --fps=60 >/dev/null
"$ms" markers --quiet --motion="$work/small.bvh" --skeleton_units=cm --markerset=auto:3 \
  --write_markerset="$work/small_markerset.json" --noise_mm=1 --seed=7 --out="$work/small.c3d" >/dev/null
"$ms" calibrate --quiet --motion="$work/small.bvh" --skeleton_units=cm --markers="$work/small.c3d" \
  --attach=auto --out="$work/small_calibrated.json" --out_subject="$work/small_subject.json" >/dev/null

run() {  # run JOBS OUT_DIR MANIFEST [flags...] -> seconds
  local jobs=$1 dir=$2 manifest=$3; shift 3
  local t0; t0=$(now)
  "$ms" batch --quiet --manifest="$manifest" --out_dir="$dir" --jobs="$jobs" ${BATCH_FLAGS:-} "$@" >>"$work/batch.log" 2>&1 || true
  echo "$(now) - $t0" | bc -l
}
frames_of() { /usr/bin/python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print(sum(t.get('frames',0) or 0 for t in s['takes']), sum(t['status']=='done' for t in s['takes']))" "$1/summary.json"; }

t1=0 t2=0 tr=0 f2=0
if [ "$takes" -gt 0 ]; then
  t1=$(run 1 "$work/j1" "$work/big.json"); read -r f1 d1 < <(frames_of "$work/j1")
  t2=$(run 2 "$work/j2" "$work/big.json"); read -r f2 d2 < <(frames_of "$work/j2")
  tr=$(run 2 "$work/j2" "$work/big.json")
  printf 'throughput: %d takes (%d done), %d frames: --jobs=1 %.1f s (%.0f frames/s), --jobs=2 %.1f s (%.0f frames/s), speedup %.2fx\n' \
    "$takes" "$d2" "$f2" "$t1" "$(echo "$f1 / $t1" | bc -l)" "$t2" "$(echo "$f2 / $t2" | bc -l)" "$(echo "$t1 / $t2" | bc -l)"
  printf 're-run with nothing to do: %d takes in %.2f s\n' "$takes" "$tr"
  cmp -s <(cd "$work/j1" && find . -name '*.bvh' | sort | xargs cat) <(cd "$work/j2" && find . -name '*.bvh' | sort | xargs cat) \
    && echo "outputs of --jobs=1 and --jobs=2: identical solved.bvh files" || echo "outputs of --jobs=1 and --jobs=2 DIFFER"
fi

# Memory over a long run of small takes: sample the batch's VmRSS with the count of records.
"$ms" batch --quiet --manifest="$work/small.json" --out_dir="$work/small" --jobs=2 >>"$work/batch.log" 2>&1 & pid=$!
set +e +o pipefail  # the sampling loop races the batch (folders appear, the process ends)
: > "$work/rss.txt"
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/VmRSS/ {print $2}' /proc/$pid/status 2>/dev/null || true)
  n=$(find "$work/small" -maxdepth 2 -name record.json 2>/dev/null | wc -l)
  [ -n "$rss" ] && echo "$n $rss" >> "$work/rss.txt"
  sleep 0.2
done
wait "$pid" || true
t0=$(now)
"$ms" batch --quiet --manifest="$work/small.json" --out_dir="$work/small" --jobs=2 >>"$work/batch.log" 2>&1 || true
small_rerun=$(echo "$(now) - $t0" | bc -l)
/usr/bin/python3 - "$work" "$takes" "$t1" "$t2" "$tr" "$f2" "$small" "$small_rerun" <<'PY'
import json, sys
work, takes, t1, t2, tr, frames, small, small_rerun = (sys.argv[1], int(sys.argv[2]), *map(float, sys.argv[3:6]),
                                                        int(sys.argv[6]), int(sys.argv[7]), float(sys.argv[8]))
rows = [tuple(map(int, l.split())) for l in open(f"{work}/rss.txt") if l.strip()]
# The batch's resident memory once k takes have records (the largest sample up to then).
at = lambda k: max(r for n, r in rows if n <= k)
early, late, peak = at(min(100, small // 10)), at(small - 1), max(r for _, r in rows)
done = sum(t["status"] == "done" for t in json.load(open(f"{work}/small/summary.json"))["takes"])
print(f"memory: {small} small takes ({done} done): batch VmRSS {early} kB at take {min(100, small // 10)}, "
      f"{late} kB at take {small - 1} ({100.0 * (late - early) / early:+.1f} %), {peak} kB with the summary")
print(f"re-run with nothing to do: {small} takes in {small_rerun:.2f} s")
json.dump({"takes": takes, "frames": frames, "jobs1_s": t1, "jobs2_s": t2, "speedup": t1 / t2 if t2 else 0,
           "rerun_nothing_to_do_s": tr, "small_takes": small, "small_done": done,
           "rss_kb_at_100": early, "rss_kb_at_end": late, "rss_kb_peak": peak,
           "small_rerun_nothing_to_do_s": small_rerun}, open(f"{work}/batch_throughput.json", "w"), indent=1)
print(f"wrote {work}/batch_throughput.json")
PY
