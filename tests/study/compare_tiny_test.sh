#!/usr/bin/env bash
# `granasym study compare` on two tiny studies that differ in one parameter:
#   compare_tiny_test.sh GRANASYM WORK_DIR
# A: 600 spheres × 2 replicates, contact friction 0.5 rad, an NCL to 20 and
# 100 kPa and an isochoric (ψ_ε = 90°) path from NC 100 kPa; B: the same
# programme with frictionless contacts and one more NCL stage (50 kPa).
# Checks: the three common states are matched (both NCL stages and the
# critical state), B's extra stage is listed as only in B, the critical
# state's difference is reported (the frictionless sample is denser: ln(1+e)
# lower) with a verdict that agrees with its interval, every state point of
# the SVG has a hover label, the studies are left as they were; --out inside
# A, A = B, a folder that is no study and a non-empty foreign --out are
# refused with status 2; the default folder and a second run into an
# earlier comparison's folder work.
set -euo pipefail
source "$(dirname "$0")/../app/test_lib.sh"
granasym="$(realpath "$1")" work="$2"
rm -rf "$work"
mkdir -p "$work"

programme() {  # programme NAME FRICTION NCL_PRESSURES
  cat <<EOF
[study]
name = "$1"
ncl = "ncl"
[scale.tiny]
count = 600
replicates = 2
[sample]
reference_count = 150000
reference_cell_size_mm = 31.0
seed = 5
[scene.material]
youngs_modulus_mpa = 500.0
stiffness_ratio = 0.3
friction_angle_rad = $2
density_kg_m3 = 2650.0
local_damping = 0.5
[scene.numerics]
time_step_s = 1.2e-7
[scene.output]
interval_strain = 0.004
[[run]]
name = "ncl"
from = "sample"
[[run.stage]]
each = { p = [$3] }
name = "p{p}"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
stop.mean_stress_kpa = "{p}"
asymptote = {}
[[run]]
name = "nc100_psi90"
from = "ncl@p100"
[[run.stage]]
name = "psi90"
psi_epsilon_deg = 90.0
stretching_rate = 167.0
stop = { asymptote = true, strain_norm = 0.5 }
EOF
}
programme small 0.5 "20, 100" > "$work/a.toml"
programme frictionless 0.0 "20, 50, 100" > "$work/b.toml"
start=$(date +%s%N)
for s in a b; do
  "$granasym" study run "$work/$s.toml" --scale tiny --out "$work/$s" --jobs 2 --threads 1 \
    --quiet > "$work/run_$s.txt"
done
run_ms=$(( ($(date +%s%N) - start) / 1000000 ))

# Everything below A and B, to check that nothing is written there.
listing() { (cd "$1" && find . -type f -printf '%p %s %T@\n' | sort); }
listing "$work/a" > "$work/a_before.txt"
listing "$work/b" > "$work/b_before.txt"

out="$work/cmp"
start=$(date +%s%N)
"$granasym" study compare "$work/a" "$work/b" --out "$out" > "$work/compare.txt" ||
  fail "study compare exited with status $?"
compare_ms=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$work/compare.txt"
grep -q "^3 states matched (main 3); 1 unmatched (0 only in A, 1 only in B" "$work/compare.txt" ||
  fail "the summary does not say 3 matched and 1 only in B"
grep -q "φ = 0 rad" "$work/compare.txt" || fail "the summary does not give B's friction"

rows() { grep -v '^#' "$1" | tail -n +2; }
[ "$(rows "$out/compare_states.csv" | wc -l)" -eq 3 ] || fail "compare_states.csv: not 3 rows"
for state in "main,ncl,ncl,p20," "main,ncl,ncl,p100," "main,csl,nc100_psi90,psi90,"; do
  rows "$out/compare_states.csv" | grep -q "^$state" || fail "compare_states.csv has no row $state"
done
rows "$out/compare_unmatched.csv" | grep -q '^main,ncl,ncl,p50,only in B,absent,' ||
  fail "compare_unmatched.csv does not list ncl p50 as only in B"
rows "$out/compare_ncl.csv" | grep -q '^main,ncl,ncl,lambda_star,' ||
  fail "compare_ncl.csv has no lambda_star of the NCL"

# The critical state's differences (data of figure (c), tab-separated: y,
# B − A of ψ_σ, its half-width, class, of ln(1+e), half-width, class, label;
# class 0: the interval leaves out 0, 1: holds 0, 2: no interval).
diffs="$out/figures/data/compare_differences.tsv"
line=$(grep -F "$(printf '\t')nc100_psi90 psi90 (csl, main sample): B − A" "$diffs" || true)
[ -n "$line" ] || fail "figure (c) has no row of the critical state"
echo "$line" | awk -F'\t' '{
    if (!($5 < -0.02)) { print "FAIL: B − A of ln(1+e) at the critical state is " $5 ", not below -0.02"; bad = 1 }
    for (k = 2; k <= 5; k += 3) {  # two replicates a side: an interval, and its verdict
      verdict = ($k > $(k+1) || -$k > $(k+1)) ? 0 : 1
      if ($(k+2) != verdict) { print "FAIL: class " $(k+2) " of " $k " +- " $(k+1); bad = 1 }
    }
    exit bad }' || fail "the critical state's difference"
grep -q "nc100_psi90 psi90 (csl, main sample): B − A ψ_σ = " "$diffs" ||
  fail "the hover label of the critical state's difference"

# One hover label per state point: 3 states × 2 studies in (a) and (b), 3 ×
# 2 panels in (c).
for stem in compare_psi_sigma compare_ln_v compare_differences; do
  for ext in png pdf svg; do
    [ -s "$out/figures/$stem.$ext" ] || fail "$stem.$ext missing or empty"
  done
  labels=$(grep -o 'showHypertext(evt,' "$out/figures/$stem.svg" | wc -l)
  [ "$labels" -eq 6 ] || fail "$stem.svg has $labels hover labels, not 6"
done
grep -q "showHypertext(evt,'A a: nc100_psi90 psi90 (csl), 2 replicates; ψ_σ = " \
  "$out/figures/compare_psi_sigma.svg" || fail "the SVG has no hover label of A's critical state"
[ "$(tail -n +2 "$out/figures/index.tsv" | wc -l)" -eq 3 ] || fail "index.tsv: not 3 figures"
grep -q "^## Without a match" "$out/compare.md" || fail "compare.md has no unmatched section"
grep -q "^| programme | small | frictionless |" "$out/compare.md" ||
  fail "compare.md does not name the programmes"

# Refused: --out inside A (or A itself), A = B, a folder that is no study, a
# non-empty folder that holds no comparison. Nothing is written.
expect_refusal() {  # expect_refusal WHAT PATTERN ARGS...
  local what="$1" pattern="$2"
  shift 2
  local status=0
  "$granasym" study compare "$@" > "$work/refused.txt" 2>&1 || status=$?
  [ "$status" -eq 2 ] || fail "$what: exit status $status, not 2"
  grep -q "$pattern" "$work/refused.txt" || { fail "$what: message"; cat "$work/refused.txt"; }
}
expect_refusal "--out inside A" "inside study A" "$work/a" "$work/b" --out "$work/a/cmp"
[ ! -e "$work/a/cmp" ] || fail "--out inside A created $work/a/cmp"
expect_refusal "--out = B" "is study B" "$work/a" "$work/b" --out "$work/b"
expect_refusal "A = B" "the same folder" "$work/a" "$work/a/." --out "$work/cmp_same"
mkdir -p "$work/empty"
expect_refusal "no study" "not a study folder" "$work/a" "$work/empty" --out "$work/cmp_none"
mkdir -p "$work/foreign" && echo keep > "$work/foreign/notes.txt"
expect_refusal "foreign --out" "holds no earlier comparison" "$work/a" "$work/b" --out "$work/foreign"
[ "$(cat "$work/foreign/notes.txt")" = keep ] || fail "the foreign folder was changed"

# Again into the same folder (an earlier comparison's), and the default folder.
"$granasym" study compare "$work/a" "$work/b" --out "$out" --data-only > /dev/null ||
  fail "a second comparison into $out was refused"
(cd "$work" && "$granasym" study compare a b --data-only > /dev/null) ||
  fail "study compare without --out failed"
[ -s "$work/compare-a-vs-b/compare_states.csv" ] || fail "no default folder compare-a-vs-b"

listing "$work/a" | cmp -s - "$work/a_before.txt" || fail "study compare changed files of A"
listing "$work/b" | cmp -s - "$work/b_before.txt" || fail "study compare changed files of B"

[ "$failures" -eq 0 ] || { echo "$failures failures"; exit 1; }
echo "PASS: two tiny studies in ${run_ms} ms, compared in ${compare_ms} ms"
