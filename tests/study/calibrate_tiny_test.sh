#!/usr/bin/env bash
# The main job's last three steps on the tiny study:
#   calibrate_tiny_test.sh GRANASYM STUDY_DIR WORK_DIR
# `study calibrate` fits the three models and writes every file the figures
# and the report read; each model.toml runs through `granasym model run`;
# the Fig. 5 paths of each fitted model are drawn; the report counts the
# three calibrations.
set -euo pipefail
granasym="$1" study="$2" work="$3"
[ -f "$study/asymptotic_states.h5" ] || { echo "FAIL: no tiny study at $study"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
out="$work/study"
cp -r "$study" "$out"
rm -rf "$out/calibration" "$out/figures"

"$granasym" study calibrate "$out" | tee "$work/calibrate.txt"
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  dir="$out/calibration/$model"
  for file in calibration.toml calibration.h5 summary.txt parameters.csv warnings.txt model.toml; do
    [ -f "$dir/$file" ] || { echo "FAIL: $dir/$file is missing"; exit 1; }
  done
  head -1 "$dir/parameters.csv" | grep -q "^parameter,value,std_error,ci95_low,ci95_high,status$" ||
    { echo "FAIL: $dir/parameters.csv has another header"; exit 1; }
  [ "$(tail -n +2 "$dir/parameters.csv" | wc -l)" -ge 4 ] ||
    { echo "FAIL: $dir/parameters.csv has fewer than 4 parameters"; exit 1; }
  [ -s "$dir/plot_data/model_lines.dat" ] || { echo "FAIL: no plot data for $model"; exit 1; }
  "$granasym" model run "$dir/model.toml" --out "$work/$model.h5" > "$work/$model.run.txt" ||
    { cat "$work/$model.run.txt"; echo "FAIL: $dir/model.toml does not run"; exit 1; }
  # The calibration it leaves reruns as a user would, to the same fit.
  "$granasym" calibrate "$dir/calibration.toml" --out "$work/$model.rerun.h5" \
    --summary "$work/$model.rerun.txt" --plot-data "$work/$model.rerun_plots" --quiet \
    > "$work/$model.calibrate.txt" ||
    { cat "$work/$model.calibrate.txt"; echo "FAIL: $dir/calibration.toml does not rerun"; exit 1; }
  # The same text but for the header line and the wall times.
  tail -n +2 "$dir/summary.txt" | sed -E 's/[0-9.]+(e[-+]?[0-9]+)? s([ )]|$)/T s\2/g' > "$work/a.txt"
  tail -n +2 "$work/$model.rerun.txt" | sed -E 's/[0-9.]+(e[-+]?[0-9]+)? s([ )]|$)/T s\2/g' > "$work/b.txt"
  diff "$work/a.txt" "$work/b.txt" ||
    { echo "FAIL: $dir/calibration.toml reruns to another fit than study calibrate's"; exit 1; }
  paths=$(find "$dir/paths" -name done.toml | wc -l)
  # Cam clay cannot follow the OC paths that soften on the dry side.
  [ "$paths" -ge 4 ] || { echo "FAIL: only $paths of 6 Fig. 5 paths of $model finished"; exit 1; }
done

"$granasym" study figures "$out" > "$work/figures.txt"
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  [ -s "$out/figures/fig05_$model.png" ] && [ -s "$out/figures/fig05_$model.pdf" ] ||
    { cat "$work/figures.txt"; echo "FAIL: fig05_$model not drawn"; exit 1; }
done
"$granasym" study report "$out" | tee "$work/report.txt"
grep -q "3 of 3 models calibrated" "$work/report.txt" ||
  { echo "FAIL: the report does not count the three calibrations"; exit 1; }
echo "PASS: three models calibrated, their Fig. 5 paths drawn and reported"
