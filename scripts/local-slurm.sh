#!/usr/bin/env bash
# local-slurm.sh start|stop DIR: a private single-node Slurm cluster (Debian's slurm-wlm and munge)
# living entirely in DIR, on free ports, beside any system one; for trying `bundlelab run --slurm`
# on one machine and for the runner's end-to-end test. After `start`, point the Slurm commands at
# it with `export SLURM_CONF=DIR/slurm.conf` (the line is printed). `stop` shuts it down.
set -euo pipefail
action=${1:-}
dir=${2:-}
[[ ( "$action" == start || "$action" == stop ) && -n "$dir" ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
export SLURM_CONF=$dir/slurm.conf

if [[ "$action" == stop ]]; then
    [[ -f "$SLURM_CONF" ]] && scontrol shutdown >/dev/null 2>&1 || true
    [[ -S "$dir/munge/socket" ]] && munged --stop --socket="$dir/munge/socket" >/dev/null 2>&1 || true
    for pidfile in "$dir"/slurmctld.pid "$dir"/slurmd.pid; do
        [[ -f "$pidfile" ]] && kill "$(cat "$pidfile")" 2>/dev/null || true
    done
    exit 0
fi

for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
    command -v "$tool" >/dev/null || { echo "local-slurm: $tool not found (Debian: slurmctld slurmd slurm-client munge)" >&2; exit 3; }
done
user=$(id -un)
host=$(hostname -s)
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
chmod 700 "$dir/munge"
chmod 755 "$dir"
# munged insists on a private key; the clients find the daemon through the socket named in slurm.conf.
[[ -f "$dir/munge/munge.key" ]] || head -c 1024 /dev/urandom >"$dir/munge/munge.key"
chmod 600 "$dir/munge/munge.key"
munged --force --socket="$dir/munge/socket" --key-file="$dir/munge/munge.key" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"

read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
ss = [socket.socket() for _ in range(2)]
for s in ss: s.bind(("127.0.0.1", 0))
print(*[s.getsockname()[1] for s in ss])')
cpus=$(nproc)
memory=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
cat >"$SLURM_CONF" <<CONF
# Written by scripts/local-slurm.sh: one node, no accounting, no cgroups.
ClusterName=bundlelab-local
SlurmctldHost=$host
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
MinJobAge=600
KillWait=5
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 1 60); do
    if sinfo --noheader --format=%t 2>/dev/null | grep -q idle; then
        echo "export SLURM_CONF=$SLURM_CONF"
        exit 0
    fi
    sleep 0.5
done
echo "local-slurm: the node did not come up in 30 s; logs in $dir/log" >&2
tail -n 20 "$dir"/log/*.log >&2 || true
exit 1
