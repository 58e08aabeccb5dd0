#!/usr/bin/env bash
# A study run as a Slurm job array gives what one process gives: runs
# studies/slurm/submit.sh (two shards and the merge) on a private single-node
# cluster, then the same study with `granasym study run` in one process with
# the same thread count, and compares the sets of cases, every case's series
# (exported to CSV, byte for byte) and the state tables.
#
#   tests/slurm/slurm_study_test.sh GRANASYM [PROGRAMME]     (as root)
#   PROGRAMME                    default: studies/programmes/paper.toml
#   GRANASYM_SLURM_TEST_SCALE    default: tiny
#   GRANASYM_SLURM_TEST_SHARDS   default: 2
#   GRANASYM_SLURM_TEST_THREADS  threads per case, in the jobs and in the
#                                single run (default: 1)
#   GRANASYM_SLURM_TEST_TIMEOUT  seconds for the jobs and for the single run
#                                each (default: 1200)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
granasym="$(realpath -m "$1")"
programme="$(realpath -m "${2:-$root/studies/programmes/paper.toml}")"
[ -x "$granasym" ] || { echo "FAIL: $granasym is not an executable" >&2; exit 1; }
[ -f "$programme" ] || { echo "FAIL: no programme file $programme" >&2; exit 1; }
# (`granasym study --help` succeeds without a study command: CLI11 prints
# the program's help.)
"$granasym" --help 2>/dev/null | grep -qE '^ +study ' || {
  echo "FAIL: $granasym has no 'study' command (granasym study run|merge|status)" >&2
  exit 1
}
if [ -z "${GRANASYM_SLURM_CLUSTER_DIR:-}" ]; then
  exec "$here/single_node_cluster.sh" "$here/$(basename "${BASH_SOURCE[0]}")" \
    "$granasym" "$programme"
fi
# shellcheck source=tests/slurm/jobs.sh
source "$here/jobs.sh"
scale="${GRANASYM_SLURM_TEST_SCALE:-tiny}"
shards="${GRANASYM_SLURM_TEST_SHARDS:-2}"
threads="${GRANASYM_SLURM_TEST_THREADS:-1}"
timeout_s="${GRANASYM_SLURM_TEST_TIMEOUT:-1200}"

work="$(mktemp -d "${TMPDIR:-/tmp}/granasym-slurm-study.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/jobs" "$work/csv/sharded" "$work/csv/single"
fail() {
  echo "FAIL: $*" >&2
  print_job_outputs "$work"/jobs/*.out
  exit 1
}

# The jobs, as a user submits them (logs into the submit directory).
start=$(date +%s.%N)
submitted="$(cd "$work/jobs" &&
  SHARDS="$shards" SCALE="$scale" OUT="$work/sharded" PROGRAMME="$programme" \
  GRANASYM="$granasym" REPORT=0 "$root/studies/slurm/submit.sh" --cpus-per-task="$threads")" ||
  fail "studies/slurm/submit.sh failed"
echo "$submitted"
shards_job="$(echo "$submitted" | sed -n 's/^shards job \([0-9][0-9]*\):.*/\1/p')"
merge_job="$(echo "$submitted" | sed -n 's/^merge job \([0-9][0-9]*\):.*/\1/p')"
[ -n "$shards_job" ] && [ -n "$merge_job" ] || fail "no job ids in the output of submit.sh"
# A failed shard leaves the merge pending for ever: check the shards first.
wait_for_jobs "$timeout_s" "$shards_job" || fail "the shards did not finish"
expected="$(for ((task = 0; task < shards; ++task)); do echo "${shards_job}_$task COMPLETED"; done)"
states="$(job_states "$shards_job" | sort)"
[ "$states" = "$expected" ] || { echo "$states" >&2; fail "not every shard COMPLETED"; }
wait_for_jobs "$timeout_s" "$merge_job" || fail "the merge did not finish"
cluster_s="$(echo "$(date +%s.%N) $start" | awk '{ printf "%.1f", $1 - $2 }')"
states="$(job_states "$shards_job" "$merge_job")"
echo "$states"
[ "$(job_states "$merge_job")" = "$merge_job COMPLETED" ] || fail "the merge did not complete"
# The merge started after the last shard ended (afterany on the whole array).
epoch() { date -d "$1" +%s; }
merge_start="$(epoch "$(job_field "$merge_job" StartTime)")"
for ((task = 0; task < shards; ++task)); do
  task_end="$(epoch "$(job_field "${shards_job}_$task" EndTime)")"
  [ "$merge_start" -ge "$task_end" ] || fail "the merge started before shard $((task + 1)) ended"
done

# The same study in one process.
start=$(date +%s.%N)
timeout "$timeout_s" "$granasym" study run "$programme" --scale "$scale" \
  --out "$work/single" --threads "$threads" >"$work/single.log" 2>&1 || {
  tail -n 60 "$work/single.log" >&2
  fail "the single-process run failed"
}
single_s="$(echo "$(date +%s.%N) $start" | awk '{ printf "%.1f", $1 - $2 }')"

# The same cases, with the same series and the same state table.
# Case folders are cases/r<replicate>/<case>.
list_cases() { (cd "$1/cases" && find . -mindepth 3 -maxdepth 3 -name result.h5 -printf '%h\n' |
                 sed 's|^\./||' | sort); }
sharded_cases="$(list_cases "$work/sharded")"
single_cases="$(list_cases "$work/single")"
[ -n "$single_cases" ] || fail "the single run wrote no cases/r<K>/<case>/result.h5"
if [ "$sharded_cases" != "$single_cases" ]; then
  diff <(echo "$sharded_cases") <(echo "$single_cases") >&2 || true
  fail "the sharded and the single run have different cases (< sharded, > single)"
fi
cases=0
while read -r case_name; do
  for run in sharded single; do
    mkdir -p "$(dirname "$work/csv/$run/$case_name.csv")"
    "$granasym" export "$work/$run/cases/$case_name/result.h5" \
      --csv "$work/csv/$run/$case_name.csv" >/dev/null ||
      fail "granasym export of the $run case $case_name failed"
  done
  [ "$(wc -l <"$work/csv/single/$case_name.csv")" -ge 2 ] || fail "case $case_name has no rows"
  cmp "$work/csv/sharded/$case_name.csv" "$work/csv/single/$case_name.csv" >&2 ||
    fail "the series of case $case_name differ"
  cases=$((cases + 1))
done <<<"$single_cases"
for run in sharded single; do
  for table in asymptotic_states.csv asymptotic_states.h5; do
    [ -s "$work/$run/$table" ] || fail "the $run run has no $table"
  done
done
[ "$(wc -l <"$work/single/asymptotic_states.csv")" -ge 2 ] || fail "the state table has no rows"
cmp "$work/sharded/asymptotic_states.csv" "$work/single/asymptotic_states.csv" >&2 ||
  fail "the state tables differ"
"$granasym" study status "$work/sharded" || fail "granasym study status failed"

echo "PASS: $programme at scale $scale, $shards shards x $threads threads:" \
     "shards job $shards_job and merge job $merge_job COMPLETED in $cluster_s s," \
     "single run $single_s s; $cases cases and the state table identical"
