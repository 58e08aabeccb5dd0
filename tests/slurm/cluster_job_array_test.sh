#!/usr/bin/env bash
# Checks the private Slurm cluster of single_node_cluster.sh by itself: a job
# array of two tasks runs (both at once on a node with two or more CPUs) and
# sees its array variables, a job with --dependency=afterok on the array runs
# only after both tasks and reads their outputs, and a job that depends on an
# array with a failing task is never started (why studies/slurm/submit.sh
# makes its merge afterany: slurm_failed_shard_test.sh).
#
#   tests/slurm/cluster_job_array_test.sh     (as root; starts its own cluster)
#   GRANASYM_SLURM_TEST_TIMEOUT  seconds to wait for the jobs (default 120)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ -z "${GRANASYM_SLURM_CLUSTER_DIR:-}" ]; then
  exec "$here/single_node_cluster.sh" "$here/$(basename "${BASH_SOURCE[0]}")" "$@"
fi
# shellcheck source=tests/slurm/jobs.sh
source "$here/jobs.sh"
timeout_s="${GRANASYM_SLURM_TEST_TIMEOUT:-120}"

work="$(mktemp -d "${TMPDIR:-/tmp}/granasym-slurm-array.XXXXXX")"
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  print_job_outputs "$work"/*.out
  exit 1
}

start=$(date +%s.%N)
array_id="$(sbatch --parsable --job-name=array --array=0-1 --cpus-per-task=1 \
  --output="$work/array-%A_%a.out" \
  --wrap "echo \$SLURM_ARRAY_TASK_ID/\$SLURM_ARRAY_TASK_COUNT > $work/task-\$SLURM_ARRAY_TASK_ID.txt")"
after_id="$(sbatch --parsable --job-name=after --dependency="afterok:$array_id" \
  --cpus-per-task=1 --output="$work/after-%j.out" \
  --wrap "cat $work/task-0.txt $work/task-1.txt > $work/after.txt")"
# A second array whose task 1 fails: its dependent job must never start.
failing_id="$(sbatch --parsable --job-name=failing --array=0-1 --cpus-per-task=1 \
  --output="$work/failing-%A_%a.out" --wrap "test \$SLURM_ARRAY_TASK_ID -eq 0")"
blocked_id="$(sbatch --parsable --job-name=blocked --dependency="afterok:$failing_id" \
  --cpus-per-task=1 --output="$work/blocked-%j.out" --wrap "touch $work/blocked.txt")"

wait_for_jobs "$timeout_s" "$array_id" "$after_id" "$failing_id" || fail "jobs did not finish"
elapsed="$(echo "$(date +%s.%N) $start" | awk '{ printf "%.1f", $1 - $2 }')"
job_states "$array_id" "$after_id" "$failing_id" "$blocked_id"

states="$(job_states "$array_id" "$after_id" | sort)"
expected="$(printf '%s\n' "${array_id}_0 COMPLETED" "${array_id}_1 COMPLETED" \
                          "$after_id COMPLETED" | sort)"
[ "$states" = "$expected" ] || fail "states of the array and its dependent job: $states"
for task in 0 1; do
  [ "$(cat "$work/task-$task.txt")" = "$task/2" ] ||
    fail "task $task wrote '$(cat "$work/task-$task.txt" 2>/dev/null)', not $task/2"
done
[ "$(cat "$work/after.txt")" = "$(printf '0/2\n1/2')" ] ||
  fail "the dependent job read '$(cat "$work/after.txt" 2>/dev/null)'"

failing_states="$(job_states "$failing_id" | sort | awk '{ print $2 }' | paste -sd ' ')"
[ "$failing_states" = "COMPLETED FAILED" ] || fail "states of the failing array: $failing_states"
# slurmctld marks the dependency as never satisfied when it next evaluates it.
reason=""
for _ in $(seq 1 60); do
  reason="$(job_field "$blocked_id" Reason)"
  [ "$reason" != DependencyNeverSatisfied ] || break
  sleep 0.5
done
[ "$(job_field "$blocked_id" JobState)" = PENDING ] && [ "$reason" = DependencyNeverSatisfied ] ||
  fail "the job after a failed task: $(job_field "$blocked_id" JobState) ($reason)"
[ ! -e "$work/blocked.txt" ] || fail "the job after a failed task ran"
scancel "$blocked_id"

echo "PASS: array $array_id (2 tasks) and dependent job $after_id completed in $elapsed s;" \
     "job $blocked_id after failing array $failing_id held ($reason)"
