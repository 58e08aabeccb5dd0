# Shared by the command-line tests of tests/app/ (sourced, not run):
# failures are counted, and a small two-stage scene is written on request.
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# two_stage_scene FILE AXIAL_STRAIN [CHECKPOINT_INTERVAL_S]: 300 spheres, an
# NCL to 150 kPa, then drained triaxial compression to AXIAL_STRAIN; with a
# checkpoint interval of 1e-6 s a checkpoint (and partial result) is written
# every 256 steps.
two_stage_scene() {
  local file="$1" strain="$2" checkpoints="${3:-}"
  {
    printf '[sample.generate]\ncount = 300\ncell_size_mm = 3.9\nseed = 8\n'
    printf '[numerics]\ntime_step_s = 1.2e-7\n[output]\ninterval_strain = 0.004\n'
    [ -n "$checkpoints" ] && printf 'checkpoint_interval_s = %s\n' "$checkpoints"
    printf '[[stage]]\nname = "ncl"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n'
    printf '[stage.stop]\nmean_stress_kpa = 150.0\n'
    printf '[[stage]]\nname = "triaxial"\ntype = "triaxial"\naxial_strain_rate = 136.355\n'
    printf 'radial_stress_kpa = 150.0\n[stage.stop]\naxial_strain = %s\n' "$strain"
  } >"$file"
}
