#!/usr/bin/env bash
# Runs a command against a private one-node Slurm cluster on this machine: munged, slurmctld and
# slurmd of Debian's slurm-wlm, with their key, config, state, spool, logs and ports under a
# temporary folder, so that nothing of the system's (/etc/slurm, /etc/munge, a running munged
# or Slurm) is used or changed. The command sees SLURM_CONF (for sbatch, squeue, scontrol,
# scancel) and BVHLAB_LOCAL_SLURM (the folder); the daemons are stopped when it ends, however
# it ends (trap), and the folder removed. Exit code: the command's; 77 (ctest's SKIP_RETURN_CODE)
# where Slurm cannot start: not root (slurmd must be, to run jobs as their users).
#   tests/slurm/with_local_slurm.sh build/bvhlab_tests --gtest_filter='SlurmCluster.*'
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  echo "with_local_slurm: skipped: slurmd must run as root to start jobs, and this is uid $(id -u)" >&2
  exit 77
fi
for program in munged mungekey slurmctld slurmd sbatch scontrol; do
  command -v "$program" >/dev/null ||
    { echo "with_local_slurm: $program is not installed (./setup.sh installs slurmctld, slurmd, slurm-client and munge)" >&2; exit 1; }
done
[ $# -gt 0 ] || { echo "usage: $0 COMMAND [ARGS...]" >&2; exit 2; }

dir=$(mktemp -d /tmp/bvhlab_slurm.XXXXXX)
pids=()
stop() {
  local code=$?
  # Jobs first (their slurmstepd would outlive slurmd), then the daemons, newest first.
  if [ -n "${SLURM_CONF:-}" ] && [ -e "$dir/slurmctld.ready" ]; then
    scancel --full --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ "$code" -ne 0 ] && [ "$code" -ne 77 ]; then
    for log in "$dir"/*.log; do [ -e "$log" ] && { echo "--- $log"; tail -n 20 "$log"; }; done >&2
  fi
  rm -rf "$dir"
  exit "$code"
}
trap stop EXIT
trap 'exit 143' TERM INT

# A port nothing listens on, from a range clear of Slurm's defaults (6817, 6818).
free_port() {
  local port
  while :; do
    port=$((20000 + RANDOM % 30000))
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || { echo "$port"; return; }
  done
}

# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local seconds=$1
  shift
  for _ in $(seq $((seconds * 5))); do "$@" >/dev/null 2>&1 && return 0; sleep 0.2; done
  return 1
}

mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
chmod 711 "$dir" "$dir/munge"  # the socket's folders: traversable by the clients
mungekey --create --keyfile="$dir/munge/munge.key"
munged --foreground --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/munged.seed" >"$dir/munged.log" 2>&1 &
pids+=($!)
wait_for 10 test -S "$dir/munge/munge.socket" || { echo "with_local_slurm: munged did not start" >&2; exit 1; }

ctld_port=$(free_port)
until slurmd_port=$(free_port) && [ "$slurmd_port" != "$ctld_port" ]; do :; done
# The node as this machine is (slurmd -C: CPUs, sockets, cores, memory), under a fixed name.
host=$(hostname -s)
node=$(slurmd -C | head -n 1 | sed -e "s/^NodeName=[^ ]*/NodeName=bvhlab NodeHostname=$host NodeAddr=127.0.0.1/")
cat >"$dir/slurm.conf" <<EOF
# Written by tests/slurm/with_local_slurm.sh: one node, no accounting, no cgroups; the daemons
# log to their stderr, which goes to slurmctld.log and slurmd.log beside this file.
ClusterName=bvhlabtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# Finished jobs stay visible to scontrol (there is no sacct without slurmdbd).
MinJobAge=600
$node State=UNKNOWN
PartitionName=bvhlab Nodes=bvhlab Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$dir/slurm.conf" BVHLAB_LOCAL_SLURM="$dir"

slurmctld -D -i -f "$SLURM_CONF" >"$dir/slurmctld.log" 2>&1 &
pids+=($!)
wait_for 20 scontrol ping || { echo "with_local_slurm: slurmctld did not answer" >&2; exit 1; }
touch "$dir/slurmctld.ready"
slurmd -D -f "$SLURM_CONF" -N bvhlab >"$dir/slurmd.log" 2>&1 &
pids+=($!)
wait_for 30 sh -c '[ "$(sinfo -h -n bvhlab -o %t)" = idle ]' ||
  { echo "with_local_slurm: node bvhlab did not become idle: $(sinfo -h -o '%n %t %E' 2>&1)" >&2; exit 1; }
echo "with_local_slurm: cluster bvhlabtest up in $dir ($(sinfo -h -o '%n %c CPUs %m MB %t'))" >&2

# Bounded, so that the trap still stops the daemons before ctest's timeout (300 s) kills this.
timeout 240 "$@"
