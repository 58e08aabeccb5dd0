#!/usr/bin/env bash
# The paper's figures from the tiny study (the output of Study.paper_tiny_end_to_end):
#   figures_tiny_test.sh GRANASYM STUDY_DIR WORK_DIR
# 1. `granasym study figures` on a copy of the study: every figure drawn as a
#    non-empty PNG and PDF, gnuplot silent (the command fails on any gnuplot
#    output), index.tsv with one row per figure.
# 2. A hypoplastic clay calibrated (`granasym calibrate`) on the study's
#    states in DIR/calibration/hypoplastic_clay/plot_data: the figures that
#    overlay models are drawn with it and say so in their captions.
set -euo pipefail
granasym="$1" study="$2" work="$3"
[ -f "$study/asymptotic_states.h5" ] || { echo "FAIL: no tiny study in $study"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
out="$work/study"
cp -r "$study" "$out"
stems="fig05_model_paths fig08_overlaps fig09_ncl fig10_csl_nc fig11_csl_oc
       fig12_triaxial_strain fig13_triaxial fig14_compression fig15_extension
       fig16_asymptotic_states fig17_asbs_sections fig18_asbs_level
       fig19_triaxial_directions fig20_friction fig21_friction_inertial fig22_inertial_number
       sec52_time_step"

check_figures() {
  for stem in $stems; do
    for ext in png pdf; do
      [ -s "$out/figures/$stem.$ext" ] || { echo "FAIL: $out/figures/$stem.$ext missing or empty"; exit 1; }
    done
  done
  rows=$(tail -n +2 "$out/figures/index.tsv" | wc -l)
  [ "$rows" -eq "$(echo $stems | wc -w)" ] || { echo "FAIL: index.tsv has $rows rows"; exit 1; }
  [ "$(head -1 "$out/figures/index.tsv")" = "$(printf 'stem\tfigure\ttitle\tcaption')" ] ||
    { echo "FAIL: index.tsv header"; exit 1; }
  if grep -q "Not drawn" "$out/figures/index.tsv"; then
    echo "FAIL: figures not drawn:"; grep "Not drawn" "$out/figures/index.tsv"; exit 1
  fi
}

start=$(date +%s%N)
"$granasym" study figures "$out" | tee "$work/figures.txt"
echo "study figures: $(( ($(date +%s%N) - start) / 1000000 )) ms"
check_figures
grep -q "No calibrated model is overlaid" "$out/figures/index.tsv" ||
  { echo "FAIL: captions do not say that no model is overlaid"; exit 1; }

# A calibration on the states (detected or drifting, constant psi_epsilon).
{
  echo "p_kpa,e,psi_sigma_deg,psi_epsilon_deg"
  tail -n +2 "$out/asymptotic_states.csv" | awk -F, \
    '($3 == "detected" || $3 == "drifting") && ($2 == "ncl" || $2 == "csl" || $2 == "compression" || $2 == "extension") && $8 > 0 {print $8 "," $9 "," $11 "," $7}'
} > "$work/states.csv"
mkdir -p "$out/calibration/hypoplastic_clay"
cat > "$work/calibration.toml" <<TOML
[model]
kind = "hypoplastic_clay"
[parameters.r]
free = false
value = 0.4
[[dataset]]
name = "tiny"
csv = "states.csv"
[output]
plot_data = "study/calibration/hypoplastic_clay/plot_data"
TOML
# Any status but a failed fit (exit 3) leaves the plot data
# (calibration/fit_status.h: 0 converged, 5 at_bound, 6 converged_inadmissible,
# 7 no_convergence): the tiny study's states need not converge cleanly.
rc=0
"$granasym" calibrate "$work/calibration.toml" --quiet || rc=$?
case "$rc" in 0 | 5 | 6 | 7) ;; *) echo "FAIL: calibrate exited with status $rc"; exit 1 ;; esac
"$granasym" study figures "$out" > "$work/figures_with_model.txt"
check_figures
for stem in fig16_asymptotic_states fig17_asbs_sections fig18_asbs_level; do
  grep -P "^$stem\t" "$out/figures/index.tsv" | grep -q "Models overlaid.*hypoplastic clay" ||
    { echo "FAIL: $stem does not overlay the calibrated model"; exit 1; }
done
[ -s "$out/figures/data/fig16_model_lines.tsv" ] || { echo "FAIL: no model lines"; exit 1; }
echo "PASS: $(echo $stems | wc -w) figures, with and without a calibrated model"
