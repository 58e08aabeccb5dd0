#!/usr/bin/env bash
# Do two granasym binaries compute the same DEM results? Runs the same short
# scenes with both and compares the exported series byte for byte (issue 11:
# a change meant to be exact must leave every series bit-identical for a
# fixed thread count). The scenes cover the run loop's kernels: the paper's
# linear law, Hertz–Mindlin and rolling resistance on a generated sample
# compressed at 167 1/s to a mean stress (every step measures the stress:
# the separate force and integration passes), then sheared isochorically to
# a strain (the fused step, with the stress every output row), each at 1 and
# 2 threads; and the inertial-number rule with an adaptive time step.
#
#   bench/same_results.sh REFERENCE_BINARY CANDIDATE_BINARY [--count N] [--out DIR]
#
# Exit status 0 when every series is identical, 1 when one differs (the first
# differing lines are printed), 2 on bad arguments.
set -euo pipefail
usage() { sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
[[ $# -ge 2 ]] || { usage >&2; exit 2; }
REF="$1"; NEW="$2"; shift 2
COUNT=3000
OUT="same_results_out"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --count) COUNT="$2"; shift 2 ;;
    --out) OUT="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "same_results.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
for b in "$REF" "$NEW"; do
  [[ -x "$b" ]] || { echo "same_results.sh: '$b' is not an executable" >&2; exit 2; }
done
[[ "$COUNT" =~ ^[0-9]+$ && "$COUNT" -ge 500 ]] ||
  { echo "same_results.sh: --count must be an integer >= 500, got '$COUNT'" >&2; exit 2; }
mkdir -p "$OUT"
cell="$(python3 -c "print(round(31.0 * ($COUNT / 150000) ** (1 / 3), 4))")"

scene() {  # name law rolling threads
  local name="$1" law="$2" rolling="$3" threads="$4"
  cat > "$OUT/$name.toml" <<TOML
[sample.generate]
count = $COUNT
cell_size_mm = $cell
seed = 7
[material]
contact_law = "$law"
rolling_friction = $rolling
friction_angle_rad = 0.5
local_damping = 0.5
[numerics]
time_step_s = 1.2e-7
threads = $threads
[output]
interval_steps = 200
[[stage]]
name = "compress"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
stop.mean_stress_kpa = 200.0
[[stage]]
name = "shear"
psi_epsilon_deg = 90.0
stretching_rate = 167.0
stop.strain_norm = 0.03
[[stage]]
name = "slow"
psi_epsilon_deg = 100.0
stretching_rate = 5000.0
rate = { rule = "inertial", inertial_number = 0.01, diameter = "d_max", min_mean_stress_kpa = 1.0 }
stop.strain_norm = 0.005
TOML
}

status=0
for threads in 1 2; do
  for variant in "linear 0.0" "hertz_mindlin 0.0" "linear 0.1"; do
    set -- $variant
    name="${1}_mur${2}_t${threads}"
    scene "$name" "$1" "$2" "$threads"
    for side in ref new; do
      bin="$REF"; [[ $side == new ]] && bin="$NEW"
      "$bin" dem run "$OUT/$name.toml" --out "$OUT/$name.$side.h5" --quiet >/dev/null
      "$bin" export "$OUT/$name.$side.h5" --csv "$OUT/$name.$side.csv" >/dev/null
    done
    # The series only: the wall-time and program columns differ by nature.
    if cmp -s "$OUT/$name.ref.csv" "$OUT/$name.new.csv"; then
      echo "identical  $name ($(($(wc -l < "$OUT/$name.ref.csv") - 1)) rows)"
    else
      echo "DIFFERENT  $name"
      diff "$OUT/$name.ref.csv" "$OUT/$name.new.csv" | head -6
      status=1
    fi
  done
done
exit $status
