#!/usr/bin/env bash
# The quasi-static ASBS (issue 39 §3) at the tiny scale of
# studies/programmes/quasi_static_extension.toml through the command line:
#   quasi_static_tiny_test.sh GRANASYM PROGRAMME WORK_DIR
# `study run`; `study calibrate --select quasi_static`, whose set in a study
# without ψ_ε = 90° rate cases is the rate cases at the smallest I* with the
# drained cases and the other cases at that I* or slower (the compression
# path, and the study's NCL: no rate case is a ψ_ε = 0° path); `study
# figures`, whose Fig. 17 draws the constant-e sections of the set's states
# only (no paper-rate case) with the fitted models' sections; `study report`,
# whose Fitted parameters and Rate study sections say which set the models
# were fitted to.
set -euo pipefail
source "$(dirname "$0")/../app/test_lib.sh"
granasym="$1" programme="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
out="$work/study"

start=$(date +%s%N)
"$granasym" study run "$programme" --scale tiny --out "$out" --jobs 2 --threads 1 --quiet \
  | tee "$work/run.txt"
run_ms=$(( ($(date +%s%N) - start) / 1000000 ))
grep -q " 0 failed 0 blocked 0 interrupted" "$work/run.txt" || fail "the run did not finish every case"

start=$(date +%s%N)
rc=0
"$granasym" study calibrate "$out" --select quasi_static > "$work/calibrate.txt" 2>&1 || rc=$?
calibrate_ms=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$work/calibrate.txt"
# 0, or a fitted model's status: at_bound 5, converged_inadmissible 6,
# no_convergence 7; not 3 (a model failed) or a refusal.
case "$rc" in 0 | 5 | 6 | 7) ;; *) fail "study calibrate --select quasi_static exited $rc" ;; esac
grep -qF "rate study: fitting the 4 rate cases at I* = 0.003 and the 2 drained cases at the slowest axial rates, E = 500 MPa, and 2 other cases at I* or slower (nc500_psi70_I0.003, ncl_qs)" \
  "$work/calibrate.txt" || fail "calibrate did not name the quasi-static set with its other cases"
selection="$out/calibration/quasi_static.toml"
grep -qx 'inertial_number = 0.003' "$selection" || fail "$selection: not I* = 0.003"
grep -qx 'other_cases = \["nc500_psi70_I0.003", "ncl_qs"\]' "$selection" ||
  fail "$selection: other_cases are not the compression path and the NCL"
grep -qx 'drained_cases = \["nc1000_drained_ea39", "nc500_drained_ea27.6"\]' "$selection" ||
  fail "$selection: drained_cases are not the drained test"
models=0
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  if [ -s "$out/calibration/$model/model.toml" ]; then
    models=$((models + 1))
    grep -q 'other_cases\|"ncl_qs"' "$out/calibration/$model/calibration.toml" ||
      fail "$model/calibration.toml does not name the other cases of the set"
  fi
done
[ "$models" -eq 3 ] || fail "$models of the three models were fitted, not 3"

"$granasym" study figures "$out" > "$work/figures.txt"
cat "$work/figures.txt"
index="$out/figures/index.tsv"
[ -s "$out/figures/fig17_asbs_sections.png" ] || fail "Fig. 17 was not drawn: $(grep '^fig17' "$index")"
grep -P "^fig17_asbs_sections\t.*the quasi-static set that the models were calibrated to \(calibration/quasi_static.toml: the 4 rate cases at I\* = 0.003" \
  "$index" > /dev/null || fail "Fig. 17's caption does not say which states it draws"
# Figs. 17 and 16 draw the states of the set only: the NCL's, no paper-rate
# sweep (…_D167) or paper-rate NCL.
for data in fig17_dem fig16_states; do
  file="$out/figures/data/$data.tsv"
  [ -s "$file" ] || fail "no $file"
  if grep -q "_D167" "$file"; then fail "$data draws a paper-rate state"; fi
  grep -q "ncl_qs (replicate 1), stage p500" "$file" || fail "$data lacks the NCL's states"
done
# The drained critical states of the set are there (the only critical
# states of this study: it has no ψ_ε = 90° path), in Fig. 16 as a block of
# their own.
sections="$out/figures/data/fig17_dem.tsv"
grep -q "nc500_drained_ea27.6 (replicate 1), stage drained.ntriaxial, detected" "$sections" ||
  fail "Fig. 17 lacks the drained critical state"
grep -q "drained triaxial (critical state)" "$out/figures/data/fig16_states.tsv" ||
  fail "Fig. 16 lacks the drained critical states"
# Each fitted model's section at every level drawn.
lines="$out/figures/data/fig17_models.tsv"
levels=$(grep -c "^p_over_pe.*ln(1+e) = " "$sections" || true)
[ "$levels" -ge 1 ] || fail "Fig. 17 has no level"
for title in "hypoplastic clay (Mašín 2005)" "Modified Cam clay" \
             "hypoplastic sand (von Wolffersdorff 1996)"; do
  n=$(grep "^p_over_pe" "$lines" | grep -cF "$title, ln(1+e) = " || true)
  [ "$n" -eq "$levels" ] || fail "Fig. 17 has $n sections of $title, not one per level ($levels)"
done

"$granasym" study report "$out" > "$work/report.txt"
grep -qF "The default calibrations (calibration/\\<model\\>/) fitted to the quasi-static set only" "$out/report.md" ||
  fail "the report does not say that the models were fitted to the quasi-static set"
grep -qF 'other cases at I\* or slower (nc500_psi70_I0.003, ncl_qs)' "$out/report.md" ||
  fail "the report does not name the set's other cases"
grep -q "fig17_asbs_sections" "$out/report.md" || fail "the report does not show Fig. 17"

[ "$failures" -eq 0 ] || { echo "$failures failures"; exit 1; }
echo "PASS: tiny quasi-static ASBS: run ${run_ms} ms, calibrate ${calibrate_ms} ms"
