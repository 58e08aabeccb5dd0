#!/usr/bin/env bash
# The main job's last three steps on the tiny study:
#   calibrate_tiny_test.sh GRANASYM STUDY_DIR WORK_DIR
# `study calibrate` fits the three models and writes every file the figures
# and the report read, with each model's status in fit_status.toml, and exits
# with the worst status's code (calibration/fit_status.h); each model.toml
# runs through `granasym model run`; each calibration.toml reruns through
# `granasym calibrate` to the same fit, status and exit status; the Fig. 5
# paths of each fitted model are drawn; the report counts the three
# calibrations.
set -euo pipefail
granasym="$1" study="$2" work="$3"
[ -f "$study/asymptotic_states.h5" ] || { echo "FAIL: no tiny study at $study"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
out="$work/study"
cp -r "$study" "$out"
rm -rf "$out/calibration" "$out/figures"

# The exit status of each status, and the statuses worst first.
code_of() {
  case "$1" in
    converged) echo 0 ;; failed) echo 3 ;; at_bound) echo 5 ;;
    converged_inadmissible) echo 6 ;; no_convergence) echo 7 ;;
    *) echo "FAIL: unknown status '$1'" >&2; exit 1 ;;
  esac
}
precedence="failed no_convergence converged_inadmissible at_bound converged"
status_of() {  # the status in a fit_status.toml, which holds status and reason only
  [ "$(grep -c . "$1")" -eq 2 ] && grep -q '^reason = ".*"$' "$1" ||
    { echo "FAIL: $1 does not hold exactly status and reason" >&2; exit 1; }
  sed -n 's/^status = "\(.*\)"$/\1/p' "$1"
}

rc=0
"$granasym" study calibrate "$out" > "$work/calibrate.txt" || rc=$?
cat "$work/calibrate.txt"
statuses=""
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  statuses="$statuses $(status_of "$out/calibration/$model/fit_status.toml")"
done
worst=""
for status in $precedence; do
  case " $statuses " in *" $status "*) worst="$status"; break ;; esac
done
[ "$rc" -eq "$(code_of "$worst")" ] ||
  { echo "FAIL: study calibrate exited $rc with statuses$statuses (worst $worst)"; exit 1; }
grep -q "exit status $rc" "$work/calibrate.txt" ||
  { echo "FAIL: study calibrate does not state its exit status"; exit 1; }
for model in hypoplastic_clay modified_cam_clay hypoplastic_sand; do
  dir="$out/calibration/$model"
  status=$(status_of "$dir/fit_status.toml")
  [ "$(sed -n 2p "$dir/summary.txt")" = "status: $status" ] ||
    { echo "FAIL: $dir/summary.txt does not open with its status"; exit 1; }
  grep -q "^  status: $status" "$work/calibrate.txt" ||
    { echo "FAIL: study calibrate does not print the status of $model"; exit 1; }
  for file in calibration.toml calibration.h5 summary.txt parameters.csv warnings.txt model.toml; do
    [ -f "$dir/$file" ] || { echo "FAIL: $dir/$file is missing"; exit 1; }
  done
  head -1 "$dir/parameters.csv" | grep -q "^parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile,units$" ||
    { echo "FAIL: $dir/parameters.csv has another header"; exit 1; }
  [ "$(tail -n +2 "$dir/parameters.csv" | wc -l)" -ge 4 ] ||
    { echo "FAIL: $dir/parameters.csv has fewer than 4 parameters"; exit 1; }
  [ -s "$dir/plot_data/model_lines.dat" ] || { echo "FAIL: no plot data for $model"; exit 1; }
  "$granasym" model run "$dir/model.toml" --out "$work/$model.h5" > "$work/$model.run.txt" ||
    { cat "$work/$model.run.txt"; echo "FAIL: $dir/model.toml does not run"; exit 1; }
  # The calibration it leaves reruns as a user would, to the same fit and status
  # (checked on the fastest model: a rerun of all three doubles the test's
  # minutes since the fits take whole paths, profiles and Pareto fronts).
  if [ "$model" = hypoplastic_clay ]; then
    rerun=0
    "$granasym" calibrate "$dir/calibration.toml" --out "$work/$model.rerun.h5" \
      --summary "$work/$model.rerun.txt" --plot-data "$work/$model.rerun_plots" \
      --status "$work/$model.rerun_status.toml" --quiet > "$work/$model.calibrate.txt" || rerun=$?
    [ "$rerun" -eq "$(code_of "$status")" ] &&
      cmp -s "$dir/fit_status.toml" "$work/$model.rerun_status.toml" ||
      { cat "$work/$model.calibrate.txt"; echo "FAIL: $dir/calibration.toml reruns to status $rerun"; exit 1; }
    # The same text but for the header line, the wall times and the study's
    # selection line (study calibrate's own).
    tail -n +2 "$dir/summary.txt" | grep -v '^selection: ' | sed -E 's/[0-9.]+(e[-+]?[0-9]+)? s([ )]|$)/T s\2/g' > "$work/a.txt"
    tail -n +2 "$work/$model.rerun.txt" | sed -E 's/[0-9.]+(e[-+]?[0-9]+)? s([ )]|$)/T s\2/g' > "$work/b.txt"
    diff "$work/a.txt" "$work/b.txt" ||
      { echo "FAIL: $dir/calibration.toml reruns to another fit than study calibrate's"; exit 1; }
  fi
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

# Two selections, two folders (issue 36 §2): a quasi-static calibration (here
# every state with I(d_max) below 1, on the fastest model) goes to
# calibration/quasi_static/<model>/ and leaves the paper-rate one in
# calibration/<model>/; both side by side in parameters_by_selection.csv and
# in the report.
default="$out/calibration/modified_cam_clay" quasi="$out/calibration/quasi_static/modified_cam_clay"
cp "$default/parameters.csv" "$work/paper_rate_parameters.csv"
grep -q '^selection = "all"$' "$default/selection.toml" ||
  { echo "FAIL: $default/selection.toml does not say all"; exit 1; }
rc=0
"$granasym" study calibrate "$out" --models modified_cam_clay --select quasi_static \
  --max-inertial-number 1 > "$work/quasi_static.txt" 2>&1 || rc=$?
case "$rc" in 0 | 5 | 6 | 7) ;; *) cat "$work/quasi_static.txt"; echo "FAIL: --select quasi_static exited $rc"; exit 1 ;; esac
[ -s "$quasi/parameters.csv" ] && grep -q '^selection = "quasi_static"$' "$quasi/selection.toml" ||
  { cat "$work/quasi_static.txt"; echo "FAIL: no quasi-static calibration in $quasi"; exit 1; }
cmp -s "$work/paper_rate_parameters.csv" "$default/parameters.csv" ||
  { echo "FAIL: the quasi-static calibration overwrote $default/parameters.csv"; exit 1; }
sed -n 4p "$quasi/summary.txt" | grep -q "^selection: quasi_static .*A paper uses" ||
  { sed -n 1,5p "$quasi/summary.txt"; echo "FAIL: $quasi/summary.txt does not say its selection"; exit 1; }
by_selection="$out/calibration/parameters_by_selection.csv"
head -1 "$by_selection" | grep -q "^model,parameter,units,all_value,all_low,all_high,all_interval,all_status,all_profile,all_verdict,quasi_static_value," ||
  { echo "FAIL: $by_selection has another header"; exit 1; }
[ "$(grep -c '^modified_cam_clay,' "$by_selection")" -eq "$(tail -n +2 "$default/parameters.csv" | wc -l)" ] ||
  { cat "$by_selection"; echo "FAIL: $by_selection lacks Cam clay's parameters"; exit 1; }
# Every row holds both values (the 4th and the 11th column).
awk -F, 'NR > 1 && ($4 == "" || $11 == "") { bad = 1 } END { exit bad }' "$by_selection" ||
  { cat "$by_selection"; echo "FAIL: $by_selection has a row without both values"; exit 1; }
grep -q "both selections side by side: " "$work/quasi_static.txt" ||
  { echo "FAIL: study calibrate does not name $by_selection"; exit 1; }
"$granasym" study report "$out" > "$work/report_both.txt"
for text in "paper rate (all detected states): value \[95 % interval\]" \
            "quasi-static: value \[95 % interval\]" 'id="calibration-modified_cam_clay-quasi-static"'; do
  grep -q "$text" "$out/index.html" ||
    { echo "FAIL: the report does not show '$text'"; exit 1; }
done
grep -q "3 of 3 models calibrated" "$work/report_both.txt" ||
  { echo "FAIL: the report counts a model's second selection as another model"; exit 1; }

# Inertial numbers that select nothing are refused (status 2) naming the
# flag; --inertial-number on a study without rate cases names what selects
# its states instead. Nothing is fitted.
for value in -1 0 nan; do
  for flag in --inertial-number --max-inertial-number; do
    rc=0
    "$granasym" study calibrate "$out" --models hypoplastic_clay "$flag" "$value" \
      > "$work/bad_inertial.txt" 2>&1 || rc=$?
    [ "$rc" -eq 2 ] || { cat "$work/bad_inertial.txt"; echo "FAIL: $flag $value exited $rc, expected 2"; exit 1; }
    grep -qF -- "$flag $value: expected a positive inertial number" "$work/bad_inertial.txt" ||
      { cat "$work/bad_inertial.txt"; echo "FAIL: $flag $value is not named"; exit 1; }
  done
done
rc=0
"$granasym" study calibrate "$out" --models hypoplastic_clay --inertial-number 1e-3 \
  > "$work/not_rate.txt" 2>&1 || rc=$?
[ "$rc" -eq 2 ] && grep -q "is not a rate study.*--max-inertial-number" "$work/not_rate.txt" ||
  { cat "$work/not_rate.txt"; echo "FAIL: --inertial-number on a study without rate cases"; exit 1; }
# An output that cannot be written: status 1 (README's exit statuses), not a failed fit (3).
unwritable="$work/unwritable"
cp -r "$out" "$unwritable"
rm -rf "$unwritable/calibration/hypoplastic_clay"
echo "not a folder" > "$unwritable/calibration/hypoplastic_clay"
rc=0
"$granasym" study calibrate "$unwritable" --models hypoplastic_clay > "$work/unwritable.txt" 2>&1 || rc=$?
[ "$rc" -eq 1 ] && grep -q "^failure: " "$work/unwritable.txt" ||
  { cat "$work/unwritable.txt"; echo "FAIL: an unwritable output exited $rc, expected 1"; exit 1; }
echo "PASS: three models calibrated, their Fig. 5 paths drawn and reported; a quasi-static selection beside them; bad inertial numbers and an unwritable output refused"
