#!/usr/bin/env bash
# Restarts from damaged checkpoints through the command line:
#   corrupt_checkpoint_test.sh GRANASYM HDF5_TAMPER WORK_DIR
# A run keeps its last periodic checkpoint (in its last stage); copies of it
# get a flipped bit in one dataset (its checksum fails), or a value that
# breaks the state's invariants under matching checksums. Each restart must
# end with status 2 and "error: FILE: dataset NAME ...", never a signal, and
# leave the checkpoint and the result as they were; the intact copy restarts
# to the same bytes as the run.
set -uo pipefail
granasym="$1" tamper="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
source "$(dirname "${BASH_SOURCE[0]}")/test_lib.sh"

two_stage_scene "$work/scene.toml" 0.02 1e-6
"$granasym" dem run "$work/scene.toml" --out "$work/run.h5" --threads 1 --quiet --keep-checkpoint \
  >/dev/null || { echo "FAIL: the run failed"; exit 1; }
"$granasym" export "$work/run.h5" --csv "$work/run.csv" >/dev/null
[ -f "$work/run.h5.ckpt" ] || { echo "FAIL: no checkpoint kept"; exit 1; }

# restart NAME EXPECTED_STATUS EXPECTED_TEXT [tamper arguments, FILE replaced]
restart() {
  local name="$1" status="$2" expected="$3"
  shift 3
  local before="$failures" case_out="$work/$name.h5"
  cp "$work/run.h5" "$case_out"
  cp "$work/run.h5.ckpt" "$case_out.ckpt"
  if [ $# -gt 0 ]; then
    local command="$1"
    shift
    "$tamper" "$command" "$case_out.ckpt" "$@" >/dev/null || fail "$name: hdf5_tamper failed"
  fi
  cp "$case_out.ckpt" "$work/$name.damaged"
  local out rc
  out=$("$granasym" dem run "$work/scene.toml" --out "$case_out" --threads 1 --quiet --restart 2>&1)
  rc=$?
  [ "$rc" -lt 128 ] || fail "$name: killed by signal $((rc - 128)): $out"
  [ "$rc" -eq "$status" ] || fail "$name: exit status $rc, expected $status: $out"
  grep -qF -- "$expected" <<<"$out" || fail "$name: no '$expected' in: $out"
  if [ "$status" -ne 0 ]; then
    cmp -s "$case_out.ckpt" "$work/$name.damaged" || fail "$name: the checkpoint was changed"
    cmp -s "$case_out" "$work/run.h5" || fail "$name: the result was changed"
  fi
  if [ "$failures" -eq "$before" ]; then echo "ok: $name ($(head -c 160 <<<"$out"))"; fi
}

restart intact 0 "completed"
"$granasym" export "$work/intact.h5" --csv "$work/intact.csv" >/dev/null
cmp -s "$work/run.csv" "$work/intact.csv" || fail "intact: the restart differs from the run"

for dataset in /engine/list/offsets /engine/id /engine/position /engine/velocity \
               /engine/list/shear /series/p_kpa; do
  restart "flip_${dataset//\//_}" 2 \
    "error: $work/flip_${dataset//\//_}.h5.ckpt: dataset '$dataset' fails its checksum (the file is corrupt)" \
    flip "$dataset" 83 3
done
restart offsets_decrease 2 "dataset /engine/list/offsets decreases" \
  set-int /engine/list/offsets 10 1000000
restart ids_no_permutation 2 "dataset /engine/id is not a permutation of 0..299" \
  set-int /engine/id 1 299999
restart neighbour_out_of_range 2 "dataset /engine/list/neighbors entry 0 = 300 " \
  set-int /engine/list/neighbors 0 300

if [ "$failures" -gt 0 ]; then
  echo "FAIL: $failures check(s) failed"
  exit 1
fi
echo "PASS: every damaged checkpoint refused with its dataset named; the intact one restarts"
