#!/usr/bin/env bash
# `mocapsolve live`'s figures on CMU 02_05 (1,854 frames, 41 markers, 120 Hz), as whole processes:
#   1. replayed at its own rate (--input=replay:...c3d, 120 Hz): per-frame latency, frame in to
#      pose out (median, 99th percentile, max), frames in / out / dropped;
#   2. replayed as fast as possible (--replay_speed=0): frames/s;
#   3. the same take streamed through stdin as JSON lines and in the binary framing, as fast as
#      the pipe delivers: frames/s and latency (parsing included).
#
#   bench/live_latency.sh [ROUNDS=3] [WORK_DIR=/tmp/mocapsolve-live-bench]
# Environment: MOCAPSOLVE (binary, default build/bin/mocapsolve), MOCAPSOLVE_DATA (../shared/data).
# Prints one line per run (and the load average) and a JSON line per run to WORK_DIR/live_latency.jsonl.
set -euo pipefail
cd "$(dirname "$0")/.."
ms=${MOCAPSOLVE:-$PWD/build/bin/mocapsolve}
data=$(realpath "${MOCAPSOLVE_DATA:-../shared/data}")
rounds=${1:-3}
work=$(realpath -m "${2:-/tmp/mocapsolve-live-bench}")
rm -rf "$work"; mkdir -p "$work"
take="$data/c3d/cmu_02_05.c3d"

# The subject: calibrated once on 02_01 with its AMC (as the demo does).
"$ms" calibrate --quiet --motion="$data/amc/02_01.amc" --skeleton="$data/amc/02.asf" \
  --markers="$data/c3d/02_01.c3d" --axes=y,z,x --out="$work/markerset.json" \
  --out_subject="$work/S02.json" >/dev/null
# The take as a stream: TRC text -> JSON lines and the binary framing (io/live_frame.h).
"$ms" convert --quiet "$take" "$work/take.trc" >/dev/null
/usr/bin/python3 - "$work" <<'PY'
import json, math, struct, sys
work = sys.argv[1]
lines = open(f"{work}/take.trc").read().splitlines()
names = [n for n in lines[3].split("\t")[2:] if n]
rows = [l.split("\t") for l in lines[5:] if l.strip()]
with open(f"{work}/take.jsonl", "w") as js, open(f"{work}/take.bin", "wb") as bn:
    bn.write(b"MOCAPLV1" + struct.pack("<I", len(names)))
    for n in names:
        bn.write(struct.pack("<B", len(n)) + n.encode())
    for f, row in enumerate(rows):
        markers, floats = {}, []
        for m, n in enumerate(names):
            cells = row[2 + 3 * m: 5 + 3 * m]
            xyz = [float(c) for c in cells] if len(cells) == 3 and all(c.strip() for c in cells) else None
            markers[n] = xyz
            floats += xyz if xyz else [math.nan] * 3
        js.write(json.dumps({"frame": f, "time": f / 120.0, "markers": markers}) + "\n")
        bn.write(b"MSFR" + struct.pack("<IfI", f, f / 120.0, len(names)) + struct.pack(f"<{len(floats)}f", *floats))
PY

run() {  # name, input redirect, flags...
  local name=$1 redirect=$2; shift 2
  local load; load=$(cut -d' ' -f1-3 /proc/loadavg)
  if [ -n "$redirect" ]; then
    "$ms" live --quiet --subject="$work/S02.json" --report="$work/$name.json" "$@" <"$redirect" >/dev/null
  else
    "$ms" live --quiet --subject="$work/S02.json" --report="$work/$name.json" "$@" >/dev/null
  fi
  /usr/bin/python3 - "$work/$name.json" "$name" "$load" "$work/live_latency.jsonl" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); l = r["latency_ms"]
print(f"{sys.argv[2]:>14}: {r['frames_in']} in, {r['frames_out']} out, {r['frames_dropped']} dropped; latency median "
      f"{l['median']:.3f} ms, p99 {l['p99']:.3f} ms, max {l['max']:.1f} ms; {r['frames_per_second']:.0f} frames/s; "
      f"RMS {r['rms_marker_residual']:.3f} mm (load {sys.argv[3]})")
line = {"name": sys.argv[2], "frames_in": r["frames_in"], "frames_out": r["frames_out"],
        "frames_dropped": r["frames_dropped"], "latency_ms": l, "frames_per_second": r["frames_per_second"],
        "load": sys.argv[3]}
open(sys.argv[4], "a").write(json.dumps(line) + "\n")
PY
}

for round in $(seq "$rounds"); do
  echo "round $round"
  run replay_120hz "" --input="replay:$take" --replay_speed=1
  run replay_fast "" --input="replay:$take" --replay_speed=0
  run stdin_json "$work/take.jsonl" --input=-
  run stdin_binary "$work/take.bin" --input=-
done
