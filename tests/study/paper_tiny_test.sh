#!/usr/bin/env bash
# The paper's programme at the tiny scale through the command line:
#   paper_tiny_test.sh GRANASYM PROGRAMME WORK_DIR
# Runs the whole study, checks that every case folder has a finished result
# and a row in the state table, that every row has a kind and a status, then
# runs it again and checks that nothing is computed the second time.
set -euo pipefail
granasym="$1" programme="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
out="$work/study"

start=$(date +%s%N)
"$granasym" study run "$programme" --scale tiny --out "$out" --jobs 2 --threads 1 --quiet \
  | tee "$work/first.txt"
first_ms=$(( ($(date +%s%N) - start) / 1000000 ))

grep -q " 0 interrupted" "$work/first.txt" || { echo "FAIL: the first run was interrupted"; exit 1; }
for file in asymptotic_states.csv asymptotic_states.h5 asymptotic_states_summary.csv \
            ncl_fit.csv path_convergence.csv findings.csv; do
  [ -s "$out/$file" ] || { echo "FAIL: $out/$file is missing or empty"; exit 1; }
done
"$granasym" study status "$out" > "$work/status.txt"
if grep -E " (not_run|checkpointed)" "$work/status.txt"; then
  echo "FAIL: cases without a finished result after the run"; exit 1
fi
# Every case folder appears in the table with a kind and a status.
cases=$(find "$out/cases" -mindepth 2 -maxdepth 2 -type d | wc -l)
listed=$(tail -n +2 "$out/asymptotic_states.csv" | cut -d, -f4 | sort -u | wc -l)
with_stages=$(grep -l 'asymptote' "$out"/cases/*/*/scene.toml | wc -l)
echo "case folders: $cases, with detectors: $with_stages, cases in the table: $listed"
[ "$listed" -ge "$with_stages" ] || { echo "FAIL: cases missing from the state table"; exit 1; }
if tail -n +2 "$out/asymptotic_states.csv" | awk -F, '$2 == "" || $3 == ""' | grep -q .; then
  echo "FAIL: rows without kind or status"; exit 1
fi
# The paper's claims, each with a verdict from the four and the numbers behind it.
claims=$(tail -n +2 "$out/findings.csv" | wc -l)
[ "$claims" -ge 16 ] || { echo "FAIL: findings.csv has $claims claims, expected 16"; exit 1; }
verdicts=$(grep -oE ',(reproduced|partly|not_reproduced|not_tested),' "$out/findings.csv" | wc -l)
[ "$verdicts" -eq "$claims" ] ||
  { echo "FAIL: findings.csv: $verdicts of $claims claims have a valid verdict"; exit 1; }
grep -q "findings (findings.csv):" "$work/first.txt" ||
  { echo "FAIL: the run did not print its findings' verdicts"; exit 1; }
# Model runs (Fig. 5) finished.
models=$(find "$out/models" -name done.toml | wc -l)
[ "$models" -ge 1 ] || { echo "FAIL: no model run finished"; exit 1; }

cp "$out/asymptotic_states.csv" "$work/table_first.csv"
start=$(date +%s%N)
"$granasym" study run "$programme" --scale tiny --out "$out" --jobs 2 --threads 1 --quiet \
  | tee "$work/second.txt"
second_ms=$(( ($(date +%s%N) - start) / 1000000 ))
grep -q ": 0 computed" "$work/second.txt" || { echo "FAIL: the second run computed cases"; exit 1; }
cmp "$work/table_first.csv" "$out/asymptotic_states.csv" ||
  { echo "FAIL: the cached re-run wrote another state table"; exit 1; }
echo "PASS: tiny study in ${first_ms} ms, cached re-run in ${second_ms} ms"
