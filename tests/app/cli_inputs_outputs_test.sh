#!/usr/bin/env bash
# The command line against bad outputs and flags, for every command:
#   cli_inputs_outputs_test.sh GRANASYM WORK_DIR
# - an output that is one of the inputs is refused with status 2 before any
#   work, the message names the flag and the file, and the input is unchanged;
# - an output in a missing folder, in a read-only folder, or that is a folder
#   is refused with status 2 before the first step;
# - bad flags exit 2 with "error:" and a hint on its own line; --help exits 0;
# - more threads than the hardware has are capped with a warning.
set -uo pipefail
granasym="$(realpath "$1")" work="$2"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0 cases=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect STATUS PATTERN COMMAND...: the exit status and a pattern of stderr+stdout.
expect() {
  local status="$1" pattern="$2"; shift 2
  cases=$((cases + 1))
  local output rc
  output="$("$@" 2>&1)"; rc=$?
  if [ "$rc" -ne "$status" ]; then
    fail "$* exited $rc, expected $status: $output"
  elif ! grep -qE -- "$pattern" <<<"$output"; then
    fail "$*: no '$pattern' in: $output"
  fi
}

# unchanged FILE COMMAND...: refused with status 2 and FILE keeps its bytes.
unchanged() {
  local file="$1"; shift
  local before; before="$(sha256sum "$file")"
  expect 2 "names the same file as " "$@"
  [ "$(sha256sum "$file")" = "$before" ] || fail "$* changed $file"
}

cat > scene.toml <<'TOML'
[sample.generate]
count = 60
cell_size_mm = 3.0
[numerics]
threads = 1
[[stage]]
psi_epsilon_deg = 0.0
stretching_rate = 167.0
[stage.stop]
steps = 50
TOML
cat > gsd.csv <<'CSV'
diameter_mm,percent_passing_by_mass
0.2,0
0.4,100
CSV
cat > model.toml <<'TOML'
[model]
kind = "hypoplastic_clay"
phi_c_deg = 22.6
lambda_star = 0.11
kappa_star = 0.016
n_intercept = 1.375
r = 0.4
[initial]
mean_stress_kpa = 100.0
ocr = 1.0
[[stage]]
type = "isotropic"
target_mean_stress_kpa = 200.0
TOML
cat > asymptotes.toml <<'TOML'
[model]
kind = "hypoplastic_clay"
phi_c_deg = 22.6
lambda_star = 0.11
kappa_star = 0.016
n_intercept = 1.375
r = 0.4
[asymptotes]
analytic_points = 10
TOML
printf 'psi_epsilon_deg,psi_sigma_deg,ln_1_plus_e,p_kpa\n0,0,0.5,100\n' > states.csv
cat > calib.toml <<'TOML'
[model]
kind = "hypoplastic_clay"
[[dataset]]
name = "d"
csv = "states.csv"
TOML
cat > programme.toml <<'TOML'
[study]
name = "p"
TOML

# A result to export (and a packing), from a real run.
"$granasym" dem run scene.toml --out result.h5 --quiet >/dev/null 2>&1 || fail "the reference run failed"

# Outputs over inputs, every command and every output flag.
unchanged scene.toml "$granasym" dem run scene.toml --out scene.toml --quiet
unchanged scene.toml "$granasym" dem run scene.toml --out ./scene.toml --quiet
ln -f scene.toml hardlink.toml
unchanged scene.toml "$granasym" dem run hardlink.toml --out scene.toml --quiet
unchanged gsd.csv "$granasym" dem generate --count 10 --gsd gsd.csv --out gsd.csv
unchanged result.h5 "$granasym" export result.h5 --csv result.h5
unchanged result.h5 "$granasym" export result.h5 --packing result.h5
unchanged model.toml "$granasym" model run model.toml --out model.toml
unchanged model.toml "$granasym" model run model.toml --csv model.toml
unchanged asymptotes.toml "$granasym" model asymptotes asymptotes.toml --out asymptotes.toml
unchanged calib.toml "$granasym" calibrate calib.toml --out calib.toml
unchanged states.csv "$granasym" calibrate calib.toml --summary states.csv
unchanged states.csv "$granasym" calibrate calib.toml --out states.csv
expect 2 "are the same file" "$granasym" export result.h5 --csv both.txt --packing both.txt
expect 2 "exists and is not a folder" "$granasym" study run programme.toml --out scene.toml

# Output locations, checked before the first step (no result computed and lost).
mkdir -p readonly && chmod 555 readonly
for out in missing/run.h5 readonly/run.h5 readonly; do
  case "$out" in
    missing/*) why="does not exist" ;;
    readonly/*) why="cannot be written" ;;
    *) why="is a folder" ;;
  esac
  if [ "$out" = readonly/run.h5 ] && [ "$(id -u)" = 0 ]; then
    # root writes anywhere: a read-only folder is not a fault for root.
    continue
  fi
  expect 2 "$why" "$granasym" dem run scene.toml --out "$out" --quiet
  expect 2 "$why" "$granasym" model run model.toml --out "$out"
done
expect 2 "does not exist" "$granasym" export result.h5 --csv missing/series.csv
expect 2 "does not exist" "$granasym" dem generate --count 10 --out missing/p.txt
expect 2 "does not exist" "$granasym" study run programme.toml --out missing/study
[ -e missing ] && fail "a refused output created its folder"

# Flags: bad input is status 2 with the hint on its own line; help is 0.
expect 2 "^error: scene is required$" "$granasym" dem run
expect 2 "^Run with --help" "$granasym" dem run scene.toml --bogus
expect 2 "^error: .*--count" "$granasym" dem generate --count 1 --out p.txt
expect 2 "^error: " "$granasym" dem run scene.toml --threads 0
expect 0 "Usage" "$granasym" dem run --help
expect 2 "^error: " "$granasym" nonsense

# Threads: capped at the hardware with a warning.
expect 0 "warning: --threads 1000 is more than the [0-9]+ hardware threads" \
  "$granasym" dem run scene.toml --out threads.h5 --threads 1000 --quiet

echo "$cases cases, $failures failures"
[ "$failures" -eq 0 ] && echo "PASS: outputs, output folders, flags and threads"
exit $((failures > 0))
