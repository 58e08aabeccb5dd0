// Asymptotic states from granasym DEM result files (layout: dem/run_record_names.h):
// every /stages/NNN group of a strain-path stage contributes
//   - its detected asymptote (asymptote_detected = 1): one state (ψ_ε of the
//     stage, asymptote_p_kpa, asymptote_e, asymptote_psi_sigma_deg);
//   - when ψ_ε = 0 and no asymptote was detected: NCL points, the stage's rows
//     with p ≥ ncl_min_p_kpa and p rising, thinned to at most max_line_points
//     evenly spaced in ln p;
//     rows of such a stage below the largest p reached before it are
//     reloading rows (an unload–reload cycle): unloading points, never NCL;
//   - when ψ_ε = 180°: unloading points (rows with p falling), for κ*;
//   unloading points start their branch at the row before the stage and
//     carry unloading_weight (fitted through the model integrated along the
//     branch, calibration_problem.h);
//   - with asbs_ln_1_plus_e set: for each detected asymptote (not at 180°) and
//     each requested value v of ln(1+e), one ASBS cross-section point (paper
//     Figs. 17–18): the asymptotic line of the stage, ln(1+e) linear in ln p
//     with the stored slope asymptote_dln1pe_dlnp through (asymptote_p_kpa,
//     asymptote_e), followed to ln(1+e) = v:
//       ln p = ln p_a + (v − ln(1+e_a)) / slope,  e = exp(v) − 1,
//     with the stage's asymptotic ψ_σ; ψ_ε of the stage is kept on the point
//     for the record (the fit does not use ψ_ε of ASBS points). Skipped with a
//     warning: stages without a usable slope (missing, not finite, or
//     |slope| < asbs_min_abs_slope — isochoric paths such as ψ_ε = 90° give
//     ~0, and the constant-e line cannot be followed), and values that would
//     need |Δ ln p| > asbs_max_ln_p_extrapolation (1.0: a factor e ≈ 2.7 in p)
//     from the asymptote;
// stages that ran the detector without success are skipped with a warning.
#pragma once

#include <string>
#include <vector>

#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct DemReadOptions {
  // Rows of a ψ_ε = 0 stage below this mean stress (kPa) are not NCL points
  // (the loose initial packing first has to form a contact network).
  double ncl_min_p_kpa = 50.0;
  // Most NCL or unloading points taken per stage (evenly spaced in ln p),
  // so that one long stage does not outweigh the asymptotes.
  int max_line_points = 12;
  double kind_tolerance_deg = 0.5;         // ψ_ε within this of 0°, 90°, 180° counts as there
  double psi_sigma_uncertainty_deg = 0.5;  // one standard deviation, per state
  double ln_volume_uncertainty = 0.002;
  double weight = 1.0;
  // Weight of the unloading and reloading rows (0: read, for the κ* start
  // and drawn, not fitted).
  double unloading_weight = 1.0;
  // Values of ln(1+e) at which ASBS cross-section points are taken (each
  // finite and > 0); empty: none.
  std::vector<double> asbs_ln_1_plus_e;
  // Stages whose |d ln(1+e)/d ln p| is below this give no ASBS points.
  double asbs_min_abs_slope = 1e-4;
  // Most |Δ ln p| from the detected asymptote to an ASBS point.
  double asbs_max_ln_p_extrapolation = 1.0;
  bool IsValid(std::string* why) const;
};

// Throws InputError naming the file for files that are not granasym results
// (no /stages, no /series/p_kpa), for partial results (termination
// interrupted: a run stopped or still running) or that yield no states. The
// stage a run failed in is skipped with a warning.
StateDataset ReadStatesDem(const std::string& path, const std::string& name,
                           const DemReadOptions& options);

}  // namespace granasym::calibration
