#!/usr/bin/env bash
# A real Slurm on this one machine, running a batch through scripts/slurm/submit.sh (issue 12):
#   1. installs Debian 12's slurm-wlm and munge if missing (as root);
#   2. starts munged (as the munge user, on a private socket), slurmctld and slurmd without
#      systemd, from a single-node slurm.conf in a temporary folder (localhost, this machine's
#      CPUs, proctrack/linuxproc, task/none, no accounting);
#   3. submits a 20-take batch as a job array of 4 shards plus the merge job, cancels one
#      array task while it runs (scancel), checks that the merge lists that shard's unfinished
#      takes as missing, resubmits, and checks that every take is then done exactly once (the
#      takes finished before the cancel are skipped, not redone) with outputs identical to a
#      local `batch --jobs=2` run;
#   4. tears down only what it started (scontrol shutdown; munged), trap-guarded.
#
#   scripts/slurm/test_local_cluster.sh            (needs build/bin/mocapsolve; run as root)
# Exit: 0 passed, 1 failed, 77 cannot run here (not root and Slurm missing). Takes ~1 minute.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
repo=$PWD
ms=${MOCAPSOLVE:-$repo/build/bin/mocapsolve}
say() { echo "test_local_cluster: $*"; }
fail() { echo "test_local_cluster: FAILED: $*" >&2; exit 1; }
[ -x "$ms" ] || fail "no $ms (build first: scripts/setup.sh)"

# --- 1. packages -------------------------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  if [ "$(id -u)" -ne 0 ]; then say "skipped: slurm-wlm/munge missing and not root"; exit 77; fi
  say "installing slurm-wlm munge"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null \
    || { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null; }
fi
[ "$(id -u)" -eq 0 ] || { say "skipped: slurmd must run as root here"; exit 77; }

# --- 2. daemons --------------------------------------------------------------------------
tmp=$(mktemp -d /tmp/mocapsolve-slurm.XXXXXX)
chmod 755 "$tmp"
started_munged=0
cleanup() {
  set +e
  if [ -f "$tmp/slurm.conf" ]; then
    SLURM_CONF="$tmp/slurm.conf" scontrol shutdown >/dev/null 2>&1
    for f in slurmctld slurmd; do  # shutdown is asynchronous: wait, then make sure
      for _ in $(seq 50); do [ -f "$tmp/$f.pid" ] && kill -0 "$(cat "$tmp/$f.pid")" 2>/dev/null || break; sleep 0.1; done
      [ -f "$tmp/$f.pid" ] && kill "$(cat "$tmp/$f.pid")" 2>/dev/null
    done
  fi
  [ "$started_munged" -eq 1 ] && [ -f "$tmp/munge/munged.pid" ] && kill "$(cat "$tmp/munge/munged.pid")" 2>/dev/null
  [ "${KEEP_TMP:-0}" = 1 ] && say "kept $tmp" || rm -rf "$tmp"
}
trap cleanup EXIT

# munged refuses to run as root and checks that its folders belong to it.
mkdir -p "$tmp/munge"
chown munge:munge "$tmp/munge"; chmod 755 "$tmp/munge"  # the users' commands reach the socket
[ -f /etc/munge/munge.key ] || { /usr/sbin/mungekey --create 2>/dev/null || dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=128 2>/dev/null; chown munge:munge /etc/munge/munge.key; chmod 400 /etc/munge/munge.key; }
socket="$tmp/munge/munge.socket"
runuser -u munge -- /usr/sbin/munged --socket="$socket" --pid-file="$tmp/munge/munged.pid" \
  --log-file="$tmp/munge/munged.log" --seed-file="$tmp/munge/munged.seed" || fail "munged did not start ($(tail -1 "$tmp/munge/munged.log" 2>/dev/null))"
started_munged=1

cpus=$(nproc)
mkdir -p "$tmp/state" "$tmp/spool"
cat > "$tmp/slurm.conf" <<EOF
ClusterName=mocapsolve-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=${SLURMCTLD_PORT:-16817}
SlurmdPort=${SLURMD_PORT:-16818}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerParameters=batch_sched_delay=0
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MailProg=/bin/true
ReturnToService=2
MaxArraySize=1001
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start: $(tail -2 "$tmp/slurmctld.log" 2>/dev/null)"
slurmd -f "$SLURM_CONF" -N localhost || fail "slurmd did not start: $(tail -2 "$tmp/slurmd.log" 2>/dev/null)"
for i in $(seq 100); do
  scontrol show node localhost 2>/dev/null | grep -q 'State=IDLE' && break
  [ "$i" -eq 100 ] && fail "node not idle after 20 s: $(tail -3 "$tmp/slurmctld.log")"
  sleep 0.2
done
say "Slurm up (slurmctld + slurmd on localhost, $cpus CPUs)"

# --- 3. the batch ------------------------------------------------------------------------
# 20 generated takes of different lengths (no shared data needed), one subject.
takes="$tmp/takes"; mkdir -p "$takes"
"$ms" generate --demo_out="$takes/base.bvh" --frames=600 --fps=60 >/dev/null
"$ms" markers --quiet --motion="$takes/base.bvh" --skeleton_units=cm --markerset=auto:3 \
  --write_markerset="$takes/markerset.json" --noise_mm=1 --seed=1 --out="$takes/base.c3d" >/dev/null
"$ms" calibrate --quiet --motion="$takes/base.bvh" --skeleton_units=cm --markers="$takes/base.c3d" \
  --attach=auto --out="$takes/calibrated.json" --out_subject="$takes/subject.json" >/dev/null
entries=()
for i in $(seq -w 0 19); do
  "$ms" generate --demo_out="$takes/t$i.bvh" --frames=$((400 + 10 * 10#$i)) --fps=60 >/dev/null
  "$ms" markers --quiet --motion="$takes/t$i.bvh" --skeleton_units=cm --markerset="$takes/markerset.json" \
    --noise_mm=1 --seed=$((10#$i + 2)) --out="$takes/t$i.c3d" >/dev/null
  entries+=("{\"name\": \"take$i\", \"markers\": \"takes/t$i.c3d\"}")
done
manifest="$tmp/M.json"
printf '{"defaults": {"subject": "takes/subject.json"},\n "takes": [%s]}\n' "$(IFS=,; echo "${entries[*]}")" > "$manifest"

wait_for_queue_empty() {  # without accounting, the queue (squeue/scontrol) is the state
  for _ in $(seq 1200); do
    [ -z "$(squeue -h 2>/dev/null)" ] && return 0
    sleep 0.25
  done
  fail "jobs still queued after 300 s: $(squeue)"
}
statuses() { /usr/bin/python3 -c "
import json, sys, collections
s = json.load(open(sys.argv[1]))
print(' '.join(f'{k}={v}' for k, v in sorted(collections.Counter(t['status'] for t in s['takes']).items())))" "$1/summary.json"; }

out="$tmp/out"
t0=$(date +%s.%N)
MOCAPSOLVE="$ms" bash scripts/slurm/submit.sh "$manifest" "$out" 4 1 | tee "$tmp/submit1.txt"
array_id=$(sed -n 's/^submitted shards \([0-9]*\) .*/\1/p' "$tmp/submit1.txt")
[ -n "$array_id" ] || fail "submit.sh printed no job id"
# Cancel array task 3 once it runs and has finished at least one take (takes 3, 7, 11, ...).
for i in $(seq 600); do
  state=$(squeue -h -j "${array_id}_3" -o %T 2>/dev/null || true)
  if [ "$state" = RUNNING ] && ls "$out"/take03/record.json >/dev/null 2>&1; then break; fi
  [ "$i" -eq 600 ] && fail "array task 3 never ran a take (state '$state')"
  sleep 0.05
done
scancel "${array_id}_3"
say "cancelled array task ${array_id}_3 mid-run"
wait_for_queue_empty
first=$(statuses "$out")
say "after the cancel: $first"
grep -q 'missing=' <<<"$first" || fail "the merge lists no missing take after the cancel ($first)"
# The takes finished before the resubmission must not run again: remember their records.
(cd "$out" && for d in take*/; do [ -f "$d/record.json" ] && stat -c '%n %i %Y' "$d/record.json"; done) > "$tmp/records_before.txt"
ran_before=$(wc -l < "$tmp/records_before.txt")

MOCAPSOLVE="$ms" bash scripts/slurm/submit.sh "$manifest" "$out" 4 1 >/dev/null
wait_for_queue_empty
t1=$(date +%s.%N)
second=$(statuses "$out")
say "after the resubmission: $second"
[ "$second" = "done=20" ] || fail "not every take done after the resubmission ($second; logs: $out/.slurm/)"
(cd "$out" && for d in take*/; do [ -f "$d/record.json" ] && stat -c '%n %i %Y' "$d/record.json"; done) > "$tmp/records_after.txt"
grep -Fxv -f "$tmp/records_after.txt" "$tmp/records_before.txt" > "$tmp/redone.txt" || true
[ ! -s "$tmp/redone.txt" ] || fail "takes finished before the cancel were run again: $(cat "$tmp/redone.txt")"
skipped=$(cat "$out"/.slurm/shard-*.log | grep -o '[0-9]* skipped as unchanged' | awk '{s += $1} END {print s + 0}')
say "$ran_before takes finished in the first submission (kept), $((20 - ran_before)) ran in the second; shards report $skipped skipped"

# Outputs equal those of a local run (record/report/summary files hold times: compared without them).
"$ms" batch --quiet --manifest="$manifest" --out_dir="$tmp/local" --jobs=2 >/dev/null
outputs() { (cd "$1" && find . -path ./.slurm -prune -o -type f ! -name 'record.json' ! -name 'report.json' \
  ! -name 'summary*' ! -name 'config.json' ! -name '*.log' -print | sort); }
[ "$(outputs "$out")" = "$(outputs "$tmp/local")" ] || fail "the Slurm run and the local run wrote different files: $(diff <(outputs "$out") <(outputs "$tmp/local") | head -5)"
n=0
while read -r f; do
  cmp -s "$out/$f" "$tmp/local/$f" || fail "$f differs between the Slurm run and the local run"
  n=$((n + 1))
done < <(outputs "$out")
say "PASSED: 20 takes done exactly once through Slurm (one array task cancelled and resubmitted), $n output files identical to a local --jobs=2 run; cluster time $(echo "$t1 - $t0" | bc -l | xargs printf '%.1f') s"
