#!/usr/bin/env bash
# `granasym study plan` of the tiny paper programme: every case with its
# depth and positive steps, totals that add up, the measured rate cached per
# machine (the second plan reads it), Slurm shards, and bad flags refused.
set -euo pipefail
granasym="$1"
programme="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
export XDG_CACHE_HOME="$work/cache"
fail() { echo "FAIL: $*"; exit 1; }

"$granasym" study plan "$programme" --scale tiny --jobs 1 --threads 1 --shards 2 > "$work/first.txt"
cat "$work/first.txt"
grep -q "measured now" "$work/first.txt" || fail "the first plan did not measure the rate"
[ -f "$XDG_CACHE_HOME/granasym/rates.toml" ] || fail "no rate cache written"
cases=$(sed -n 's/^study plan of .*: \([0-9]*\) cases .*/\1/p' "$work/first.txt")
[ -n "$cases" ] && [ "$cases" -gt 0 ] || fail "no case count in the header"
# The table: rows "r<K>/<name> depth time-step steps particle-steps time".
awk -v cases="$cases" '
  /^r[0-9]+\// { rows++; if ($2 < 1) bad = bad " depth " $1; if ($4 <= 0 || $5 <= 0) bad = bad " steps " $1;
                 steps += $4; ps += $5; if ($2 > depth) depth = $2 }
  /^total:/ { for (i = 1; i <= NF; i++) { if ($(i+1) == "steps,") tsteps = $i; if ($(i+1) == "particle-steps,") tps = $i; if ($i == "depth") tdepth = $(i+3) } }
  END {
    if (rows != cases) { print "FAIL: " rows " rows for " cases " cases"; exit 1 }
    if (bad != "") { print "FAIL:" bad; exit 1 }
    if (depth < 2 || tdepth + 0 != depth) { print "FAIL: depth " depth " vs total " tdepth; exit 1 }
    # The rows are rounded to 3 digits: their sums agree with the totals within 1 %.
    if (steps <= 0 || (steps - tsteps) ^ 2 > (0.01 * tsteps) ^ 2) { print "FAIL: steps " steps " vs " tsteps; exit 1 }
    if ((ps - tps) ^ 2 > (0.01 * tps) ^ 2) { print "FAIL: particle-steps " ps " vs " tps; exit 1 }
  }' "$work/first.txt"
grep -q "^wall time on this machine: " "$work/first.txt" || fail "no wall time"
grep -q "^peak memory: " "$work/first.txt" || fail "no peak memory"
grep -q "^jobs x threads: 1 x 1" "$work/first.txt" || fail "no jobs x threads"
[ "$(grep -c '^  shard [12]/2: ' "$work/first.txt")" = 2 ] || fail "not two shards"
grep -qE '^time limit per array task: --time=[0-9]+-[0-9]{2}:[0-9]{2}:00 ' "$work/first.txt" ||
  fail "no Slurm time limit"

# The paper's extension paths stop when they liquefy: bounds, marked and counted.
# Each with the low end of its range (it liquefies as early as the model
# allows), and the wall time a range.
grep -qE '^r1/nc100_psi120 .*  at most \(from [0-9.]+ (s|min|h)\)$' "$work/first.txt" ||
  fail "no 'at most (from ...)' on a liquefying case"
grep -qE "^  [0-9]+ case\(s\) marked 'at most'.*, [0-9.]+ (s|min|h) in all$" "$work/first.txt" ||
  fail "no count of the bounds and the low end of the total"
# (one time where both ends read the same)
grep -qE '^wall time on this machine: (between [0-9.]+ (s|min|h) and )?[0-9.]+ (s|min|h) with ' "$work/first.txt" ||
  fail "the wall time is not a range"

# --stages: every stage's estimate under its case; --tsv: the cases for scripts.
"$granasym" study plan "$programme" --scale tiny --jobs 1 --threads 1 --stages > "$work/stages.txt"
grep -qE '^    stage 1: strain [0-9.e+-]+, [0-9.e+-]+ steps .*: mean_stress_kpa$' "$work/stages.txt" ||
  fail "no stage estimates with --stages"
grep -qE '^    stage 1: strain [0-9.e+-]+, [0-9.e+-]+ steps .*\(from strain [0-9.e+-]+, [0-9.e+-]+ steps\): .*at most' "$work/stages.txt" ||
  fail "no earliest end of a stage that may liquefy with --stages"
"$granasym" study plan "$programme" --scale tiny --jobs 1 --threads 1 --tsv > "$work/plan.tsv"
head -1 "$work/plan.tsv" | grep -qP '^case\tdepth\ttime_step_s\tsteps\tloose_steps\tstill_steps\tstress_steps\tparticle_steps\tseconds\tat_most\tearliest_steps\tearliest_seconds$' ||
  fail "no TSV header"
[ "$(tail -n +2 "$work/plan.tsv" | wc -l)" = "$cases" ] || fail "TSV rows are not the $cases cases"
awk -F'\t' 'NR > 1 && !($4 > 0 && $9 > 0 && $6 <= $5 && $5 + $7 <= $4 * 1.000001 &&
                        $11 > 0 && $11 <= $4 * 1.000001 && $12 <= $9 * 1.000001 &&
                        ($10 == 1 || $11 == $4)) { print "FAIL: TSV row " $0; bad = 1 }
             END { exit bad }' "$work/plan.tsv"

"$granasym" study plan "$programme" --scale tiny --jobs 1 --threads 1 > "$work/second.txt"
grep -q "cached, measured" "$work/second.txt" || fail "the second plan measured again"
[ "$(grep -c '^\[\[rate\]\]' "$XDG_CACHE_HOME/granasym/rates.toml")" = 1 ] || fail "cache entries"

refuse() {  # expected text, then the arguments
  local expected="$1"; shift
  if "$granasym" study plan "$@" > "$work/bad.txt" 2>&1; then fail "accepted: $*"; fi
  grep -q -- "$expected" "$work/bad.txt" || { cat "$work/bad.txt"; fail "no '$expected' for: $*"; }
}
refuse "--shards" "$programme" --scale tiny --shards 0
refuse "--shards 100000" "$programme" --scale tiny --shards 100000
refuse "--jobs" "$programme" --scale tiny --jobs 0
refuse "--threads" "$programme" --scale tiny --threads x
refuse "--scale" "$programme" --scale huge
refuse "no_such.toml" "$work/no_such.toml" --scale tiny
echo "PASS: study plan of the tiny programme"
