#!/usr/bin/env bash
# Every writer of granasym on a full disk, through the command line:
#   disk_full_test.sh GRANASYM SOURCE_DIR WORK_DIR
# For each writer (dem run's result and checkpoint, dem generate, export --csv
# and --packing, model run --out/--csv, calibrate, study run) a good file
# sits at the final name first; then the command runs with no space left and
# must exit with status 1 (a file-system failure) and a message naming the
# file, never be killed by a signal, leave no *.tmp behind and leave the good
# file as it was. A run that fails to write keeps its last checkpoint, says so,
# and continues from it bit-identically once there is space.
#
# The disk is full in one of two ways, and the test says which: a small tmpfs
# mounted over the output folder and filled up (needs root and a mount that
# is allowed), else RLIMIT_FSIZE (`ulimit -f`: writes beyond the limit fail
# with EFBIG; SIGXFSZ is ignored, as a process on a full disk gets no signal).
# GRANASYM_DISK_FULL_MODE=rlimit forces the second.
set -uo pipefail
granasym="$1" source_dir="$2" work="$3"
mode="${GRANASYM_DISK_FULL_MODE:-auto}"
full="$work/full"  # every output goes here
if mountpoint -q "$full" 2>/dev/null; then umount "$full"; fi
rm -rf "$work"
mkdir -p "$full" "$work/good"
source "$(dirname "${BASH_SOURCE[0]}")/test_lib.sh"

if [ "$mode" != rlimit ] && mount -t tmpfs -o size=16m tmpfs "$full" 2>/dev/null; then
  mode=tmpfs
  trap 'umount "$full" 2>/dev/null' EXIT
else
  mode=rlimit
fi
echo "disk full by: $mode"

# Fills the tmpfs but for `$1` KiB (0: full).
fill() {
  local leave_kib="${1:-0}" avail_kib
  rm -f "$full/filler"
  avail_kib=$(df -k --output=avail "$full" | tail -1)
  if [ "$leave_kib" -gt 0 ]; then
    dd if=/dev/zero of="$full/filler" bs=1k count=$((avail_kib - leave_kib)) 2>/dev/null
  else
    dd if=/dev/zero of="$full/filler" bs=64k 2>/dev/null
    dd if=/dev/zero of="$full/filler" bs=1k oflag=append conv=notrunc 2>/dev/null
  fi
}
unfill() { rm -f "$full/filler"; }

# Runs a command on the full disk (`$1` KiB left, or the file-size limit in
# rlimit mode; 0: nothing), its output in $out and its status in $rc. Output
# goes through a pipe: a file-size limit applies to files only.
on_full_disk() {
  local room_kib="$1"
  shift
  if [ "$mode" = tmpfs ]; then
    fill "$room_kib"
    out=$("$@" 2>&1)
    rc=$?
    unfill
  else
    out=$( (trap '' XFSZ; ulimit -f "$room_kib"; exec "$@") 2>&1)
    rc=$?
  fi
}

# A good file to keep: its copy outside the full folder.
keep() { cp -a "$1" "$work/good/$(basename "$1")"; }

# The checks of one writer: status 1, the file named, no signal, no
# temporary, the good file unchanged.
check() {
  local what="$1" named="$2" before="$failures"
  shift 2
  if [ "$rc" -ge 128 ]; then fail "$what: killed by signal $((rc - 128)): $out"; fi
  [ "$rc" -eq 1 ] || fail "$what: exit status $rc, expected 1: $out"
  grep -q "^failure: .*$named" <<<"$out" || fail "$what: no 'failure: ... $named' in: $out"
  local leftover
  leftover=$(find "$full" -name '*.tmp')
  [ -z "$leftover" ] || fail "$what: temporary files left: $leftover"
  for good in "$@"; do
    cmp -s "$good" "$work/good/$(basename "$good")" || fail "$what: $good was changed"
  done
  if [ "$failures" -eq "$before" ]; then
    echo "ok: $what ($(grep -o 'failure: .*' <<<"$out" | cut -c1-150)...)"
  fi
}

# The inputs, on a disk with space.
two_stage_scene "$work/scene.toml" 0.02
# The same with a checkpoint every 256 steps.
sed 's/^interval_strain = 0.004$/interval_strain = 0.004\ncheckpoint_interval_s = 1e-6/' \
  "$work/scene.toml" >"$work/scene_checkpoints.toml"
"$granasym" dem run "$work/scene.toml" --out "$work/straight.h5" --threads 1 --quiet >/dev/null ||
  fail "the straight run failed"
"$granasym" export "$work/straight.h5" --csv "$work/straight.csv" >/dev/null

# HDF5 writers get 8 KiB: the file is created, its data do not fit.
# dem run: the result at the end (no checkpoint was written: nothing kept).
"$granasym" dem run "$work/scene.toml" --out "$full/run.h5" --threads 1 --quiet >/dev/null
keep "$full/run.h5"
on_full_disk 8 "$granasym" dem run "$work/scene.toml" --out "$full/run.h5" --threads 1 --quiet
check "dem run (result)" "cannot write '$full/run.h5'" "$full/run.h5"
grep -q "no checkpoint had been written" <<<"$out" || fail "dem run (result): no word on checkpoints"

# dem run: checkpoints every 256 steps and partial results, until a write
# fails (they grow with the series and the contacts: 60 to 240 kB); the last
# checkpoint is kept and named, and the run continues from it to the same
# bytes as the straight run. Room for a few of them: 300 kB on the tmpfs
# (then a checkpoint beside a partial result does not fit), or files of at
# most 150 kB.
room=$([ "$mode" = tmpfs ] && echo 300 || echo 150)
on_full_disk "$room" "$granasym" dem run "$work/scene_checkpoints.toml" \
  --out "$full/ckpt_run.h5" --threads 1 --quiet
check "dem run (checkpoint, partial results)" "cannot write '$full/ckpt_run.h5"
grep -q "nothing computed up to step [0-9]* is lost: the checkpoint '$full/ckpt_run.h5.ckpt'" \
  <<<"$out" || fail "dem run (checkpoint): the kept checkpoint is not named: $out"
[ -f "$full/ckpt_run.h5.ckpt" ] || fail "dem run (checkpoint): the checkpoint is gone"
"$granasym" dem run "$work/scene_checkpoints.toml" --out "$full/ckpt_run.h5" --threads 1 \
  --quiet --restart >/dev/null || fail "dem run (checkpoint): the restart failed"
"$granasym" export "$full/ckpt_run.h5" --csv "$work/restarted.csv" >/dev/null
cmp -s "$work/straight.csv" "$work/restarted.csv" ||
  fail "dem run (checkpoint): the restarted run differs from the straight run"

# dem generate --out.
"$granasym" dem generate --count 300 --cell-mm 3.9 --out "$full/packing.txt" >/dev/null
keep "$full/packing.txt"
on_full_disk 0 "$granasym" dem generate --count 300 --cell-mm 3.9 --seed 2 --out "$full/packing.txt"
check "dem generate --out" "cannot write '$full/packing.txt'" "$full/packing.txt"

# export --csv and --packing.
cp "$work/straight.csv" "$full/run.csv"
"$granasym" export "$work/straight.h5" --packing "$full/final.txt" >/dev/null
keep "$full/run.csv"
keep "$full/final.txt"
on_full_disk 0 "$granasym" export "$work/straight.h5" --csv "$full/run.csv"
check "export --csv" "cannot write '$full/run.csv'" "$full/run.csv"
on_full_disk 0 "$granasym" export "$work/straight.h5" --packing "$full/final.txt"
check "export --packing" "cannot write '$full/final.txt'" "$full/final.txt"

# export --csv to a full device (its own, 1:7 like /dev/full, where it may).
device="$work/full_device"
mknod "$device" c 1 7 2>/dev/null || device=/dev/full
out=$("$granasym" export "$work/straight.h5" --csv "$device" 2>&1)
rc=$?
check "export --csv $device" "cannot write '$device': No space left on device"
[ -c "$device" ] || fail "export --csv $device: the device was replaced"
[ ! -e "$device.tmp" ] || fail "export --csv $device: $device.tmp left"

# model run --out and --csv.
cp "$source_dir/constitutive/examples/cam_clay_drained.toml" "$work/model.toml"
"$granasym" model run "$work/model.toml" --out "$full/model.h5" --csv "$full/model.csv" >/dev/null ||
  fail "model run failed"
keep "$full/model.h5"
keep "$full/model.csv"
on_full_disk 8 "$granasym" model run "$work/model.toml" --out "$full/model.h5" --csv "$full/model.csv"
check "model run --out --csv" "cannot write '$full/model" "$full/model.h5" "$full/model.csv"

# calibrate: the record, the summary, the plot data (synthetic states).
cat >"$work/states.csv" <<'EOF'
p_kpa,e,psi_sigma_deg,psi_epsilon_deg
50,1.575,0,0
100,1.385,0,0
200,1.215,0,0
400,1.062,0,0
800,0.925,0,0
50,1.430,11.4,90
100,1.253,11.4,90
200,1.095,11.4,90
400,0.953,11.4,90
60,1.497,6.8,45
120,1.323,6.8,45
240,1.158,6.8,45
EOF
cat >"$work/calibration.toml" <<'EOF'
[model]
kind = "modified_cam_clay"
[parameters.poisson_ratio]
free = false
value = 0.25
[[dataset]]
name = "synthetic"
csv = "states.csv"
[fitter]
method = "ceres"
EOF
calibrate=("$granasym" calibrate "$work/calibration.toml" --quiet --out "$full/calibration.h5"
  --summary "$full/calibration.txt" --plot-data "$full/calibration_plots")
"${calibrate[@]}" >/dev/null || fail "calibrate failed"
keep "$full/calibration.h5"
keep "$full/calibration.txt"
on_full_disk 8 "${calibrate[@]}"
check "calibrate" "cannot write '$full/calibration" "$full/calibration.h5" "$full/calibration.txt"

# study run: a one-case study, then the same again (cached: it rewrites its
# tables) on the full disk.
cat >"$work/programme.toml" <<'EOF'
[study]
name = "disk-full"
ncl = "ncl"
[scale.tiny]
count = 250
[sample]
reference_count = 150000
reference_cell_size_mm = 31.0
seed = 4
[scene.numerics]
time_step_s = 1.2e-7
[scene.output]
interval_strain = 0.004
[[run]]
name = "ncl"
from = "sample"
[[run.stage]]
name = "p20"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
stop.mean_stress_kpa = 20.0
asymptote = {}
EOF
study=("$granasym" study run "$work/programme.toml" --scale tiny --out "$full/study" --quiet)
"${study[@]}" >/dev/null || fail "study run failed"
keep "$full/study/asymptotic_states.csv"
keep "$full/study/cases/r1/ncl/done.toml"
on_full_disk 0 "${study[@]}"
check "study run" "cannot write '$full/study/" "$full/study/asymptotic_states.csv" \
  "$full/study/cases/r1/ncl/done.toml"

if [ "$failures" -gt 0 ]; then
  echo "FAIL: $failures check(s) failed (disk full by $mode)"
  exit 1
fi
echo "PASS: every writer on a full disk (by $mode)"
