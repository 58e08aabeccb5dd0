#!/usr/bin/env bash
# Runs a command inside a private single-node Slurm cluster that lives in a
# temporary folder and is stopped when the command ends.
#
#   tests/slurm/single_node_cluster.sh COMMAND [ARGUMENT...]
#
# Starts munged (its own key, socket, pid, log and seed files), slurmctld and
# slurmd (foreground children of this script, from a slurm.conf written into
# the folder: this host as the one node at 127.0.0.1 with `nproc` CPUs, one
# default partition, free ports, no accounting, no cgroups), waits until
# sinfo shows the node idle, then runs COMMAND with
#   SLURM_CONF                    the cluster's slurm.conf (sbatch, squeue, ...)
#   GRANASYM_SLURM_CLUSTER_DIR    the temporary folder (logs in DIR/log/)
# and exits with COMMAND's status. On exit (also on an error or a signal) it
# cancels the cluster's jobs, stops the daemons and removes the folder; when
# COMMAND fails, the daemon logs are printed first. Nothing under /etc/slurm
# or /etc/munge is read or written, and instances do not share anything, so
# several can run at once.
#
# Needs root (slurmd starts jobs as their user) and Debian's slurm-wlm and
# munge packages (scripts/install_deps.sh installs them).
#   GRANASYM_SLURM_START_TIMEOUT  seconds to wait for an idle node (default 60)
#   GRANASYM_SLURM_KEEP=1         keep the folder (its path is printed)
set -euo pipefail

log() { echo "slurm-cluster: $*" >&2; }
die() { log "error: $*"; exit 1; }

if [ $# -eq 0 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
# The daemons are in /usr/sbin, which a non-login PATH may lack.
case ":$PATH:" in *:/usr/sbin:*) ;; *) PATH="$PATH:/usr/sbin" ;; esac
missing=()
for command in munged mungekey munge unmunge slurmctld slurmd sbatch sinfo squeue scontrol scancel; do
  command -v "$command" >/dev/null 2>&1 || missing+=("$command")
done
if [ ${#missing[@]} -gt 0 ]; then
  die "missing ${missing[*]}: install Debian's slurm-wlm and munge with scripts/install_deps.sh"
fi
if [ "$(id -u)" -ne 0 ]; then
  die "the private Slurm cluster must run as root (slurmd launches jobs as their" \
      "user and munged/slurmd refuse otherwise); run the Slurm tests as root"
fi

# A short folder: munge and slurmd put Unix sockets in it (108-byte limit).
tmp_parent="${TMPDIR:-/tmp}"
if [ ${#tmp_parent} -gt 40 ] || [ ! -d "$tmp_parent" ]; then tmp_parent=/tmp; fi
dir="$(mktemp -d "$tmp_parent/granasym-slurm.XXXXXX")"
mkdir -p "$dir/munge" "$dir/log" "$dir/state" "$dir/spool" "$dir/tmp"
# munged wants every folder above its socket searchable by all, writable by
# the owner only; the key file stays private (0600).
chmod 711 "$dir"
chmod 755 "$dir/munge"
conf="$dir/slurm.conf"
pids_file="$dir/pids"
: >"$pids_file"
munged_pid="" slurmctld_pid="" slurmd_pid="" watchdog_pid="" command_pid=""

# The daemons' logs; what they wrote to stderr only where the log is empty
# (in the foreground they write both, the log file once it is open).
print_logs() {
  local file
  for file in "$dir"/log/*; do
    [ -s "$file" ] || continue
    case "$file" in *.stderr) [ ! -s "${file%.stderr}.log" ] || continue ;; esac
    echo "----- ${file#"$dir"/} (last 60 lines) -----" >&2
    tail -n 60 "$file" >&2
  done
}

# Stops the processes whose pids are in "$@": TERM, then KILL after 10 s.
stop_processes() {
  local pid
  for pid in "$@"; do kill -TERM "$pid" 2>/dev/null || true; done
  for _ in $(seq 1 100); do
    local alive=0
    for pid in "$@"; do if kill -0 "$pid" 2>/dev/null; then alive=1; fi; done
    [ $alive -eq 1 ] || return 0
    sleep 0.1
  done
  for pid in "$@"; do kill -KILL "$pid" 2>/dev/null || true; done
}

# Processes of this cluster still alive once the daemons are stopped: job
# step daemons (slurmstepd) get slurmd's environment, which carries this
# cluster's folder as a marker, and job processes the SLURM_CONF of their
# sbatch. Prints their pids.
cluster_processes() {
  local environ pid
  for environ in /proc/[0-9]*/environ; do
    pid="${environ#/proc/}"; pid="${pid%/environ}"
    [ "$pid" != "$$" ] && [ "$pid" != "$BASHPID" ] || continue
    if { tr '\0' '\n' <"$environ"; } 2>/dev/null |
         grep -qxF -e "GRANASYM_SLURM_NODE_OF=$dir" -e "SLURM_CONF=$conf"; then
      echo "$pid"
    fi
  done
}

# The command's process group (it runs in a session of its own): TERM, then
# KILL after 10 s.
stop_command() {
  [ -n "$command_pid" ] || return 0
  kill -TERM -- "-$command_pid" 2>/dev/null || return 0
  for _ in $(seq 1 100); do
    kill -0 -- "-$command_pid" 2>/dev/null || return 0
    sleep 0.1
  done
  log "the command did not stop on SIGTERM; killing it"
  kill -KILL -- "-$command_pid" 2>/dev/null || true
}

cleanup() {
  local status=$?
  trap - EXIT INT TERM HUP
  set +e
  stop_command
  if [ -n "$slurmctld_pid" ] && kill -0 "$slurmctld_pid" 2>/dev/null; then
    local jobs
    jobs="$(squeue -h -o %A 2>/dev/null | sort -u)"
    if [ -n "$jobs" ]; then
      log "cancelling jobs still in the queue: $(echo "$jobs" | paste -sd ' ')"
      # shellcheck disable=SC2086
      scancel $jobs 2>/dev/null
      for _ in $(seq 1 100); do
        [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break
        sleep 0.1
      done
    fi
  fi
  [ -z "$watchdog_pid" ] || kill "$watchdog_pid" 2>/dev/null
  local daemons=()
  for pid in "$slurmd_pid" "$slurmctld_pid"; do [ -z "$pid" ] || daemons+=("$pid"); done
  [ ${#daemons[@]} -eq 0 ] || stop_processes "${daemons[@]}"
  local leftovers
  leftovers="$(cluster_processes)"
  # shellcheck disable=SC2086
  [ -z "$leftovers" ] || stop_processes $leftovers
  [ -z "$munged_pid" ] || stop_processes "$munged_pid"
  if [ "${GRANASYM_SLURM_KEEP:-0}" = 1 ]; then
    log "kept $dir"
  else
    rm -rf "$dir"
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

# A free TCP port below the ephemeral range, not listed in /proc/net/tcp*.
free_port() {
  local port hex
  for _ in $(seq 1 200); do
    port=$((15000 + RANDOM % 15000))
    hex="$(printf ':%04X' "$port")"
    if ! awk -v h="$hex" 'FNR > 1 && substr($2, length($2) - 4) == h { found = 1 }
                          END { exit !found }' /proc/net/tcp /proc/net/tcp6 2>/dev/null; then
      echo "$port"
      return 0
    fi
  done
  die "no free TCP port found between 15000 and 30000"
}

start=$(date +%s.%N)

# munged: its own key; as root it checks that the files are private.
mungekey --create --keyfile="$dir/munge/munge.key" --bits=1024 >/dev/null
chmod 600 "$dir/munge/munge.key"
socket="$dir/munge/munge.socket"
munged --foreground --key-file="$dir/munge/munge.key" --socket="$socket" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
  --seed-file="$dir/munge/munged.seed" >>"$dir/log/munged.stderr" 2>&1 &
munged_pid=$!
echo "$munged_pid" >>"$pids_file"
for _ in $(seq 1 100); do
  if munge -n -S "$socket" 2>/dev/null | unmunge -S "$socket" >/dev/null 2>&1; then break; fi
  kill -0 "$munged_pid" 2>/dev/null || { print_logs; die "munged exited at start"; }
  sleep 0.05
done
munge -n -S "$socket" | unmunge -S "$socket" >/dev/null 2>&1 || {
  print_logs; die "munged does not answer on $socket"; }

# If this script is killed outright (SIGKILL), its trap cannot run: a
# watchdog stops the daemons and removes the folder once it is gone.
(
  trap - EXIT INT TERM HUP
  exec >/dev/null 2>&1 </dev/null
  while kill -0 $$ 2>/dev/null; do sleep 1; done
  xargs -r kill -KILL -- <"$pids_file"
  sleep 1
  cluster_processes | xargs -r kill -KILL
  rm -rf "$dir"
) &
watchdog_pid=$!

node="$(hostname -s)"
cpus="$(nproc)"
memory_mb=$(( $(awk '/^MemTotal:/ { print $2 }' /proc/meminfo) / 1024 * 9 / 10 ))
write_conf() {
  cat >"$conf" <<EOF
# Private single-node cluster of tests/slurm/single_node_cluster.sh.
ClusterName=granasym-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$1
SlurmdPort=$2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
TmpFS=$dir/tmp
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
PropagateResourceLimits=NONE
MailProg=/bin/true
ReturnToService=2
SlurmdParameters=config_overrides
SchedulerType=sched/backfill
MinJobAge=600
InactiveLimit=0
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

export SLURM_CONF="$conf"
export GRANASYM_SLURM_CLUSTER_DIR="$dir"
idle=0
for attempt in 1 2 3; do
  ctld_port="$(free_port)"
  slurmd_port="$(free_port)"
  [ "$slurmd_port" != "$ctld_port" ] || slurmd_port=$((ctld_port + 1))
  write_conf "$ctld_port" "$slurmd_port"
  slurmctld -D -c -f "$conf" >>"$dir/log/slurmctld.stderr" 2>&1 &
  slurmctld_pid=$!
  echo "$slurmctld_pid" >>"$pids_file"
  GRANASYM_SLURM_NODE_OF="$dir" slurmd -D -f "$conf" -N "$node" \
    >>"$dir/log/slurmd.stderr" 2>&1 &
  slurmd_pid=$!
  echo "$slurmd_pid" >>"$pids_file"
  deadline=$(( $(date +%s) + ${GRANASYM_SLURM_START_TIMEOUT:-60} ))
  while [ "$(date +%s)" -lt "$deadline" ]; do
    if ! kill -0 "$slurmctld_pid" 2>/dev/null || ! kill -0 "$slurmd_pid" 2>/dev/null; then
      break
    fi
    state="$(sinfo -h -N -n "$node" -o %T 2>/dev/null || true)"
    if [ "$state" = idle ]; then idle=1; break; fi
    sleep 0.1
  done
  [ $idle -eq 0 ] || break
  # Another process may have taken a port between the check and the bind.
  if grep -qs "Address already in use" "$dir"/log/slurm*; then
    log "a port was taken (attempt $attempt); retrying with other ports"
    stop_processes "$slurmd_pid" "$slurmctld_pid"
    slurmd_pid="" slurmctld_pid=""
    rm -rf "$dir/state"/* "$dir/spool"/*
    for file in "$dir"/log/slurm*; do mv "$file" "$file.attempt$attempt"; done
    continue
  fi
  break
done
if [ $idle -eq 0 ]; then
  print_logs
  die "the node $node did not become idle within ${GRANASYM_SLURM_START_TIMEOUT:-60} s" \
      "(sinfo: ${state:-no answer}); daemon logs above"
fi
elapsed="$(echo "$(date +%s.%N) $start" | awk '{ printf "%.1f", $1 - $2 }')"
log "node $node idle with $cpus CPUs after $elapsed s (ports $ctld_port/$slurmd_port, $dir)"

# In a session of its own, so that a signal to this script stops the
# command's whole process tree; `wait` (unlike a foreground command) lets the
# traps run at once. A non-interactive shell's background child is no group
# leader, so setsid runs the command in place: its pid is its group's id.
setsid "$@" &
command_pid=$!
echo "-$command_pid" >>"$pids_file"
set +e
wait "$command_pid"
status=$?
set -e
command_pid=""
if [ $status -ne 0 ]; then
  log "command failed with status $status; daemon logs:"
  print_logs
fi
exit $status
