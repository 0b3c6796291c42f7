#!/usr/bin/env bash
# A take that starts with a long still stance (issue 32): the shared take with STILL frames
# (1000 by default) of its first frame put before it, each sample moved by 0.5 mm of noise
# (a body standing still sways; seeded), written as OUT/data/c3d/TAKE_still.c3d beside a
# link to the shared characters; then bench/auto_subject.sh runs `pipeline --subject=auto`
# on it (its table: exit, fit frames, marker RMS, gate). Nothing is written in the repo.
#   bench/still_start.sh OUTDIR [DATA_DIR] [take ...]   (STILL=frames; MOCAPSOLVE_CLI, VARIANTS
#   as bench/auto_subject.sh)
set -euo pipefail
out=${1:?usage: $0 OUTDIR [DATA_DIR] [take ...]}
data=${2:-${MOCAPSOLVE_DATA:-$(dirname "$0")/../../shared/data}}
shift $(( $# >= 2 ? 2 : 1 ))
takes=("$@")
[ ${#takes[@]} -gt 0 ] || takes=(cmu_02_05 squat)
ms=${MOCAPSOLVE_CLI:-$(dirname "$0")/../build/bin/mocapsolve}
mkdir -p "$out/data/c3d"
ln -sfn "$(cd "$data/gltf" && pwd)" "$out/data/gltf"
still_takes=()
for take in "${takes[@]}"; do
  "$ms" convert "$data/c3d/$take.c3d" "$out/$take.trc" >/dev/null
  /usr/bin/python3 - "$out/$take.trc" "$out/${take}_still.trc" "${STILL:-1000}" <<'PY'
import random, sys
src, dst, still = sys.argv[1], sys.argv[2], int(sys.argv[3])
lines = open(src).read().split("\n")
blank = 6 if len(lines) > 5 and not lines[5].strip() else 5  # The header's blank line, if any.
header, rows = lines[:blank], [l for l in lines[blank:] if l.strip()]
rate = float(header[2].split("\t")[0])
first = rows[0].split("\t")
random.seed(1)
def row(index, values):
    return "\t".join([str(index + 1), "%.9g" % (index / rate)] + values)
out = []
for f in range(still):
    values = [("%.6f" % (float(v) + random.gauss(0.0, 0.5))) if v.strip() else v for v in first[2:]]
    out.append(row(f, values))
for f, r in enumerate(rows):
    out.append(row(still + f, r.split("\t")[2:]))
fields = header[2].split("\t")
fields[2] = fields[7] = str(len(out))
header[2] = "\t".join(fields)
open(dst, "w").write("\n".join(header + out) + "\n")
PY
  "$ms" convert "$out/${take}_still.trc" "$out/data/c3d/${take}_still.c3d" >/dev/null
  still_takes+=("${take}_still")
done
MOCAPSOLVE_CLI=$ms "$(dirname "$0")/auto_subject.sh" "$out" "$out/data" "${still_takes[@]}"
