#!/usr/bin/env bash
# A private one-node Slurm cluster on this machine, for the farm tests and for trying
# tools/glint-farm without a real cluster (docs/farm.md). Everything it writes lives in DIR:
# its own munge key and socket, slurm.conf, state, spool, logs and pid files, and its own ports,
# so it never touches a system Slurm or munge. Needs root (munged runs as the munge user,
# slurmd as root) and the Debian packages slurm-wlm and munge.
#
#   tools/slurm-local.sh check              exit 0 when a cluster can start here, else say why (exit 77)
#   tools/slurm-local.sh start DIR [CPUS]   start munged, slurmctld and slurmd; prints the line
#                                           `export SLURM_CONF=DIR/slurm.conf` for the clients
#   tools/slurm-local.sh stop DIR           cancel its jobs, stop the three daemons by pid
set -euo pipefail

readonly kSkip=77 # ctest's SKIP_RETURN_CODE for the tests that use this script

die() {
  echo "slurm-local: $*" >&2
  exit 1
}

check() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "slurm-local: cannot run a local Slurm cluster: not root (munged must run as the munge user and slurmd as root)" >&2
    return $kSkip
  fi
  local missing=()
  for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel setpriv; do
    command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
  done
  id munge >/dev/null 2>&1 || missing+=("user munge")
  if [ ${#missing[@]} -gt 0 ]; then
    echo "slurm-local: cannot run a local Slurm cluster: missing ${missing[*]} (apt-get install slurm-wlm munge)" >&2
    return $kSkip
  fi
}

# A TCP port on 127.0.0.1 that nothing listens on, starting the search at $1.
free_port() {
  local port=$1
  while (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; do port=$((port + 1)); done
  echo "$port"
}

# True while PID is a live process (a zombie counts as gone: it has stopped running).
alive() {
  [ -e "/proc/$1" ] && ! grep -q '^[^ ]* ([^)]*) Z' "/proc/$1/stat" 2>/dev/null
}

wait_gone() { # PID SECONDS
  local i
  for ((i = 0; i < $2 * 10; i++)); do
    alive "$1" || return 0
    sleep 0.1
  done
  return 1
}

start() {
  local dir=$1 cpus=${2:-$(nproc)}
  check || exit $?
  [ -e "$dir/slurm.conf" ] && die "$dir already holds a cluster (stop it first)"
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  # Whatever started before a failure is stopped again.
  trap 'stop "$dir" || true' ERR
  # munged insists that the munge user can reach its socket directory and that its key is
  # private. DIR may sit under a private temporary directory, so munge gets a short directory
  # of its own under /tmp (a short path also keeps the socket name within its length limit).
  local munge
  munge=$(mktemp -d /tmp/glint-munge.XXXXXX)
  echo "$munge" >"$dir/munge.dir"
  chown munge:munge "$munge"
  chmod 755 "$munge"
  setpriv --reuid=munge --regid=munge --init-groups \
    mungekey --create --keyfile="$munge/munge.key" >/dev/null
  setpriv --reuid=munge --regid=munge --init-groups \
    munged --socket="$munge/socket" --key-file="$munge/munge.key" \
    --pid-file="$munge/munged.pid" --log-file="$munge/munged.log" \
    --seed-file="$munge/munged.seed"
  cp "$munge/munged.pid" "$dir/munged.pid"

  local host ctld_port slurmd_port
  host=$(hostname -s)
  ctld_port=$(free_port $((20000 + $$ % 20000)))
  slurmd_port=$(free_port $((ctld_port + 1)))
  # proctrack/linuxproc and task/none: no cgroups (none inside containers); SlurmUser=root: the
  # daemons and every job run as root; CR_CPU: tasks share the node by CPUs, so two
  # one-CPU tasks run side by side on a two-core machine.
  cat >"$dir/slurm.conf" <<EOF
ClusterName=glintlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$munge/socket
CredType=cred/munge
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
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=glint Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF" -N "$host"
  local i state=""
  for ((i = 0; i < 300; i++)); do
    state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.1
  done
  if [ "$state" != idle ]; then
    tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
    stop "$dir" || true
    die "the node did not come up (state '${state:-unknown}'); logs above"
  fi
  echo "export SLURM_CONF=$SLURM_CONF"
}

stop() {
  local dir=$1 name pid i
  [ -d "$dir" ] || die "no directory $dir"
  export SLURM_CONF="$dir/slurm.conf"
  # Jobs first, so that no slurmstepd outlives the daemons.
  if [ -f "$dir/slurmctld.pid" ] && alive "$(cat "$dir/slurmctld.pid")"; then
    scancel --quiet --user=root 2>/dev/null || true
    for ((i = 0; i < 100; i++)); do
      [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid")
    alive "$pid" || continue
    kill -TERM "$pid" 2>/dev/null || true
    wait_gone "$pid" 10 || kill -KILL "$pid" 2>/dev/null || true
  done
  if [ -f "$dir/munge.dir" ]; then
    cp "$(cat "$dir/munge.dir")/munged.log" "$dir/log/" 2>/dev/null || true
    rm -rf "$(cat "$dir/munge.dir")"
    rm -f "$dir/munge.dir"
  fi
}

case "${1:-}" in
check) check ;;
start) [ $# -ge 2 ] || die "usage: slurm-local.sh start DIR [CPUS]"; start "$2" "${3:-}" ;;
stop) [ $# -eq 2 ] || die "usage: slurm-local.sh stop DIR"; stop "$2" ;;
*) die "usage: slurm-local.sh check | start DIR [CPUS] | stop DIR" ;;
esac
