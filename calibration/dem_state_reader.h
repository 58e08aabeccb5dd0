// Asymptotic states from granasym DEM result files (dem/simulation.cc):
// every /stages/NNN group of a strain-path stage contributes
//   - its detected asymptote (asymptote_detected = 1): one state (ψ_ε of the
//     stage, asymptote_p_kpa, asymptote_e, asymptote_psi_sigma_deg);
//   - when ψ_ε = 0 and no asymptote was detected: NCL points, the stage's rows
//     with p ≥ ncl_min_p_kpa and p rising, thinned to at most max_line_points
//     evenly spaced in ln p;
//   - when ψ_ε = 180°: unloading points (rows with p falling), for κ*;
// stages that ran the detector without success are skipped with a warning.
#pragma once

#include <string>

#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct DemReadOptions {
  // Rows of a ψ_ε = 0 stage below this mean stress (kPa) are not NCL points
  // (the loose initial packing first has to form a contact network).
  double ncl_min_p_kpa = 50.0;
  // Most NCL or unloading points taken per stage (evenly spaced in ln p),
  // so that one long stage does not outweigh the asymptotes.
  int max_line_points = 12;
  double kind_tolerance_deg = 0.5;  // ψ_ε within this of 0°, 90°, 180° counts as there
  double psi_sigma_uncertainty_deg = 0.5;  // one standard deviation, per state
  double ln_volume_uncertainty = 0.002;
  double weight = 1.0;
  bool IsValid(std::string* why) const;
};

// Throws InputError naming the file for files that are not granasym results
// (no /stages, no /series/p_kpa) or that yield no states.
StateDataset ReadStatesDem(const std::string& path, const std::string& name,
                           const DemReadOptions& options);

}  // namespace granasym::calibration
