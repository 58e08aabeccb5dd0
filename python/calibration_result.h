// A calibration's outcome as the Python module gives it, from a run
// (python/calibration.cc) or read from a study calibration's folder
// (python/results.cc): the texts of the files that `study calibrate` writes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "calibration/fit_status.h"

namespace granasym::python {

struct CalibrationResult {
  std::string model;  // the model kind's name
  calibration::FitOutcome outcome;
  std::string parameters_csv;  // parameters.csv; "" when the fit failed
  std::string warnings;        // warnings.txt
  std::string summary;         // summary.txt
  std::string folder;          // where its files are; "" when none were kept
  // selection.toml's selection ("all" or "quasi_static") of a study
  // calibration's folder; "" for a folder without one.
  std::string selection;
};

// DIR/calibration/<model>/ of `study calibrate`, or the `out` folder of
// granasym.calibrate: fit_status.toml, parameters.csv (absent after a failed
// fit), warnings.txt, summary.txt and the model of calibration.h5.
CalibrationResult ReadCalibrationFolder(const std::string& folder);

}  // namespace granasym::python
