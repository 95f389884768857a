#!/usr/bin/env bash
# The job array of docs/sweeps.md, run on a real Slurm (single node, started
# here), merged, and checked against the same sweep run in one process.
#
#   sudo bash xtask/scripts/slurm-check.sh        (or: cargo xtask slurm-check)
#
# Needs root and Debian's packages (apt-get): installs slurmctld, slurmd,
# slurm-client and munge, starts munged, then slurmctld and slurmd in the
# foreground with a generated slurm.conf (no cgroups, no accounting), under
# target/slurm-check/. Then:
#   1. submits the docs' array (SHARDS tasks × PER_SHARD maps), waits, merges
#      the shards and checks the merged summary is byte-identical to the
#      summary of the same sweep run in one process (and the records too);
#   2. submits it again with KILL_COUNT maps a shard, kills task 2 with
#      SIGKILL while it runs, and checks that the merge refuses, naming
#      shard 2, and that the killed task left no shard file;
#   3. stops the daemons it started.
# Prints the job ids, per-task timings and checksums (recorded in
# docs/sweeps.md). Not part of .ci/run: it needs root and minutes.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
WORK="${SLURM_CHECK_DIR:-$ROOT/target/slurm-check}"
SHARDS="${SHARDS:-4}"
PER_SHARD="${PER_SHARD:-50}"
KILL_COUNT="${KILL_COUNT:-1500}"
SWEEP_ARGS=(--planners dtc,grid-cover,rect-priority --size 32 --density 0.2 --seed 0 --generator connected)

say() { printf 'slurm-check: %s\n' "$*"; }
die() { printf 'slurm-check: error: %s\n' "$*" >&2; exit 2; }

[ "$(id -u)" = 0 ] || die "needs root (it installs packages and starts daemons)"
command -v apt-get >/dev/null || die "needs apt-get (Debian or Ubuntu) to install Slurm and munge"

say "installing slurmctld, slurmd, slurm-client, munge"
DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurmctld slurmd slurm-client munge >/dev/null
say "slurm $(dpkg-query -W -f='${Version}' slurmctld), munge $(dpkg-query -W -f='${Version}' munge)"

# munge: the key the package made, the daemon as its own user.
[ -s /etc/munge/munge.key ] || mungekey --create
mkdir -p /run/munge && chown munge:munge /run/munge
STARTED_MUNGE=0
if ! pgrep -x munged >/dev/null; then
    runuser -u munge -- /usr/sbin/munged
    STARTED_MUNGE=1
fi
munge -n | unmunge >/dev/null || die "munge does not authenticate"

HOST="$(hostname -s)"
CPUS="$(nproc)"
MEM="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"
rm -rf "$WORK"
mkdir -p "$WORK"/{state,spool,logs,results,killed}
export SLURM_CONF="$WORK/slurm.conf"
cat > "$SLURM_CONF" <<EOF
ClusterName=oxcover-check
SlurmctldHost=$HOST
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MinJobAge=3600
NodeName=$HOST CPUs=$CPUS RealMemory=$MEM State=UNKNOWN
PartitionName=check Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF

say "starting slurmctld and slurmd ($HOST, $CPUS CPUs)"
slurmctld -D -i -f "$SLURM_CONF" >"$WORK/slurmctld.out" 2>&1 &
CTLD=$!
slurmd -D -f "$SLURM_CONF" >"$WORK/slurmd.out" 2>&1 &
SLURMD=$!
cleanup() {
    kill "$SLURMD" "$CTLD" 2>/dev/null || true
    wait "$SLURMD" "$CTLD" 2>/dev/null || true
    if [ "$STARTED_MUNGE" = 1 ]; then pkill -x munged || true; fi
    say "stopped the cluster"
}
trap cleanup EXIT
for _ in $(seq 120); do
    state="$(sinfo -h -n "$HOST" -o %t 2>/dev/null || true)"
    [ "$state" = idle ] && break
    sleep 0.5
done
[ "$state" = idle ] || die "the node did not come up (state '$state'; see $WORK/slurmctld.log, $WORK/slurmd.log)"
say "node $HOST is idle"

say "building xtask once, before the array (docs/sweeps.md)"
(cd "$ROOT" && cargo build --release --locked -p xtask --quiet)

# The job array of docs/sweeps.md at this cluster's size.
cat > "$WORK/sweep.sbatch" <<EOF
#!/bin/bash
#SBATCH --job-name=oxcover-sweep
#SBATCH --array=0-$((SHARDS - 1))
#SBATCH --cpus-per-task=1
#SBATCH --output=$WORK/logs/sweep-%A_%a.out
set -euo pipefail
cd "$ROOT"
export RAYON_NUM_THREADS="\$SLURM_CPUS_PER_TASK"
echo "start \$(date +%s.%N) task \$SLURM_ARRAY_TASK_ID of job \$SLURM_ARRAY_JOB_ID on \$(hostname)"
cargo xtask sweep ${SWEEP_ARGS[*]} --count "\$SWEEP_COUNT" \\
    --shard "\${SLURM_ARRAY_TASK_ID}/\${SLURM_ARRAY_TASK_COUNT}" \\
    --out "\$SWEEP_OUT/sweep-\${SLURM_ARRAY_TASK_ID}.jsonl"
echo "end \$(date +%s.%N)"
EOF

wait_for() { # job id, seconds
    for _ in $(seq $(($2 * 5))); do
        [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
        sleep 0.2
    done
    die "job $1 still running after $2 s"
}

tasks() { # job id: one line per array task
    scontrol -o show job "$1" | tr ' ' '\n' | awk -F= '
        $1 == "ArrayTaskId" {id = $2}
        $1 == "JobState" {st = $2}
        $1 == "ExitCode" {ec = $2}
        $1 == "RunTime" {rt = $2}
        $1 == "StartTime" {s = $2}
        $1 == "EndTime" {print "  task " id ": " st ", exit " ec ", run time " rt " (" s " to " $2 ")"}' |
        sort -t: -k1,1V
}

# 1. The whole array, merged, against one process.
COUNT=$((SHARDS * PER_SHARD))
say "submitting $SHARDS tasks x $PER_SHARD maps ($COUNT maps)"
T0="$(date +%s.%N)"
JOB="$(cd "$ROOT" && SWEEP_COUNT=$COUNT SWEEP_OUT="$WORK/results" sbatch --parsable "$WORK/sweep.sbatch")"
say "job array $JOB submitted"
wait_for "$JOB" 600
T1="$(date +%s.%N)"
tasks "$JOB"
say "array wall time $(awk -v a="$T0" -v b="$T1" 'BEGIN {printf "%.2f", b - a}') s"
for f in "$WORK"/logs/sweep-"$JOB"_*.out; do
    awk -v f="$(basename "$f")" '/^start/ {s = $2} /^end/ {printf "  %s: %.2f s in the task script\n", f, $2 - s}' "$f"
done
n_ok="$(scontrol -o show job "$JOB" | grep -c 'JobState=COMPLETED' || true)"
[ "$n_ok" = "$SHARDS" ] || die "only $n_ok of $SHARDS tasks completed (see $WORK/logs)"

cd "$ROOT"
cargo xtask merge "$WORK"/results/sweep-*.jsonl --out "$WORK/results/summary.json"
say "the same sweep in one process"
T2="$(date +%s.%N)"
cargo xtask sweep "${SWEEP_ARGS[@]}" --count "$COUNT" --out "$WORK/single.jsonl" --summary "$WORK/single-summary.json"
T3="$(date +%s.%N)"
say "one process: $(awk -v a="$T2" -v b="$T3" 'BEGIN {printf "%.2f", b - a}') s"
sha_merged="$(sha256sum "$WORK/results/summary.json" | cut -d' ' -f1)"
sha_single="$(sha256sum "$WORK/single-summary.json" | cut -d' ' -f1)"
say "merged summary     sha256 $sha_merged"
say "one-process summary sha256 $sha_single"
[ "$sha_merged" = "$sha_single" ] || die "the merged summary differs from the one-process summary"
records() { grep -hv '^{"sweep"' "$@" | LC_ALL=C sort; }
[ "$(records "$WORK"/results/sweep-*.jsonl | sha256sum)" = "$(records "$WORK/single.jsonl" | sha256sum)" ] ||
    die "the shards' records differ from the one-process records"
say "records sha256 $(records "$WORK/single.jsonl" | sha256sum | cut -d' ' -f1) (both)"

# 2. A task killed while it runs: the merge must name its shard.
KCOUNT=$((SHARDS * KILL_COUNT))
say "submitting again with $KILL_COUNT maps a shard; task 2 will be killed"
KJOB="$(SWEEP_COUNT=$KCOUNT SWEEP_OUT="$WORK/killed" sbatch --parsable "$WORK/sweep.sbatch")"
for _ in $(seq 3000); do
    st="$(squeue -h -j "${KJOB}_2" -o %T 2>/dev/null || true)"
    [ "$st" = RUNNING ] && break
    sleep 0.1
done
[ "$st" = RUNNING ] || die "task ${KJOB}_2 never ran (state '$st')"
sleep 1
scancel --signal=KILL --full "${KJOB}_2"
say "scancel --signal=KILL --full ${KJOB}_2, one second into its sweep"
wait_for "$KJOB" 1200
tasks "$KJOB"
[ ! -e "$WORK/killed/sweep-2.jsonl" ] || die "the killed task left a shard file"
set +e
ls -a "$WORK/killed" | sed 's/^/  killed run folder: /'
merge_out="$(RUST_BACKTRACE=0 cargo xtask merge "$WORK"/killed/sweep-*.jsonl --out "$WORK/killed/summary.json" 2>&1)"
merge_status=$?
set -e
say "merge of the killed run: exit $merge_status: $(printf '%s' "$merge_out" | grep '^Error' || true)"
[ "$merge_status" != 0 ] || die "the merge accepted a sweep with a killed task"
printf '%s' "$merge_out" | grep -q "shard 2/$SHARDS of the sweep is missing" || die "the merge did not name shard 2"
[ ! -e "$WORK/killed/summary.json" ] || die "the refused merge wrote a summary"
say "passed: merged summary identical to one process; the killed shard refused by name"
