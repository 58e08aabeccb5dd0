#!/usr/bin/env bash
# Partial results under the final name, through the command line:
#   partial_result_test.sh GRANASYM WORK_DIR
# A run killed with SIGKILL (and one stopped with SIGINT) leaves a readable
# result whose termination is "interrupted": `export --info` says it is not
# final and names the checkpoint, `export --csv` warns (and exports),
# `calibrate` refuses it (status 2); after `dem run --restart` the result is
# final and the warning is gone.
set -uo pipefail
granasym="$1" work="$2"
rm -rf "$work"
mkdir -p "$work"
source "$(dirname "${BASH_SOURCE[0]}")/test_lib.sh"

# A run long enough to be stopped in (about 2 s), with a checkpoint and a
# partial result every 256 steps.
two_stage_scene "$work/scene.toml" 0.3 1e-6

# Starts the run into $1 and sends $2 once its first partial result exists.
stop_run() {
  local out="$1" signal="$2"
  "$granasym" dem run "$work/scene.toml" --out "$out" --threads 1 --quiet >"$out.log" 2>&1 &
  local pid=$!
  for _ in $(seq 1 500); do
    [ -f "$out" ] && break
    sleep 0.01
  done
  kill "-$signal" "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  status=$?
}

stop_run "$work/killed.h5" KILL
[ "$status" -eq 137 ] || fail "SIGKILL: exit status $status (the run ended before the signal?)"
info=$("$granasym" export "$work/killed.h5" --info 2>&1)
rc=$?
grep -q '^rows: [1-9]' <<<"$info" || fail "export --info: the partial result has no rows: $info"
[ "$rc" -eq 0 ] || fail "export --info: status $rc: $info"
for line in "termination: interrupted" "final: no: '$work/killed.h5' is a partial result" \
            "checkpoint: $work/killed.h5.ckpt" "scene: $work/scene.toml"; do
  grep -qF -- "$line" <<<"$info" || fail "export --info: no '$line' in: $info"
done
# One item per line, "key: value".
if grep -qv '^[a-z_0-9 ]*: ' <<<"$info"; then fail "export --info: lines that are not 'key: value'"; fi
echo "$info" | sed 's/^/  /'

out=$("$granasym" export "$work/killed.h5" --csv "$work/killed.csv" 2>&1)
rc=$?
[ "$rc" -eq 0 ] || fail "export --csv of a partial result: status $rc: $out"
grep -q "^warning: '$work/killed.h5' is a partial result" <<<"$out" ||
  fail "export --csv of a partial result: no warning in: $out"
[ -s "$work/killed.csv" ] || fail "export --csv of a partial result: no CSV"

cat >"$work/calibration.toml" <<'TOML'
[model]
kind = "modified_cam_clay"
[[dataset]]
name = "partial"
dem = "killed.h5"
TOML
out=$("$granasym" calibrate "$work/calibration.toml" --quiet 2>&1)
rc=$?
[ "$rc" -eq 2 ] || fail "calibrate on a partial result: status $rc, expected 2: $out"
grep -q "^error: $work/killed.h5: a partial result, not calibration data" <<<"$out" ||
  fail "calibrate on a partial result: no refusal in: $out"

out=$("$granasym" dem run "$work/scene.toml" --out "$work/killed.h5" --threads 1 --quiet --restart 2>&1)
rc=$?
[ "$rc" -eq 0 ] || fail "the restart after SIGKILL: status $rc: $out"
info=$("$granasym" export "$work/killed.h5" --info 2>&1)
grep -qx "final: yes" <<<"$info" || fail "after the restart: not final: $info"
grep -qx "checkpoint: none" <<<"$info" || fail "after the restart: a checkpoint is left: $info"
out=$("$granasym" export "$work/killed.h5" --csv "$work/final.csv" 2>&1)
if grep -q warning <<<"$out"; then fail "export of the final result warns: $out"; fi

stop_run "$work/interrupted.h5" INT
[ "$status" -eq 130 ] || fail "SIGINT: exit status $status, expected 130"
info=$("$granasym" export "$work/interrupted.h5" --info 2>&1)
grep -q "^message: interrupted at step [0-9]*; continue with --restart" <<<"$info" ||
  fail "SIGINT: export --info: $info"
grep -q "^final: no: " <<<"$info" || fail "SIGINT: export --info says final: $info"

if [ "$failures" -gt 0 ]; then
  echo "FAIL: $failures check(s) failed"
  exit 1
fi
echo "PASS: partial results are named as such by export --info, export and calibrate"
