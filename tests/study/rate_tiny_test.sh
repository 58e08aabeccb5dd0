#!/usr/bin/env bash
# The rate study (studies/programmes/rate.toml, issue 10 §2) at the tiny scale
# through the command line:
#   rate_tiny_test.sh GRANASYM PROGRAMME WORK_DIR
# `study run` (timed: the tiny scale is meant to take under two minutes on 2
# cores), the rate files with a row per rate case and per group, `study
# figures` drawing the rate figures and only the paper figures the programme
# declares, `study report` with its Rate study section, and a second run
# that computes nothing and writes the same rate tables.
set -euo pipefail
source "$(dirname "$0")/../app/test_lib.sh"
granasym="$1" programme="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
out="$work/study"

start=$(date +%s%N)
"$granasym" study run "$programme" --scale tiny --out "$out" --jobs 2 --threads 1 --quiet \
  | tee "$work/first.txt"
run_ms=$(( ($(date +%s%N) - start) / 1000000 ))
grep -q " 0 interrupted" "$work/first.txt" || fail "the first run was interrupted"
grep -q "rate study: " "$work/first.txt" || fail "study run printed no rate-study line"

# Rows of a CSV without its '#' comments and header.
rows() { grep -v '^#' "$1" | tail -n +2 | wc -l; }
for file in rate_states.csv rate_summary.csv rate_lines.csv rate_quasi_static.csv \
            rate_independence.csv rate_stiffness.csv rate_extension.csv rate_extension_limit.csv; do
  [ -s "$out/$file" ] || { fail "$out/$file is missing or empty"; continue; }
done
# Two replicates of eight rate cases (ψ_ε = 0° and 90° at I* = 0.1, 0.03 and
# 167 1/s from NC 100 kPa, and the extension sweep's 120° and 150° at
# I* = 0.1), one detector stage each; eight groups; a verdict per direction
# with two I*; three quasi-static quantities per direction.
[ "$(rows "$out/rate_states.csv")" -eq 16 ] || fail "rate_states.csv: $(rows "$out/rate_states.csv") rows, not 16"
[ "$(rows "$out/rate_summary.csv")" -eq 8 ] || fail "rate_summary.csv: not 8 groups"
[ "$(rows "$out/rate_independence.csv")" -eq 2 ] || fail "rate_independence.csv: not 2 verdicts"
[ "$(rows "$out/rate_quasi_static.csv")" -eq 12 ] || fail "rate_quasi_static.csv: not 12 rows"
# The sweep at I* = 0.1 from NC 100 kPa: three steps (90°, 120°, 150°) and
# one end, a result of the four kinds with its sentence.
[ "$(rows "$out/rate_extension.csv")" -eq 3 ] || fail "rate_extension.csv: not 3 steps"
[ "$(rows "$out/rate_extension_limit.csv")" -eq 1 ] || fail "rate_extension_limit.csv: not 1 sweep"
grep -v '^#' "$out/rate_extension_limit.csv" | tail -n +2 |
  grep -qE ',(limit_d|liquefied|not_reached|undetermined),.*,"?(psi_epsilon\(d\)|liquefied at|sigma_r/p > 0|undetermined)' ||
  fail "rate_extension_limit.csv: no result with its sentence"
grep -q "extension, E 500 MPa, I\* = 0.1, from 100 kPa: " "$work/first.txt" ||
  fail "study run printed no extension line"
if grep -v '^#' "$out/rate_independence.csv" | tail -n +2 |
   grep -vE ',(rate_independent|rate_dependent|undetermined),' | grep -q .; then
  fail "a verdict is not one of rate_independent, rate_dependent, undetermined"
fi
# The drained case (triaxial at σ_r = 100 kPa, ε̇_a = 42.3908 1/s), two
# replicates, in its own files: one group, one σ_r.
[ "$(rows "$out/rate_drained_states.csv")" -eq 2 ] || fail "rate_drained_states.csv: not 2 rows"
[ "$(rows "$out/rate_drained.csv")" -eq 1 ] || fail "rate_drained.csv: not 1 group"
[ "$(rows "$out/rate_drained_limit.csv")" -eq 1 ] || fail "rate_drained_limit.csv: not 1 start"
grep -v '^#' "$out/rate_drained_states.csv" | tail -n +2 | grep -q '^1,nc100_drained_ea42.3908,drained,' ||
  fail "rate_drained_states.csv: no row for r1/nc100_drained_ea42.3908"
# Every rate case of the state table is in rate_states.csv or
# rate_drained_states.csv, with its start and rate.
# Its ensemble rows (source ensemble: the mean path of the two replicates,
# one per case and stage) are no replicate and stay out of the rate study.
in_table=$(grep ',rate,' "$out/asymptotic_states.csv" | grep -vc ',ensemble,' || true)
[ "$in_table" -eq 18 ] || fail "the state table has $in_table rate rows, not 18"
ensemble=$(grep ',rate,' "$out/asymptotic_states.csv" | grep -c ',ensemble,' || true)
[ "$ensemble" -eq 9 ] || fail "the state table has $ensemble ensemble rate rows, not 9"
if grep -v '^#' "$out/rate_states.csv" | tail -n +2 | awk -F, '$8 != 100' | grep -q .; then
  fail "a rate state does not start from NC 100 kPa"
fi

"$granasym" study figures "$out" | tee "$work/figures.txt"
index="$out/figures/index.tsv"
stems=$(tail -n +2 "$index" | cut -f1 | tr '\n' ' ')
[ "$stems" = "fig09_ncl rate_psi_sigma_p rate_csl_ncl rate_critical_state_ratio rate_extension rate_against_models " ] ||
  fail "figures/index.tsv lists '$stems'"
for stem in fig09_ncl rate_psi_sigma_p rate_csl_ncl rate_extension; do
  for ext in png pdf; do
    [ -s "$out/figures/$stem.$ext" ] || fail "$stem.$ext was not drawn"
  done
done
# M against I needs a detected 90° state: drawn, or the index says why not.
if [ ! -s "$out/figures/rate_critical_state_ratio.png" ]; then
  grep -P "^rate_critical_state_ratio\t.*Not drawn: no ψ_ε = 90° or drained rate" "$index" ||
    fail "rate_critical_state_ratio neither drawn nor explained"
fi

# Models against the quasi-static set need a CSL from two starts: the tiny
# scale has one start, so the figure says why it is not drawn, and
# `study calibrate` refuses with the reason.
grep -P "^rate_against_models\t.*Not drawn: no I\* has usable psi_epsilon = 90 deg states from two starts" "$index" ||
  fail "rate_against_models: no reason given"
if "$granasym" study calibrate "$out" > "$work/calibrate.txt" 2>&1; then
  fail "study calibrate fitted a rate study without a quasi-static CSL"
fi
grep -q "a rate study, but no I\* has usable" "$work/calibrate.txt" || fail "calibrate gave no reason"
# Asked for I* = 0.1: the quasi-static set is two datasets, the ψ_ε = 0°
# states (drifting too) and the others with the drained cases; the tiny
# scale's short paths detect no CSL, so each model says which dataset is empty.
rc=0
"$granasym" study calibrate "$out" --inertial-number 0.1 > "$work/calibrate01.txt" 2>&1 || rc=$?
[ "$rc" -eq 3 ] || fail "study calibrate without a detected CSL exited $rc, not 3 (failed)"
grep -q '^status = "failed"$' "$out/calibration/hypoplastic_clay/fit_status.toml" ||
  fail "fit_status.toml does not say failed"
grep -q "fitting the 4 rate cases at I\* = 0.1 and the 0 drained cases" "$work/calibrate01.txt" ||
  fail "calibrate --inertial-number 0.1 did not name its quasi-static set"
grep -q "hypoplastic_clay: FAILED: dataset 'quasi_static': .*no state passes the selections (kinds csl, compression, extension, triaxial; statuses detected" \
  "$work/calibrate01.txt" || fail "calibrate did not say that the quasi-static dataset is empty"
for name in quasi_static_ncl quasi_static; do
  grep -q "^name = \"$name\"" "$out/calibration/hypoplastic_clay/calibration.toml" ||
    fail "calibration.toml has no dataset $name"
done
rm -rf "$out/calibration"

"$granasym" study report "$out" | tee "$work/report.txt"
grep -q "^## Rate study" "$out/report.md" || fail "report.md has no Rate study section"
grep -q 'id="rate-study"' "$out/index.html" || fail "index.html has no Rate study section"
grep -q "Figure rate (a)" "$out/report.md" || fail "the report does not show figure rate (a)"
grep -q "Quasi-static critical state from drained tests" "$out/report.md" ||
  fail "the report has no table of the drained critical state"

cp "$out/rate_summary.csv" "$work/summary_first.csv"
start=$(date +%s%N)
"$granasym" study run "$programme" --scale tiny --out "$out" --jobs 2 --threads 1 --quiet \
  > "$work/second.txt"
second_ms=$(( ($(date +%s%N) - start) / 1000000 ))
grep -q ": 0 computed" "$work/second.txt" || fail "the second run computed cases"
cmp -s "$work/summary_first.csv" "$out/rate_summary.csv" ||
  fail "the cached re-run wrote another rate_summary.csv"

[ "$failures" -eq 0 ] || { echo "$failures failures"; exit 1; }
echo "PASS: tiny rate study in ${run_ms} ms (budget 120 s on 2 cores), cached re-run in ${second_ms} ms"
