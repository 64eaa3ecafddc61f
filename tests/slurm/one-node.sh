#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, every file of it in one folder (docs/cluster.md):
#   bash tests/slurm/one-node.sh start DIR    writes DIR/slurm.conf, starts munged, slurmctld, slurmd
#   export SLURM_CONF=DIR/slurm.conf          then sbatch, squeue, scancel, passim ... --slurm use it
#   bash tests/slurm/one-node.sh stop DIR     stops the three daemons (by their pid files)
# Needs Debian's slurm-wlm and munge (scripts/install-deps.sh --test) and root: slurmd starts
# jobs as their users. Nothing outside DIR is written or read (no /etc/slurm, no /run/munge);
# the daemons listen on ports of their own, so a real Slurm on the machine is not disturbed.
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(realpath -m "$2")

# A pid file's process, if it still runs.
live_pid() { [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null && cat "$1"; }

stop() {
  for f in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    local pid
    pid=$(live_pid "$f") || continue
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
  done
  return 0
}

# A TCP port nobody listens on, from a range above the usual services.
free_port() {
  local port
  for _ in $(seq 200); do
    port=$(( 20000 + RANDOM % 20000 ))
    if ! ss -Htln "sport = :$port" 2>/dev/null | grep -q .; then echo "$port"; return 0; fi
  done
  echo "one-node.sh: no free port found" >&2
  return 1
}

start() {
  for p in munged slurmctld slurmd sinfo; do
    command -v "$p" >/dev/null || { echo "one-node.sh: $p not found (scripts/install-deps.sh --test installs slurm-wlm and munge)" >&2; exit 1; }
  done
  [ "$(id -u)" -eq 0 ] || { echo "one-node.sh: needs root (slurmd runs jobs as their users)" >&2; exit 1; }
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
  # munged wants its socket folder searchable by all (clients connect to it) and writable only by it.
  chmod 0755 "$dir" "$dir/munge"

  # MUNGE with its own key and socket: 1024 random bytes, readable by its owner only.
  head -c 1024 /dev/urandom > "$dir/munge/munge.key"
  chmod 0400 "$dir/munge/munge.key"
  munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
         --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
         --seed-file="$dir/munge/munged.seed"

  local host ctld_port slurmd_port mem_mb
  host=$(hostname -s)
  ctld_port=$(free_port)
  slurmd_port=$(free_port)
  while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done
  # Most of the machine's memory, so that jobs may ask for --mem (slurmd drains a node that
  # claims more than it has).
  mem_mb=$(( $(awk '/MemTotal/ { print $2 }' /proc/meminfo) / 1024 * 8 / 10 ))
  # No cgroups and no accounting: process tracking by /proc, no task binding, job state
  # from squeue only (sacct needs an accounting storage this set-up does not have).
  cat > "$dir/slurm.conf" <<EOF
ClusterName=passim-one-node
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
# A cancelled task is killed 1 s after its SIGTERM; finished jobs leave the controller soon.
KillWait=1
MinJobAge=10
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld
  slurmd
  # The node takes a moment to register: ready when sinfo shows it idle.
  for _ in $(seq 100); do
    if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
      echo "one-node.sh: cluster up ($host, ports $ctld_port/$slurmd_port): export SLURM_CONF=$dir/slurm.conf"
      return 0
    fi
    sleep 0.2
  done
  echo "one-node.sh: the node did not become idle in 20 s; logs in $dir:" >&2
  tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
  stop
  exit 1
}

case $action in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
