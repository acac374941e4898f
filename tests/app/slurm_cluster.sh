#!/bin/bash
# A one-node SLURM cluster on this machine, from Debian's slurm-wlm and munge, for tests/test_slurm.cpp.
#   slurm_cluster.sh start DIR   start munged, slurmctld and slurmd with a configuration under DIR; prints
#                                the SLURM_CONF to export; waits until the node is idle
#   slurm_cluster.sh stop DIR    stop the daemons started by `start DIR`
# The daemons run as root (as the CI does), on ports of their own, with state, spool and logs under DIR.
set -euo pipefail
cmd=$1 dir=$(readlink -f "$2")
conf=$dir/slurm.conf
case "$cmd" in
start)
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge" "$dir/log"
  # A cluster of an earlier, killed test on the same ports would answer instead of ours.
  pkill -9 -f "slurm(ctld|d) -f .*/siloscope_slurm\..*/cluster/slurm.conf" 2>/dev/null || true
  # A munged that answers is used as it is; otherwise one is started (a zombie or stale socket does not count).
  if ! (munge -n 2>/dev/null | unmunge >/dev/null 2>&1); then
    mkdir -p /run/munge && chown munge:munge /run/munge 2>/dev/null || true
    if [ ! -s /etc/munge/munge.key ]; then
      (mungekey --create 2>/dev/null || create-munge-key -f) >/dev/null 2>&1
    fi
    # As the munge user where possible (munged refuses root without --force).
    # (The munge user must reach the pid file: a private temporary directory falls back to root.)
    if ! { id munge >/dev/null 2>&1 && chown munge "$dir/munge" 2>/dev/null &&
           runuser -u munge -- munged --pid-file="$dir/munge/munged.pid" 2>>"$dir/log/munged.log"; }; then
      munged --force --pid-file="$dir/munge/munged.pid" 2>>"$dir/log/munged.log"
    fi
    touch "$dir/started_munged"
  fi
  # slurmctld needs a working munge at once: wait until a credential round-trips.
  for _ in $(seq 50); do
    munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break
    sleep 0.2
  done
  host=$(hostname -s)
  cpus=$(nproc)
  # batch_sched_delay=0: a finished task's core is given to the next one at once, not at the next 3 s
  # scheduling pass (the default), which made a test's array of short tasks wait 3 s per round.
  cat > "$conf" <<CONF
ClusterName=siloscope-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$conf
  slurmctld -f "$conf" -i
  slurmd -f "$conf"
  for _ in $(seq 60); do
    state=$(sinfo -h -N -o %t 2>/dev/null | head -n 1 || true)
    [ "$state" = "idle" ] && break
    sleep 0.5
  done
  if [ "${state:-}" != "idle" ]; then
    echo "slurm_cluster: the node did not become idle (state '${state:-none}'); logs in $dir/log" >&2
    tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
    exit 1
  fi
  echo "$conf"
  ;;
stop)
  export SLURM_CONF=$conf
  for f in "$dir/slurmd.pid" "$dir/slurmctld.pid"; do
    [ -s "$f" ] && kill "$(cat "$f")" 2>/dev/null || true
  done
  if [ -e "$dir/started_munged" ] && [ -s "$dir/munge/munged.pid" ]; then
    kill "$(cat "$dir/munge/munged.pid")" 2>/dev/null || true
  fi
  # Wait until the daemons are gone, so that the next cluster can take the same ports.
  for _ in $(seq 50); do
    pgrep -f "slurm(ctld|d) -f $conf" >/dev/null || break
    sleep 0.2
  done
  pkill -9 -f "slurm(ctld|d) -f $conf" 2>/dev/null || true
  ;;
esac
