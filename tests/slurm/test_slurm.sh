#!/usr/bin/env bash
# The documented Slurm script (scripts/slurm/skyspec-job.sbatch) run for real: a single-node Slurm
# on localhost (munged, slurmctld, slurmd from Debian's munge and slurm-wlm, in a scratch folder,
# no systemd; stopped afterwards). A job submitted as an array of shards plus an afterany collect
# step gives the same files as the job run here; a shard that fails does not leave the collect step
# waiting: it runs, reports the failed task and exits 4.
# Usage: test_slurm.sh path/to/skyspec
skyspec=$(realpath "$1")
source "$(dirname "$0")/../cli/lib.sh"
sbatch_script=$(realpath "$(dirname "$0")/../../scripts/slurm/skyspec-job.sbatch")
for tool in munged slurmctld slurmd sbatch; do
  command -v $tool >/dev/null || { echo "FAIL: $tool not installed (munge, slurm-wlm)"; exit 1; }
done

d=$work/slurm
mkdir -p "$d/state" "$d/spool"
head -c 1024 /dev/urandom >"$d/munge.key"
chmod 600 "$d/munge.key"
pids=()
cleanup() {
  kill "${pids[@]}" 2>/dev/null
  [ -f "$d/munged.pid" ] && kill "$(cat "$d/munged.pid")" 2>/dev/null
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
munged -f -S "$d/munge.sock" --key-file="$d/munge.key" --log-file="$d/munged.log" --pid-file="$d/munged.pid" \
  --seed-file="$d/munged.seed" || { echo "FAIL: munged did not start"; exit 1; }
host=$(hostname)
read -r port1 port2 < <(/usr/bin/python3 -c "
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(('127.0.0.1', 0))
print(*[x.getsockname()[1] for x in s])")
cat >"$d/slurm.conf" <<CONF
ClusterName=skyspectest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port1
SlurmdPort=$port2
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
AuthType=auth/munge
AuthInfo=socket=$d/munge.sock
CredType=cred/munge
ProctrackType=proctrack/pgid
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$d/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$d/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >"$d/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
# last_lines FILE...: the last 3 lines of each file, named (GNU tail refuses `tail -3 A B`).
last_lines() { for f in "$@"; do [ -f "$f" ] && { echo "== $(basename "$f")"; tail -n 3 "$f"; }; done; }
if ! sinfo -h -o %t | grep -q idle; then
  # A machine without a cgroup file system (some containers) cannot run slurmd at all: said in one
  # line, as a skip (CTest: SKIP_RETURN_CODE 77), not a failure of skyspec.
  reason=$(grep -hi -m1 'cgroup' "$d/slurmd.log" "$d/slurmd.out" 2>/dev/null)
  if [ -n "$reason" ] && ! kill -0 "${pids[-1]}" 2>/dev/null; then
    echo "SKIP slurm_job: slurmd cannot start on this machine: $reason"
    exit 77
  fi
  bad "the Slurm node did not come up: $(last_lines "$d/slurmctld.log" "$d/slurmd.log" "$d/slurmd.out")"
  finish slurm_job
  exit 1
fi
ok

# submit JOB OUT N: the array and the collect step, as docs/jobs.md says; prints the collect job id.
submit() {
  local array
  array=$(sbatch --parsable --chdir="$work" --export=ALL,SKYSPEC="$skyspec" --array=1-$3 "$sbatch_script" "$1" "$2" "$3")
  sbatch --parsable --chdir="$work" --dependency=afterany:"$array" --export=ALL,SKYSPEC="$skyspec",SKYSPEC_COLLECT=1 \
    "$sbatch_script" "$1" "$2"
}
# wait_done JOBID: until Slurm no longer lists it (at most 120 s).
wait_done() {
  for _ in $(seq 600); do
    [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
    sleep 0.2
  done
  return 1
}

# The small job of cli_job, here first, then moved aside; then on Slurm into the same folder.
cp "$(dirname "$0")/../data/jobs/small.toml" "$(dirname "$0")/../data/jobs/mixed.toml" "$work/"
"$skyspec" job run "$work/small.toml" --out "$work/S" --shard 1/1 --threads 1 --quiet || bad "the job here failed"
mv "$work/S" "$work/S-here"
collect=$(submit "$work/small.toml" "$work/S" 3)
wait_done "$collect" && ok || bad "the collect step did not end"
(cd "$work/S" && sha256sum tasks/*.exr tasks/*.png irradiance_*.csv) >"$work/slurm.sha" 2>/dev/null
(cd "$work/S-here" && sha256sum tasks/*.exr tasks/*.png irradiance_*.csv) >"$work/here.sha"
[ -s "$work/here.sha" ] && cmp -s "$work/slurm.sha" "$work/here.sha" && ok || bad "Slurm and the run here wrote different files"
grep -q "12 task(s) done" "$work/skyspec-${collect}_"*.log "$work/skyspec-${collect}.log" 2>/dev/null && ok ||
  bad "collect log: $(cat "$work"/skyspec-"$collect"*.log)"

# A shard that fails (task t000002 has bad input): the collect step still runs and exits 4.
collect=$(submit "$work/mixed.toml" "$work/M" 2)
wait_done "$collect" && ok || bad "after a failed shard the collect step did not run"
log=$(cat "$work"/skyspec-"$collect"*.log 2>/dev/null)
grep -q "3 task(s) done, 1 failed" <<<"$log" && grep -q "t000002: atmosphere.ozone.peak_m" <<<"$log" && ok ||
  bad "collect after a failed shard: $log"
grep -q "ExitCode=4:0" < <(scontrol show job "$collect" 2>/dev/null) && ok || bad "the collect step's exit code: $(scontrol show job "$collect" | grep ExitCode)"

# Interpolated tables as docs/jobs.md submits them: the grid's sets first, an array task per set
# (SKYSPEC_TABLE_SETS=1) into the shared table cache, then the shards (afterany) and the collect
# step; two aerosol amounts on the grid's nodes, two sets (cli_budget builds a blend's). Every set's task succeeds, the cache then holds those sets and no more, and both tasks are
# done. Not under the sanitizers: the builds take minutes there.
if [ -n "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  echo "SKIP slurm table sets: they build tables, left to the release stage"
else
  export SKYSPEC_CACHE_DIR="$work/grid-cache"
  printf '[job]\nname = "grid"\nproduce = ["exr"]\n[scene]\ncamera.width = 8\ncamera.height = 8\nrender.ms_altitude_samples = 8\nrender.ms_sun_samples = 16\nrender.scattering_orders = 2\nrender.ms_tables = "interpolated"\natmosphere.mie.angstrom_exponent = 0\n[axes]\n"atmosphere.mie.scattering_per_m" = [1e-5, 2e-5]\n' \
    >"$work/grid.toml"
  sets=$("$skyspec" job plan "$work/grid.toml" --out "$work/G" --json |
    /usr/bin/python3 -c 'import json, sys; print(",".join(map(str, json.load(sys.stdin)["table_sets"])))')
  count=$(tr ',' '\n' <<<"$sets" | grep -c .)
  tables=$(sbatch --parsable --chdir="$work" --export=ALL,SKYSPEC="$skyspec",SKYSPEC_TABLE_SETS=1 --array="$sets" \
    "$sbatch_script" "$work/grid.toml" "$work/G")
  array=$(sbatch --parsable --chdir="$work" --dependency=afterany:"$tables" --export=ALL,SKYSPEC="$skyspec" --array=1-2 \
    "$sbatch_script" "$work/grid.toml" "$work/G" 2)
  collect=$(sbatch --parsable --chdir="$work" --dependency=afterany:"$array" \
    --export=ALL,SKYSPEC="$skyspec",SKYSPEC_COLLECT=1 "$sbatch_script" "$work/grid.toml" "$work/G")
  wait_done "$collect" && ok || bad "the interpolated job's collect step did not end"
  failed=""
  for k in ${sets//,/ }; do
    grep -q "ExitCode=0:0" < <(scontrol show job "${tables}_$k" 2>/dev/null) || failed+=" $k"
  done
  [ "$count" -ge 2 ] && [ -z "$failed" ] && ok || bad "table sets '$sets': these did not end with 0:$failed"
  [ "$(ls "$work/grid-cache" | grep -c '^orders-')" = "$count" ] && ok \
    || bad "the cache holds $(ls "$work/grid-cache" | grep -c '^orders-') sets, the plan listed $count"
  grep -q "2 task(s) done" "$work"/skyspec-"$collect"*.log 2>/dev/null && ok \
    || bad "the interpolated job's collect: $(cat "$work"/skyspec-"$collect"*.log 2>/dev/null)"
fi
finish slurm_job
