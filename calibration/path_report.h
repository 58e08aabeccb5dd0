// The whole-path datasets of a calibration in its outputs (issue 36 §4):
// per path the DEM's samples against the fitted model along them, for the
// summary and for plots/calibration_paths.gp.
#pragma once

#include <string>
#include <vector>

#include "calibration/calibration_problem.h"

namespace granasym::calibration {

// One line per path dataset (and one for the fitted unloading points) with
// its kind, control, samples and the RMS of the model − DEM misfit of ln p,
// ψ_σ (deg) and, under drained control, ln(1+e) at the full parameter
// vector `values`; where the model stopped early, how far it got. Empty
// without paths and fitted unloading points.
std::string PathSummaryText(const CalibrationProblem& problem, const std::vector<double>& values);

// In `folder` (created): path_<k>.csv per path dataset (k from 1), columns
// strain_path, DEM and model p_kpa, q_kpa, q_over_p, e, and paths.txt, one
// line per path, tab-separated: its file, "name (kind)" (the figure's row
// title) and its kind (PathKind name; isotropic unload_reload paths are drawn
// in e-p instead of q-p).
// Nothing without path datasets.
void WritePathPlotData(const CalibrationProblem& problem, const std::vector<double>& values,
                       const std::string& folder);

}  // namespace granasym::calibration
