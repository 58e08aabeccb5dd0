#!/usr/bin/env bash
# A shard that fails does not leave the merge pending: studies/slurm/submit.sh
# on a private single-node cluster with two shards of a five-case tiny
# programme, where array task 1 (shard 2/2) is made to fail before it runs
# anything (GRANASYM is a wrapper that exits 3 for --shard 2/2). The array's
# task 1 is FAILED, the merge job runs after the array (afterany), names
# shard 2/2 and the cases without a result, and exits 3 (FAILED, ExitCode 3).
#
#   tests/slurm/slurm_failed_shard_test.sh GRANASYM     (as root)
#   GRANASYM_SLURM_TEST_TIMEOUT  seconds for the jobs (default 300)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ $# -ne 1 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
granasym="$(realpath -m "$1")"
[ -x "$granasym" ] || { echo "FAIL: $granasym is not an executable" >&2; exit 1; }
if [ -z "${GRANASYM_SLURM_CLUSTER_DIR:-}" ]; then
  exec "$here/single_node_cluster.sh" "$here/$(basename "${BASH_SOURCE[0]}")" "$granasym"
fi
# shellcheck source=tests/slurm/jobs.sh
source "$here/jobs.sh"
timeout_s="${GRANASYM_SLURM_TEST_TIMEOUT:-300}"

work="$(mktemp -d "${TMPDIR:-/tmp}/granasym-slurm-failed.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/jobs"
fail() {
  echo "FAIL: $*" >&2
  print_job_outputs "$work"/jobs/*.out
  exit 1
}

# Five cases of 250 spheres: an NCL and four paths from it.
cat >"$work/programme.toml" <<'TOML'
[study]
name = "failed-shard-test"
ncl = "ncl"
[scale.tiny]
count = 250
[sample]
reference_count = 150000
reference_cell_size_mm = 31.0
seed = 4
[scene.numerics]
time_step_s = 1.2e-7
[scene.output]
interval_strain = 0.002
[[run]]
name = "ncl"
from = "sample"
[[run.stage]]
each = { p = [20, 50] }
name = "p{p}"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
stop.mean_stress_kpa = "{p}"
asymptote = {}
[[run]]
name = "nc{p}_psi{psi}"
from = "ncl@p{p}"
vary = { p = [20, 50], psi = [60, 90] }
[[run.stage]]
psi_epsilon_deg = "{psi}"
stretching_rate = 167.0
stop = { strain_norm = 0.02 }
asymptote = {}
TOML
# The wrapper: shard 2/2 fails at once, everything else is granasym.
cat >"$work/granasym-failing" <<WRAPPER
#!/usr/bin/env bash
for argument in "\$@"; do
  if [ "\$argument" = "2/2" ]; then
    echo "granasym-failing: shard 2/2 made to fail" >&2
    exit 3
  fi
done
exec "$granasym" "\$@"
WRAPPER
chmod +x "$work/granasym-failing"

submitted="$(cd "$work/jobs" &&
  SHARDS=2 SCALE=tiny OUT="$work/study" PROGRAMME="$work/programme.toml" \
  GRANASYM="$work/granasym-failing" REPORT=0 "$root/studies/slurm/submit.sh" --cpus-per-task=1)" ||
  fail "studies/slurm/submit.sh failed"
echo "$submitted"
shards_job="$(echo "$submitted" | sed -n 's/^shards job \([0-9][0-9]*\):.*/\1/p')"
merge_job="$(echo "$submitted" | sed -n 's/^merge job \([0-9][0-9]*\):.*/\1/p')"
[ -n "$shards_job" ] && [ -n "$merge_job" ] || fail "no job ids in the output of submit.sh"
# The merge must not stay pending: both the array and the merge end.
wait_for_jobs "$timeout_s" "$shards_job" "$merge_job" ||
  fail "the jobs did not end (a merge pending after a failed shard?)"
states="$(job_states "$shards_job" "$merge_job")"
echo "$states"
[ "$(job_states "$shards_job" | sort)" = "$(printf '%s\n' "${shards_job}_0 COMPLETED" \
  "${shards_job}_1 FAILED")" ] || fail "expected shard 1/2 COMPLETED and shard 2/2 FAILED"
[ "$(job_states "$merge_job")" = "$merge_job FAILED" ] || fail "the merge job did not fail"
[ "$(job_field "$merge_job" ExitCode)" = "3:0" ] ||
  fail "the merge job's ExitCode is $(job_field "$merge_job" ExitCode), expected 3:0"
merge_out="$(ls "$work"/jobs/slurm-granasym-merge-*.out)"
grep -q "shard 2/2: never ended" "$merge_out" || fail "the merge does not name shard 2/2"
grep -q "incomplete: 1 of 2 shards did not finish" "$merge_out" ||
  fail "the merge does not say the study is incomplete"
grep -q "without a result" "$merge_out" || fail "the merge does not name the missing cases"
[ -f "$work/study/shards/1-of-2.toml" ] && grep -q 'status = "complete"' "$work/study/shards/1-of-2.toml" ||
  fail "shard 1/2 left no complete marker"
[ -s "$work/study/asymptotic_states.csv" ] || fail "the merge wrote no state table"
echo "PASS: shard 2/2 FAILED, merge job $merge_job ran after the array, named the shard and exited 3"
