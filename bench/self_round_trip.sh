#!/usr/bin/env bash
# The self round trip on every glTF character, with the commands a user runs: the
# character's own first clip converted to BVH, retargeted back onto the character, and the
# joint world positions of the result (`fk` of the written .glb's new clip, its first) compared with
# those of the character's own clip (`fk` of the file), frame by frame. Prints per
# character the largest joint error over joints and frames as a share of its height (the
# bind-pose mesh's, as `info` prints it), where it is, and the retarget's own note on the
# path it took; a JSON line per character goes to WORK_DIR/self_round_trip.jsonl.
#
#   bench/self_round_trip.sh [WORK_DIR=/tmp/mocapsolve-self-round-trip] [CHARACTER.glb ...]
# Environment: MOCAPSOLVE (binary, default build/bin/mocapsolve), MOCAPSOLVE_DATA (../shared/data).
set -euo pipefail
cd "$(dirname "$0")/.."
ms=${MOCAPSOLVE:-$PWD/build/bin/mocapsolve}
data=$(realpath "${MOCAPSOLVE_DATA:-../shared/data}")
work=$(realpath -m "${1:-/tmp/mocapsolve-self-round-trip}")
shift || true
characters=("$@")
if [ ${#characters[@]} -eq 0 ]; then characters=("$data"/gltf/*.glb); fi
rm -rf "$work"; mkdir -p "$work"
: > "$work/self_round_trip.jsonl"
for glb in "${characters[@]}"; do
  name=$(basename "$glb" .glb)
  "$ms" convert --quiet "$glb" "$work/$name.bvh" >/dev/null 2>&1
  "$ms" retarget --quiet --source="$work/$name.bvh" --target="$glb" --out="$work/${name}_back.glb" \
    --report="$work/$name.json" 2>/dev/null >/dev/null
  "$ms" fk --quiet --motion="$glb" --out="$work/${name}_truth.csv" >/dev/null 2>&1
  "$ms" fk --quiet --motion="$work/${name}_back.glb" --animation=0 --out="$work/${name}_back.csv" >/dev/null 2>&1
  height=$("$ms" info "$glb" 2>/dev/null | sed -n 's/^height: *\([0-9.eE+-]*\).*/\1/p')
  /usr/bin/python3 - "$work" "$name" "$height" <<'PY'
import csv, json, math, sys
work, name, height = sys.argv[1], sys.argv[2], float(sys.argv[3])
def read(path):
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            rows[(int(r["frame"]), r["joint"])] = (float(r["x"]), float(r["y"]), float(r["z"]))
    return rows
truth, back = read(f"{work}/{name}_truth.csv"), read(f"{work}/{name}_back.csv")
missing = [k for k in truth if k not in back]
worst, where = 0.0, ("", 0)
for key, p in truth.items():
    if key not in back: continue
    e = math.dist(p, back[key]) / height
    if e > worst: worst, where = e, key
report = json.load(open(f"{work}/{name}.json"))
own = any("own skeleton" in n for n in report.get("notes", []))
frames = len({k[0] for k in truth})
print(f"{name:16s} {frames:4d} frames  max joint error {100 * worst:.5f} % of height {height:g} "
      f"(frame {where[0]}, {where[1]}){'' if own else '  [solved, not transferred]'}"
      f"{f'  {len(missing)} samples missing' if missing else ''}")
with open(f"{work}/self_round_trip.jsonl", "a") as f:
    f.write(json.dumps({"character": name, "frames": frames, "height": height, "own_skeleton": own,
                        "max_joint_error_percent_of_height": 100 * worst, "missing": len(missing)}) + "\n")
PY
done
