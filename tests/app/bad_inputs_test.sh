#!/usr/bin/env bash
# Bad inputs through the command line: exit status 2 and "error: " with a
# message naming the file, the line and the value; nothing written.
#   bad_inputs_test.sh GRANASYM WORK_DIR
# 1. `dem generate --gsd BAD.csv` for GSD tables with a defect each.
# 2. `dem generate --count 1000000000` is refused at once (no allocation of
#    gigabytes first): by its memory, or by the solid fraction where the
#    machine has the memory.
# 3. `dem run` of a scene whose packing file has a defect.
set -uo pipefail
granasym="$1" work="$2"
rm -rf "$work"
mkdir -p "$work"
cd "$work" || exit 1
failures=0

# expect_error NAME "TEXT..." -- COMMAND...: status 2, stderr "error: " and every TEXT.
expect_error() {
  local name="$1"
  shift
  local texts=()
  while [ "$1" != "--" ]; do
    texts+=("$1")
    shift
  done
  shift
  local status=0
  "$@" >"$name.out" 2>"$name.err" || status=$?
  if [ "$status" -ne 2 ]; then
    echo "FAIL: $name: exit status $status, expected 2: $(cat "$name.err")"
    failures=$((failures + 1))
    return
  fi
  if ! grep -q "^error: " "$name.err"; then
    echo "FAIL: $name: no 'error: ' line: $(cat "$name.err")"
    failures=$((failures + 1))
  fi
  for text in "${texts[@]}"; do
    if ! grep -qF -- "$text" "$name.err"; then
      echo "FAIL: $name: '$text' not in: $(cat "$name.err")"
      failures=$((failures + 1))
    fi
  done
  echo "ok: $name: $(cat "$name.err")"
}

header="diameter_mm,percent_passing_by_mass"
gsd() { printf '%s\n' "$header" "$@" >"$name.csv"; }

name=gsd_1e-300_mm; gsd 1e-300,0 1,100
expect_error $name "$name.csv: line 2" "1e-300 mm" -- "$granasym" dem generate --gsd $name.csv --count 1000 --cell-mm 5.8 --out $name.txt
name=gsd_in_metres; gsd 0.0001,0 0.0005,40 0.002,100
expect_error $name "$name.csv" "0.002 mm at line 4" "metres" -- "$granasym" dem generate --gsd $name.csv --count 1000 --cell-mm 5.8 --out $name.txt
name=gsd_0.001_to_10_mm; gsd 0.001,0 10,100
expect_error $name "$name.csv" "0.001 mm (line 2)" "10 mm (line 3)" "at most 100" -- "$granasym" dem generate --gsd $name.csv --out $name.txt
name=gsd_decreasing; gsd 0.2,0 0.6,50 0.4,100
expect_error $name "$name.csv: line 4" "0.4 mm" -- "$granasym" dem generate --gsd $name.csv --out $name.txt
name=gsd_unknown_column; printf '%s\n' "$header,note" 0.2,0,1 1,100,2 >$name.csv
expect_error $name "$name.csv: line 1" "unknown column 'note'" -- "$granasym" dem generate --gsd $name.csv --out $name.txt
name=gsd_duplicate_column; printf '%s\n' "$header,diameter_mm" 0.2,0,0.2 1,100,1 >$name.csv
expect_error $name "$name.csv: line 1" "columns 1 and 3" -- "$granasym" dem generate --gsd $name.csv --out $name.txt

name=count_of_a_billion
start=$(date +%s%N)
expect_error $name "1000000000 spheres" -- "$granasym" dem generate --count 1000000000 --out $name.txt
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
# Generous for a loaded machine; before the check it took 50 s and 7.8 GB.
if [ "$elapsed_ms" -gt 5000 ]; then
  echo "FAIL: $name: refused after $elapsed_ms ms, expected at once"
  failures=$((failures + 1))
fi
if ! grep -qE "physical memory|fill at least" $name.err; then
  echo "FAIL: $name: neither memory nor solid fraction named: $(cat $name.err)"
  failures=$((failures + 1))
fi

scene() {
  printf '[sample]\npacking = "%s"\n[[stage]]\nname = "ncl"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n[stage.stop]\nsteps = 1\n' "$1" >"$name.toml"
}
name=packing_count_below_rows
printf '1 0.01 0.01 0.01\n0.002 0.002 0.002 0.001\n0.006 0.006 0.006 0.001\n' >$name.txt
scene $name.txt
expect_error $name "$name.txt: line 3" "follows the 1 spheres" -- "$granasym" dem run $name.toml --out $name.h5 --quiet
name=packing_overlap
printf '2 0.01 0.01 0.01\n0.002 0.002 0.002 0.001\n0.0034 0.002 0.002 0.001\n' >$name.txt
scene $name.txt
expect_error $name "$name.txt: lines 2 and 3" "overlap by 30 %" -- "$granasym" dem run $name.toml --out $name.h5 --quiet

for output in gsd_*.txt count_*.txt *.tmp *.h5; do
  [ -e "$output" ] && { echo "FAIL: $output written"; failures=$((failures + 1)); }
done
if [ "$failures" -ne 0 ]; then
  echo "$failures failures"
  exit 1
fi
echo "all bad inputs refused"
