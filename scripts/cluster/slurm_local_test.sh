#!/usr/bin/env bash
# End-to-end test of the Slurm templates (scripts/cluster/interiornet.sbatch and
# interiornet-array.sbatch; docs/cluster.md) on a real, throwaway one-node Slurm cluster that
# this script starts on this machine: its own munged, slurmctld and slurmd, with every file
# (config, key, state, spool, logs, build folders) under one temporary folder.
#
# Usage: scripts/cluster/slurm_local_test.sh [--install] [--requeue] [--keep] [INTERIORNET]
#   INTERIORNET  the interiornet binary (default: build/apps/interiornet under the repo root)
#   --install    apt-get install the Slurm and MUNGE packages when they are missing
#   --requeue    also test INTERIORNET_REQUEUE=1 (the job requeues itself after the time-limit
#                signal until the build is complete; adds some 3 minutes: Slurm holds a requeued
#                job back for about two minutes before it starts it again)
#   --keep       keep the temporary folder (logs, build folders) and print where it is
#
# Checks, on the tiny spec below (2 layouts, 5 work units, 14 frames):
#   0. a plain local `dataset build` (the reference bytes; timed)
#   1. sbatch --wait of interiornet.sbatch with 3 tasks (1 coordinator + 2 workers, 1 CPU each):
#      the job completes, ran as 3 MPI ranks, `status --json` has every unit done and none
#      failed, `verify` passes, and data/ is byte-identical (diff -r) to the reference
#   2. the same plan in a new folder, submitted with a 1-minute limit and --signal=TERM@59:
#      Slurm's time-limit signal stops the ranks mid-build, the job ends with 143, `status`
#      shows no unit running and some pending, `verify` passes on what is done; resubmitted,
#      the build completes and data/ is byte-identical to the reference
#   3. interiornet-array.sbatch: the spec cut into two one-layout slices (first_seed/count),
#      one folder per array task: both complete and verify, and their data/ trees together are
#      byte-identical to the reference
#   4. (--requeue) as 2, with INTERIORNET_REQUEUE=1: one submission completes the build
#
# Exit status: 0 every check passed; 1 a check failed ("FAILED check NAME: ..." on stderr);
# 77 Slurm cannot run here (not root, packages missing without --install, a daemon does not
# start, the node never comes up, no PMIx plugin): one line on stderr says why. 77 is the
# "skipped" code of Automake and of ctest's SKIP_RETURN_CODE; CI counts it as skipped.
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
install=0 requeue=0 keep=0 bin=""
for a in "$@"; do
  case "$a" in
    --install) install=1 ;;
    --requeue) requeue=1 ;;
    --keep) keep=1 ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "slurm_local_test: unknown option $a" >&2; exit 2 ;;
    *) bin=$a ;;
  esac
done

skip() { echo "slurm_local_test: skipped: $*" >&2; exit 77; }
fail() { echo "slurm_local_test: FAILED check $1: ${2:-}" >&2; exit 1; }
say() { echo "[$(date +%T)] $*"; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN{printf "%.1f", b - a}'; }

bin=${bin:-$repo/build/apps/interiornet}
[ -x "$bin" ] || fail binary "$bin is not an executable file (build it, or pass its path)"
bin=$(readlink -f "$bin")

# A clean environment: not inside someone's Slurm job or MPI launch.
for v in $(env | sed -n 's/^\(SLURM_[A-Za-z0-9_]*\|SBATCH_[A-Za-z0-9_]*\|SALLOC_[A-Za-z0-9_]*\|SRUN_[A-Za-z0-9_]*\|PMIX_[A-Za-z0-9_]*\|OMPI_[A-Za-z0-9_]*\)=.*/\1/p'); do
  unset "$v"
done

# ---- packages and privileges ---------------------------------------------------------------
[ "$(id -u)" = 0 ] || skip "needs root: slurmd runs as root (SlurmUser=root in its slurm.conf)"
tools=(munged munge slurmctld slurmd sbatch srun sinfo squeue scontrol scancel)
missing_tools() {
  local t m=()
  for t in "${tools[@]}"; do command -v "$t" >/dev/null 2>&1 || m+=("$t"); done
  echo "${m[*]:-}"
}
m=$(missing_tools)
if [ -n "$m" ]; then
  [ "$install" = 1 ] || skip "Slurm is not installed (missing: $m); rerun with --install"
  say "installing slurm-wlm munge (missing: $m)"
  export DEBIAN_FRONTEND=noninteractive
  if ! apt-get install -y --no-install-recommends slurm-wlm slurm-wlm-basic-plugins munge \
      >/tmp/slurm_local_test.apt.log 2>&1; then
    apt-get update >>/tmp/slurm_local_test.apt.log 2>&1
    apt-get install -y --no-install-recommends slurm-wlm slurm-wlm-basic-plugins munge \
      >>/tmp/slurm_local_test.apt.log 2>&1 ||
      skip "apt-get install slurm-wlm munge failed (/tmp/slurm_local_test.apt.log)"
  fi
  m=$(missing_tools)
  [ -z "$m" ] || skip "still missing after the install: $m"
fi

# ---- the temporary cluster -----------------------------------------------------------------
T=$(mktemp -d /tmp/inet-slurm.XXXXXX) || skip "cannot make a temporary folder"
chmod 755 "$T"
mkdir -p "$T/munge" "$T/run" "$T/state" "$T/spool" "$T/log" "$T/jobs"
chmod 700 "$T/munge"
export SLURM_CONF=$T/slurm.conf

# stops what this script started, by the pids in its own pid files, then removes $T
stop_pidfile() {
  local f=$1 pid i
  [ -s "$f" ] || return 0
  pid=$(cat "$f")
  kill -0 "$pid" 2>/dev/null || return 0
  kill -TERM "$pid" 2>/dev/null
  for i in $(seq 50); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.2; done
  kill -KILL "$pid" 2>/dev/null
}
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  if [ -s "$T/slurmctld.pid" ] && kill -0 "$(cat "$T/slurmctld.pid")" 2>/dev/null; then
    # end our jobs first so that no slurmstepd outlives its slurmd
    local jobs i
    jobs=$(squeue -h -o %i 2>/dev/null)
    if [ -n "$jobs" ]; then
      scancel $jobs 2>/dev/null
      for i in $(seq 60); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 1; done
    fi
  fi
  stop_pidfile "$T/slurmd.pid"
  stop_pidfile "$T/slurmctld.pid"
  stop_pidfile "$T/munge/munged.pid"
  if [ "$keep" = 1 ]; then
    echo "slurm_local_test: kept $T (logs in $T/log, job logs in $T/jobs)" >&2
  else
    rm -rf "$T"
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# MUNGE, Slurm's authentication: a fresh key, our own socket, run as root (--force)
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$T/munge/munge.key"
munged --force --key-file="$T/munge/munge.key" --socket="$T/run/munge.sock" \
  --pid-file="$T/munge/munged.pid" --seed-file="$T/munge/munged.seed" \
  --log-file="$T/log/munged.log" >"$T/log/munged.out" 2>&1 ||
  skip "munged does not start: $(tail -qn 1 "$T/log/munged.out" "$T/log/munged.log" 2>/dev/null | tr '\n' ' ')"
munge -n -S "$T/run/munge.sock" | unmunge -S "$T/run/munge.sock" >/dev/null 2>&1 ||
  skip "munge cannot encode and decode a credential with its own daemon"

# two free TCP ports on the loopback for slurmctld and slurmd
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
p=$((20000 + RANDOM % 20000))
while ! { port_free "$p" && port_free $((p + 1)); }; do p=$((p + 2)); done

host=$(hostname -s)
cpus=$(nproc)
# RealMemory in MiB: 90 % of MemTotal (slurmd marks a node invalid that has less than it says)
mem=$(awk '/^MemTotal:/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)
cat >"$SLURM_CONF" <<EOF
# one-node test cluster of scripts/cluster/slurm_local_test.sh
ClusterName=inetlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$p
SlurmdPort=$((p + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/run/munge.sock
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# no cgroups: processes tracked by their parent ids, no CPU binding
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
# no accounting, no job completion log, no mail
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MailProg=/bin/true
# keep finished jobs 10 minutes for scontrol show job
MinJobAge=600
KillWait=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
# OverSubscribe=YES: jobs that ask (--oversubscribe) may share CPUs; 3 tasks of one job on
# 2 CPUs take --overcommit
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE OverSubscribe=YES State=UP
EOF

slurmctld -f "$SLURM_CONF" -i >"$T/log/slurmctld.out" 2>&1 ||
  skip "slurmctld does not start: $(tail -qn 2 "$T/log/slurmctld.out" "$T/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
slurmd -f "$SLURM_CONF" -N "$host" >"$T/log/slurmd.out" 2>&1 ||
  skip "slurmd does not start: $(tail -qn 2 "$T/log/slurmd.out" "$T/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
state=""
alive() { [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
for i in $(seq 60); do
  if [ "$i" -ge 3 ]; then  # pid files are written a moment after the daemons fork
    alive "$T/slurmctld.pid" ||
      skip "slurmctld died: $(tail -n 2 "$T/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
    alive "$T/slurmd.pid" ||
      skip "slurmd died: $(tail -n 2 "$T/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
  fi
  state=$(sinfo -h -N -n "$host" -o %t 2>/dev/null | head -n 1)
  [ "$state" = idle ] && break
  sleep 1
done
[ "$state" = idle ] ||
  skip "the node did not come up (state '${state:-none}'; $(sinfo -h -R 2>/dev/null | head -n 1)); logs: $T/log (use --keep)"
srun --mpi=list 2>&1 | grep -qw pmix || skip "this Slurm has no PMIx plugin (srun --mpi=list)"
say "Slurm $(sinfo -V | awk '{print $2}') up: node $host, $cpus CPU(s), ports $p/$((p + 1)), in $T"

# ---- helpers -------------------------------------------------------------------------------
# units_field DIR FIELD: FIELD (pending, running, done, failed) of "units" in status --json
units_field() {
  "$bin" dataset status "$1" --json 2>/dev/null | awk -v f="$2" '
    /"units"[ ]*:[ ]*\{/ {u = 1; next}
    u && /\}/ {u = 0}
    u {line = $0; gsub(/[ ",]/, "", line); split(line, kv, ":"); if (kv[1] == f) print kv[2]}'
}
# job_field JOBID FIELD: FIELD of scontrol show job (JobState, ExitCode, RunTime, Restarts...)
job_field() { scontrol show job -o "$1" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1; }
# submit NAME SBATCH_ARGS...: sbatch --wait, at most 15 minutes; sets jid and jrc
submit() {
  local name=$1 out
  shift
  out=$(timeout 900 sbatch --parsable --wait -D "$T" -o "$T/jobs/$name.out" \
    --export="ALL,INTERIORNET=$bin" "$@")
  jrc=$?
  jid=${out%%;*}
  [ "$jrc" = 124 ] && fail "$name" "the job did not end within 15 minutes ($T/jobs/$name.out)"
  [ -n "$jid" ] || fail "$name" "sbatch gave no job id"
}
# complete NAME DIR: every unit done, none failed, verify passes, data/ is the reference's
complete() {
  local name=$1 dir=$2 pending running done failed
  pending=$(units_field "$dir" pending) running=$(units_field "$dir" running)
  done=$(units_field "$dir" done) failed=$(units_field "$dir" failed)
  [ "$pending/$running/$failed" = 0/0/0 ] && [ "${done:-0}" -gt 0 ] ||
    fail "$name-status" "status --json of $dir: pending $pending, running $running, done $done, failed $failed"
  "$bin" dataset verify "$dir" >"$T/jobs/$name.verify" 2>&1 ||
    fail "$name-verify" "$(tail -n 3 "$T/jobs/$name.verify")"
}
same_bytes() {
  diff -r "$ref/data" "$1" >"$T/jobs/$2.diff" 2>&1 ||
    fail "$2-bytes" "data/ differs from the local build: $(head -n 3 "$T/jobs/$2.diff")"
}
sbatch_script=$here/interiornet.sbatch
array_script=$here/interiornet-array.sbatch

spec() {  # the tiny spec; $1 $2 = first_seed, count of the procedural layouts
  cat <<EOF
version: 1
name: tiny
seed: 3
layouts:
  procedural: {first_seed: $1, count: $2, rooms: [2, 3], furniture: parametric}
sequences: {per_layout: 1, frames: 4, unit_frames: 2}
sparse: {batch: 2}
camera: {width: 48, height: 36, fx: 45, fy: 45}
render: {spp: 1}
imu: 200
EOF
}
spec 0 2 >"$T/tiny.yaml"
"$bin" dataset plan "$T/tiny.yaml" --out "$T/ref" >"$T/jobs/plan.out" 2>&1 ||
  fail plan "$(tail -n 3 "$T/jobs/plan.out")"
units_total=$(units_field "$T/ref" pending)
ref=$T/ref

# ---- 0. the reference: a plain local build ---------------------------------------------------
say "0. local build, 2 threads (the reference)"
t=$(now)
"$bin" dataset build "$ref" --threads 2 --no-progress >"$T/jobs/local.out" 2>&1 ||
  fail local-build "$(tail -n 3 "$T/jobs/local.out")"
local_s=$(since "$t")
complete local "$ref"
say "   $units_total units in $local_s s"

# ---- 1. MPI job: 1 coordinator + 2 workers -----------------------------------------------------
say "1. sbatch --wait -n 3 -c 1 interiornet.sbatch"
mkdir "$T/slurm1" && cp "$ref/plan.json" "$T/slurm1/"
t=$(now)
submit slurm1 -n 3 -c 1 --overcommit --time=10 "$sbatch_script" "$T/slurm1"
slurm1_s=$(since "$t")
[ "$jrc" = 0 ] && [ "$(job_field "$jid" JobState)" = COMPLETED ] ||
  fail slurm1-job "job $jid: exit $jrc, state $(job_field "$jid" JobState) ($(tail -n 5 "$T/jobs/slurm1.out" | tr '\n' ' '))"
grep -q "^3 rank(s): 1 coordinator, 2 worker(s)" "$T/jobs/slurm1.out" ||
  fail slurm1-mpi "the job did not run as one 3-rank MPI build (srun --mpi=pmix): see $T/jobs/slurm1.out"
complete slurm1 "$T/slurm1"
same_bytes "$T/slurm1/data" slurm1
slurm1_run=$(job_field "$jid" RunTime)
slurm1_build=$(sed -n 's/^ran .* in \([0-9.]*\) s .*/\1/p' "$T/jobs/slurm1.out")
say "   job $jid COMPLETED: job run time $slurm1_run, build $slurm1_build s, sbatch --wait $slurm1_s s; verify and diff -r pass"

# ---- 2. stopped by the time-limit signal, then resumed ------------------------------------------
say "2. sbatch --wait -n 2 --time=1 --signal=TERM@59 (Slurm's SIGTERM mid-build), then again"
stopped_by=""
for attempt in 1 2; do
  d=$T/slurm2_$attempt
  mkdir "$d" && cp "$ref/plan.json" "$d/"
  if [ "$attempt" = 1 ]; then
    submit slurm2-stop -n 2 -c 1 --overcommit --time=1 --signal=TERM@59 "$sbatch_script" "$d"
    if [ "$jrc" = 0 ] && [ "$(units_field "$d" pending)" = 0 ]; then
      # slurmctld looks at time limits every 30 s: here its signal came after the build's end
      say "   job $jid finished before Slurm's signal came; stopping the next with scancel --signal=TERM"
      continue
    fi
    stopped_by="the time-limit signal (--signal=TERM@59, --time=1)"
  else
    # the fallback: the same signal, sent by hand once the first unit is done
    jid=$(sbatch --parsable -D "$T" -o "$T/jobs/slurm2-stop.out" --open-mode=append \
      --export="ALL,INTERIORNET=$bin" -n 2 -c 1 --overcommit --time=10 "$sbatch_script" "$d")
    for i in $(seq 300); do
      [ "$(units_field "$d" done)" -ge 1 ] 2>/dev/null && break
      sleep 0.5
    done
    scancel --signal=TERM "$jid"
    for i in $(seq 120); do [ -z "$(squeue -h -j "$jid" -o %i 2>/dev/null)" ] && break; sleep 1; done
    jrc=$(job_field "$jid" ExitCode)
    jrc=${jrc%%:*}
    stopped_by="scancel --signal=TERM"
  fi
  break
done
[ "$jrc" = 143 ] ||
  fail slurm2-stop "job $jid stopped by $stopped_by exited $jrc, not 143: $(tail -n 5 "$T/jobs/slurm2-stop.out" | tr '\n' ' ')"
grep -q "stopped by SIGTERM" "$T/jobs/slurm2-stop.out" ||
  fail slurm2-stop "no rank says 'stopped by SIGTERM' in $T/jobs/slurm2-stop.out"
running=$(units_field "$d" running) pending=$(units_field "$d" pending)
done_before=$(units_field "$d" done) failed=$(units_field "$d" failed)
[ "$running" = 0 ] && [ "$failed" = 0 ] && [ "${pending:-0}" -gt 0 ] ||
  fail slurm2-stopped-status "after the stop: running $running, pending $pending, failed $failed (want 0, > 0, 0)"
"$bin" dataset verify "$d" >"$T/jobs/slurm2-stop.verify" 2>&1 ||
  fail slurm2-stopped-verify "$(tail -n 3 "$T/jobs/slurm2-stop.verify")"
say "   job $jid stopped by $stopped_by: exit 143, $done_before of $units_total units done, $pending pending, none running; verify passes"
t=$(now)
submit slurm2-resume -n 3 -c 1 --overcommit --time=10 "$sbatch_script" "$d"
resume_s=$(since "$t")
[ "$jrc" = 0 ] || fail slurm2-resume "job $jid exit $jrc: $(tail -n 5 "$T/jobs/slurm2-resume.out" | tr '\n' ' ')"
complete slurm2-resume "$d"
same_bytes "$d/data" slurm2-resume
say "   resubmitted as job $jid: COMPLETED in $resume_s s, verify and diff -r pass"

# ---- 3. job array: one folder per task ----------------------------------------------------------
say "3. sbatch --wait --array=1-2 interiornet-array.sbatch (one one-layout slice per task)"
: >"$T/folders.txt"
for k in 0 1; do
  spec "$k" 1 >"$T/slice$k.yaml"
  "$bin" dataset plan "$T/slice$k.yaml" --out "$T/slice$k" >>"$T/jobs/plan.out" 2>&1 ||
    fail array-plan "$(tail -n 3 "$T/jobs/plan.out")"
  echo "$T/slice$k" >>"$T/folders.txt"
done
t=$(now)
out=$(timeout 900 sbatch --parsable --wait -D "$T" -o "$T/jobs/array-%a.out" \
  --export="ALL,INTERIORNET=$bin" --array=1-2 -c 1 --time=10 "$array_script" "$T/folders.txt")
jrc=$?
array_s=$(since "$t")
jid=${out%%;*}
[ "$jrc" = 0 ] || fail array-job "array job $jid: exit $jrc ($(tail -qn 3 "$T"/jobs/array-*.out | tr '\n' ' '))"
for k in 0 1; do complete "array-$k" "$T/slice$k"; done
common=$(comm -12 <(cd "$T/slice0/data" && find . -type f | sort) <(cd "$T/slice1/data" && find . -type f | sort))
[ -z "$common" ] || fail array-disjoint "both slices wrote $(echo "$common" | head -n 1)"
mkdir "$T/merged"
cp -r "$T/slice0/data/." "$T/slice1/data/." "$T/merged/"
same_bytes "$T/merged" array
say "   array job $jid: both tasks COMPLETED in $array_s s; each slice verifies; together they are the reference's bytes"

# ---- 4. (--requeue) the job requeues itself until the build is complete ---------------------------
if [ "$requeue" = 1 ]; then
  say "4. INTERIORNET_REQUEUE=1 sbatch --wait -n 2 --time=1 --signal=TERM@59"
  d=$T/slurm4
  mkdir "$d" && cp "$ref/plan.json" "$d/"
  t=$(now)
  out=$(INTERIORNET_REQUEUE=1 timeout 900 sbatch --parsable --wait -D "$T" -o "$T/jobs/requeue.out" \
    --export="ALL,INTERIORNET=$bin" -n 2 -c 1 --overcommit --time=1 --signal=TERM@59 \
    "$sbatch_script" "$d")
  jrc=$?
  requeue_s=$(since "$t")
  jid=${out%%;*}
  [ "$jrc" = 0 ] && [ "$(job_field "$jid" JobState)" = COMPLETED ] ||
    fail requeue-job "job $jid: exit $jrc, state $(job_field "$jid" JobState)"
  complete requeue "$d"
  same_bytes "$d/data" requeue
  restarts=$(job_field "$jid" Restarts)
  if [ "${restarts:-0}" -ge 1 ]; then
    say "   job $jid requeued itself $restarts time(s), COMPLETED in $requeue_s s; verify and diff -r pass"
  else
    say "   job $jid finished before Slurm's signal came (not requeued); verify and diff -r pass"
  fi
fi

say "all checks passed. local build $local_s s; Slurm 3-rank job: build $slurm1_build s, job run time $slurm1_run, sbatch --wait $slurm1_s s"
exit 0
