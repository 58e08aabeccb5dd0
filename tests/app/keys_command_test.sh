#!/usr/bin/env bash
# `granasym keys`: the key tables of every input kind, as text and Markdown;
# an unknown kind or format is refused with status 2.
set -euo pipefail
granasym="$1"
fail() { echo "FAIL: $*"; exit 1; }

scene=$("$granasym" keys scene)
grep -q '^\[sample.generate\]$' <<<"$scene" || fail "no [sample.generate] in keys scene"
grep -q '^  youngs_modulus_mpa: number (MPa), in \[0.001, 10000000\]; default 500$' <<<"$scene" ||
  fail "youngs_modulus_mpa line"
if grep -q 'psi_epsilon_deg' <<<"$scene"; then fail "stage keys in keys scene"; fi

all=$("$granasym" keys)
for kind in scene stage programme calibration figures; do
  grep -q "^$kind keys: " <<<"$all" || fail "no $kind table in granasym keys"
done

markdown=$("$granasym" keys stage --format markdown)
grep -q '^# Keys: stage$' <<<"$markdown" || fail "no Markdown title"
grep -q '^| key | type | unit | valid | default | meaning |$' <<<"$markdown" || fail "no Markdown table"
grep -q '^| `psi_epsilon_deg` | number | deg | in \[-180, 180\] | required |' <<<"$markdown" ||
  fail "psi_epsilon_deg row"

for args in "bogus" "scene --format html"; do
  status=0
  # shellcheck disable=SC2086
  "$granasym" keys $args > /dev/null 2> keys_error.txt || status=$?
  [ "$status" = 2 ] || fail "keys $args: status $status, expected 2"
  grep -q "${args##* }" keys_error.txt || fail "keys $args: the message does not name it"
done
rm -f keys_error.txt
echo "PASS: granasym keys"
