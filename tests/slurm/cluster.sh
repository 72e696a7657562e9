#!/bin/sh
# A one-node Slurm cluster on this machine, for the sweep's cluster test (tests/platform/
# slurm_test.cpp): slurmctld and slurmd with a generated slurm.conf, munged with its own key,
# all under DIR and on ports of their own, run as root.
#   cluster.sh start DIR   writes DIR/slurm.conf, starts the daemons, waits until the node is idle
#   cluster.sh stop DIR    stops them
# On failure it says why and prints the daemons' logs.
set -eu
command=$1
dir=$2

stop() {
  for file in "$dir"/slurmd.pid "$dir"/slurmctld.pid "$dir"/munged.pid; do
    [ -f "$file" ] || continue
    pid=$(cat "$file")
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 40); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done  # its ports free for the next
  done
}

fail() {
  echo "cluster.sh: $1" >&2
  for log in "$dir"/log/*.log; do [ -f "$log" ] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }; done
  stop
  exit 1
}

case "$command" in
start)
  for tool in munged mungekey slurmctld slurmd sinfo sbatch; do
    command -v "$tool" >/dev/null || fail "$tool is missing: install slurm-wlm and munge (scripts/bootstrap.sh does)"
  done
  [ "$(id -u)" = 0 ] || fail "the test cluster runs its daemons as root"
  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  host=$(hostname -s)
  mungekey --create --force --keyfile="$dir/munge.key" || fail "mungekey could not make a key"
  munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge.seed" || fail "munged did not start"
  cat >"$dir/slurm.conf" <<CONF
ClusterName=surfvptest
SlurmctldHost=$host
SlurmctldPort=${SURFVP_SLURM_PORT:-26817}
SlurmdPort=$(( ${SURFVP_SLURM_PORT:-26817} + 1 ))
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$dir/slurm.conf" || fail "slurmctld did not start"
  slurmd -f "$dir/slurm.conf" || fail "slurmd did not start"
  for _ in $(seq 60); do
    state=$(sinfo -h -o %T 2>/dev/null || true)
    [ "$state" = idle ] && exit 0
    sleep 0.5
  done
  fail "the node did not become idle within 30 s (sinfo: ${state:-nothing})"
  ;;
stop) stop ;;
*) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
esac
