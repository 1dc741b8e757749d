#!/usr/bin/env bash
# A one-node Slurm on this machine for run_pipeline's Slurm benchmarks (the tests start their
# own: tests/unit/pipeline/local_slurm.h). As root, with slurm-wlm and munge (scripts/setup):
#
#   bench/local_slurm.sh start DIR   # munged, slurmctld, slurmd; prints the SLURM_CONF to export
#   bench/local_slurm.sh stop DIR    # cancels every job, stops the daemons by their pid files
#                                      and waits (bounded) until each is gone
#
# DIR holds slurm.conf, the munge key and socket, pid files, logs, state and spool; keep it
# short (slurmstepd's socket paths in DIR/spool must stay under 108 bytes), e.g. /tmp/cjs.
set -euo pipefail
cmd="${1:?start|stop}"; dir="${2:?folder}"
if [ "$cmd" = stop ]; then
  export SLURM_CONF="$dir/slurm.conf"
  scancel --full --quiet --user=root 2>/dev/null || true
  for i in $(seq 50); do [ -z "$(squeue --noheader --format=%i 2>/dev/null)" ] && break; sleep 0.2; done
  # each daemon gone (a zombie counts: it holds nothing) before the next start: 10 s, then SIGKILL
  alive() { local s; s="$(ps -o stat= -p "$1" 2>/dev/null)"; [ -n "$s" ] && [ "${s:0:1}" != Z ]; }
  for d in slurmd slurmctld munged; do
    pid="$(cat "$dir/$d.pid" 2>/dev/null || true)"
    [ -n "$pid" ] && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$d" ] || continue
    kill "$pid" 2>/dev/null || true
    for i in $(seq 100); do alive "$pid" || break; sleep 0.1; done
    alive "$pid" && { echo "local_slurm.sh: $d $pid still there 10 s after SIGTERM; SIGKILL" >&2; kill -9 "$pid" 2>/dev/null || true; }
  done
  exit 0
fi
[ "$(id -u)" -eq 0 ] || { echo "local_slurm.sh: run as root" >&2; exit 1; }
mkdir -p "$dir/state" "$dir/spool"
host="$(hostname -s)"; cpus="$(nproc)"
port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
head -c 1024 /dev/urandom > "$dir/munge.key"; chmod 400 "$dir/munge.key"
cat > "$dir/slurm.conf" <<CONF
ClusterName=clearjoint_bench
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$(port)
SlurmdPort=$(port)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
KillWait=5
MinJobAge=300
MaxJobCount=100000
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=bench Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
munged -f --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munged.seed"
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N "$host"
for i in $(seq 300); do
  [ "$(sinfo --noheader --format=%T --nodes="$host" 2>/dev/null)" = idle ] && { echo "export SLURM_CONF=$SLURM_CONF"; exit 0; }
  sleep 0.2
done
echo "local_slurm.sh: the node did not become idle; see $dir/slurmd.log" >&2
exit 1
