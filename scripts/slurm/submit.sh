#!/usr/bin/env bash
# Runs a mocapsolve batch as a Slurm job array, one shard per array task, then merges the
# takes' records into DIR/summary.json and DIR/summary.csv once every shard has ended.
#
#   scripts/slurm/submit.sh M.json DIR [SHARDS] [CPUS_PER_SHARD] [extra batch flags...]
#
# Each array task runs `mocapsolve batch --manifest=M.json --out_dir=DIR --jobs=CPUS`,
# which reads its shard from SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT (takes at
# manifest positions p with p % SHARDS == task), so the shards write disjoint take
# folders under DIR (a shared file system) and their own DIR/summary.shard<i>of<n>.json.
# The merge job (afterany: it also runs when shards failed or were cancelled) lists the
# takes without a record as "missing"; re-submitting resumes: finished takes are skipped.
# Environment: MOCAPSOLVE (the binary, default: mocapsolve on PATH), SBATCH_EXTRA (more
# sbatch options, e.g. "--partition=cpu --time=04:00:00").
set -euo pipefail

if [[ $# -lt 2 ]]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 1
fi
manifest=$(realpath "$1")
out_dir=$(realpath -m "$2")
shards=${3:-8}
cpus=${4:-4}
shift $(( $# < 4 ? $# : 4 ))
extra=("$@")
binary=${MOCAPSOLVE:-$(command -v mocapsolve || true)}
if [[ -z "$binary" ]]; then
  echo "submit.sh: set MOCAPSOLVE to the mocapsolve binary" >&2
  exit 1
fi
mkdir -p "$out_dir/.slurm"
# Check the manifest once here, before anything is queued (exit 1 names the bad field).
"$binary" batch --manifest="$manifest" --write_manifest=/dev/null >/dev/null

array_id=$(sbatch --parsable ${SBATCH_EXTRA:-} --job-name=mocapsolve-batch --array=0-$((shards - 1)) \
  --cpus-per-task="$cpus" --output="$out_dir/.slurm/shard-%a.log" \
  --wrap="$(printf '%q ' "$binary" batch --quiet --manifest="$manifest" --out_dir="$out_dir" --jobs="$cpus" \
    "${extra[@]}")")
merge_id=$(sbatch --parsable ${SBATCH_EXTRA:-} --job-name=mocapsolve-merge --dependency=afterany:"$array_id" \
  --output="$out_dir/.slurm/merge.log" \
  --wrap="$(printf '%q ' "$binary" batch --merge --manifest="$manifest" --out_dir="$out_dir")")
echo "submitted shards $array_id (0-$((shards - 1)), $cpus CPUs each) and merge $merge_id; summary: $out_dir/summary.json"
