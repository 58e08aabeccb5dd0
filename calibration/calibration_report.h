// Running a calibration file and reporting it: the fitted parameters with
// standard errors, 95 % intervals and correlations, residuals per dataset and
// per point, warnings, objective history, the parameters in the orders of
// Mašín's UMAT and PLAXIS; an HDF5 record, a readable summary and CSV/DAT
// files for the figures (plots/calibration_*.gp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "calibration/calibration_config.h"
#include "calibration/calibration_problem.h"
#include "calibration/fit_result.h"
#include "calibration/starting_values.h"

namespace granasym::calibration {

struct CalibrationRun {
  CalibrationConfig config;
  StartingValues starting_values;
  std::unique_ptr<CalibrationProblem> problem;
  std::vector<FitResult> fits;  // one per fitter, in the order run
  // method = both: the largest |θ_ceres − θ_nlopt| / standard error (Ceres).
  double agreement_in_standard_errors = 0.0;
};

// The parameters for `kind` with the user's choices applied; parameters
// without a value start from the data where an estimate exists.
ModelParameters ChooseParameters(ModelKind kind, const std::vector<ParameterChoice>& choices,
                                 const StartingValues& starting_values);

// Reads the datasets, estimates starting values, builds the problem and runs
// the fitters. Throws InputError for bad data (naming file/line/column).
CalibrationRun RunCalibration(const CalibrationConfig& config);

std::string SummaryText(const CalibrationRun& run);
void WriteCalibrationHdf5(const CalibrationRun& run, const std::string& path);
// states.csv, model_curve.csv, model_lines.dat in `folder` (created).
void WritePlotData(const CalibrationRun& run, const FitResult& fit, const std::string& folder);

}  // namespace granasym::calibration
