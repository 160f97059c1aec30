#!/bin/bash
# A real one-node Slurm cluster for the cohort's cluster test, in a folder of its own: slurmctld
# and slurmd as this user, no munge (auth/none), ports found free, everything under DIR.
#   vpSlurmCluster.sh start DIR   prints the SLURM_CONF to use once the node is idle (30 s at most)
#   vpSlurmCluster.sh stop DIR    stops both daemons
set -euo pipefail
action=${1:?usage: vpSlurmCluster.sh start|stop DIR} dir=${2:?usage: vpSlurmCluster.sh start|stop DIR}
case "$action" in
  start)
    command -v slurmctld >/dev/null && command -v slurmd >/dev/null || { echo "slurm-wlm is not installed" >&2; exit 3; }
    mkdir -p "$dir/state" "$dir/spool"
    port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
    host=$(hostname -s) user=$(id -un) cpus=$(nproc)
    cat > "$dir/slurm.conf" <<CONF
ClusterName=vptest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$(port)
SlurmdPort=$(port)
AuthType=auth/none
CredType=cred/none
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
    export SLURM_CONF=$dir/slurm.conf
    slurmctld -i
    slurmd -N "$host"
    for _ in $(seq 150); do
      if sinfo -h -o %t 2>/dev/null | grep -qE '^idle'; then
        echo "$SLURM_CONF"
        exit 0
      fi
      sleep 0.2
    done
    echo "the Slurm node did not become idle in 30 s (see $dir/slurmctld.log, $dir/slurmd.log)" >&2
    exit 1
    ;;
  stop)
    for daemon in slurmd slurmctld; do
      [ -f "$dir/$daemon.pid" ] && kill "$(cat "$dir/$daemon.pid")" 2>/dev/null || true
    done
    ;;
esac
