# Helpers of the Slurm tests for watching jobs (sourced; bash, set -euo pipefail).
# shellcheck shell=bash
# Uses only squeue-free scontrol output, so no accounting (sacct) is needed:
# a finished job stays known to slurmctld for MinJobAge seconds.

# The JobState of every record of the jobs "$@" (array tasks one line each),
# as "JOBID STATE" lines; JOBID is ArrayJobId_ArrayTaskId for array tasks.
# A job slurmctld does not know (any more) is "JOB UNKNOWN".
job_states() {
  local job records
  for job in "$@"; do
    records="$(scontrol -o show job "$job" 2>/dev/null)" || records=""
    if [ -z "$records" ]; then
      echo "$job UNKNOWN"
      continue
    fi
    echo "$records" | awk '{
      id = ""; task = ""; state = ""
      for (i = 1; i <= NF; ++i) {
        if ($i ~ /^JobId=/) id = substr($i, 7)
        if ($i ~ /^ArrayJobId=/) id = substr($i, 12)
        if ($i ~ /^ArrayTaskId=/) task = "_" substr($i, 13)
        if ($i ~ /^JobState=/) state = substr($i, 10)
      }
      print id task, state
    }'
  done
}

# The value of FIELD (e.g. Reason, ExitCode, StdOut) of the job record JOB.
job_field() {
  scontrol -o show job "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1
}

is_terminal_state() {
  case "$1" in
    COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | PREEMPTED | \
      BOOT_FAIL | DEADLINE | UNKNOWN) return 0 ;;
    *) return 1 ;;
  esac
}

# Waits until every record of the jobs "$@" is in a terminal state; returns 1
# (with the states printed) after TIMEOUT_S seconds.
wait_for_jobs() {
  local timeout_s="$1"
  shift
  local deadline=$(($(date +%s) + timeout_s)) line all_done
  while :; do
    all_done=1
    while read -r line; do
      is_terminal_state "${line##* }" || all_done=0
    done < <(job_states "$@")
    [ $all_done -eq 0 ] || return 0
    if [ "$(date +%s)" -ge "$deadline" ]; then
      echo "error: jobs $* not finished after $timeout_s s:" >&2
      job_states "$@" >&2
      return 1
    fi
    sleep 0.5
  done
}

# Prints the output files named FILE... (the jobs' logs), for a failure report.
print_job_outputs() {
  local file
  for file in "$@"; do
    [ -f "$file" ] || continue
    echo "----- $file (last 60 lines) -----" >&2
    tail -n 60 "$file" >&2
  done
}
