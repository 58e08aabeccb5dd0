#!/usr/bin/env bash
# The Slurm job scripts' own checks, run without Slurm (with a stand-in for
# granasym that records its calls): JOBS=0 is refused with a message (not
# bash's "division by 0"), and merge.sbatch draws the figures and the report
# after a failed calibration, says so and ends with the calibration's status.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fake="$work/granasym"
cat > "$fake" <<'FAKE'
#!/usr/bin/env bash
echo "$*" >> "$CALLS"
[ "$1 $2" = "study calibrate" ] && exit 3
exit 0
FAKE
chmod +x "$fake"
export CALLS="$work/calls.txt"

status=0
SLURM_ARRAY_TASK_ID=0 SHARDS=1 JOBS=0 GRANASYM="$fake" OUT="$work/out" \
  bash "$root/studies/slurm/paper.sbatch" > "$work/jobs0.txt" 2>&1 || status=$?
[ "$status" = 2 ] || { echo "FAIL: JOBS=0 exited $status"; cat "$work/jobs0.txt"; exit 1; }
grep -q "JOBS=0 is not a positive number" "$work/jobs0.txt" ||
  { echo "FAIL: JOBS=0 without its message"; cat "$work/jobs0.txt"; exit 1; }
! grep -q "division" "$work/jobs0.txt" || { echo "FAIL: bash arithmetic error"; exit 1; }

: > "$CALLS"
status=0
GRANASYM="$fake" OUT="$work/out" bash "$root/studies/slurm/merge.sbatch" > "$work/merge.txt" 2>&1 ||
  status=$?
[ "$status" = 3 ] || { echo "FAIL: merge.sbatch exited $status, not the calibration's 3"; exit 1; }
for command in "study merge" "study calibrate" "study figures" "study report"; do
  grep -q "^$command" "$CALLS" || { echo "FAIL: merge.sbatch did not run $command"; cat "$CALLS"; exit 1; }
done
grep -q "study calibrate exited 3" "$work/merge.txt" ||
  { echo "FAIL: the failed calibration is not reported"; cat "$work/merge.txt"; exit 1; }

# An incomplete study (study merge exits 3: shards or cases named): the
# figures and the report are still made, SHARDS reaches the merge as
# --shards, and the job ends with 3.
incomplete="$work/incomplete"
cat > "$incomplete" <<'FAKE'
#!/usr/bin/env bash
echo "$*" >> "$CALLS"
[ "$1 $2" = "study merge" ] && exit 3
exit 0
FAKE
chmod +x "$incomplete"
: > "$CALLS"
status=0
SHARDS=4 GRANASYM="$incomplete" OUT="$work/out" bash "$root/studies/slurm/merge.sbatch" \
  > "$work/incomplete.txt" 2>&1 || status=$?
[ "$status" = 3 ] || { echo "FAIL: merge.sbatch exited $status after an incomplete merge"; exit 1; }
grep -q "^study merge .* --shards 4" "$CALLS" || { echo "FAIL: SHARDS not passed"; cat "$CALLS"; exit 1; }
grep -q "^study report" "$CALLS" || { echo "FAIL: no report after an incomplete merge"; exit 1; }
grep -q "the study is incomplete" "$work/incomplete.txt" ||
  { echo "FAIL: the incomplete study is not reported"; cat "$work/incomplete.txt"; exit 1; }
echo "PASS: JOBS=0 refused; a failed calibration still gets figures and a report, exit 3; an incomplete merge too"
