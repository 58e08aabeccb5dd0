// The calibration of the constitutive models to a study's asymptotic states
// (`granasym study calibrate`): the calibration built in code from the study
// folder, run through the calibration library, and its outputs in
// DIR/calibration/<model>/ (the study's default selection; the other
// selection in DIR/calibration/<selection>/<model>/:
// analysis/calibration_selections.h), whose names the figures and the report read:
//   calibration.toml  the calibration as a file (calibration/calibration_config.h),
//                     to edit and rerun with `granasym calibrate`
//   calibration.h5, summary.txt, warnings.txt, parameters.csv, model.toml,
//   plot_data/        the calibration library's outputs (calibration_report.h)
//   fit_status.toml   the fit's status and its reason (calibration/fit_status.h:
//                     `status` and `reason`), also when the fit failed (then
//                     without parameters.csv, model.toml and plot_data/)
//   paths/psi<ψ>_ocr<k>/  Fig. 5 for the fitted model (WriteModelPaths)
//   selection.toml    the selection (all or quasi_static) and what it fits
//
// The data: a study's detected states whose OCR refers to the study's NCL
// (other samples, e.g. φ = 0, stay out), or a quasi-static selection (issue 36
// §2, `study calibrate --select quasi_static`): for a rate study its
// quasi-static set (analysis/quasi_static_selection.h: its ψ_ε = 0° states also
// when drifting, its other states with the drained cases when detected), for
// another study those of its states with I(d_max) below a bound
// (kQuasiStaticInertialNumber by default).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "analysis/calibration_selections.h"
#include "analysis/quasi_static_selection.h"
#include "calibration/calibration_config.h"
#include "calibration/fit_status.h"

namespace granasym::analysis {

// The whole-path datasets (issue 36 §3, calibration/path_dataset.h) of a
// study: the finished cases of replicate r1 whose stages make one of the
// paper's paths: Fig. 9 (unload and reload stages at psi_epsilon = 180 and
// 0 deg only: unload_reload), Fig. 11 (one stage at 90 deg: isochoric; from
// an OC state when the case name starts with "oc") and Fig. 12 (one drained
// triaxial stage), starting at p >= kStudyPathMinStartKpa (the paths from
// 1-5 kPa are stiff to integrate and noisy at small scales). Of each of the
// four groups (cycles, OC isochoric, NC isochoric, drained) at most
// kStudyPathsPerKind, the ones of median starting p, each with
// kStudyPathPoints samples and weight 1 (a path counts as one state), so
// that the fit's cost stays a few short integrations per evaluation. A case whose path cannot be
// read is left out with a note. Not for rate studies (their quasi-static selection has no paths).
inline constexpr size_t kStudyPathsPerKind = 1;
inline constexpr double kStudyPathMinStartKpa = 10.0;
inline constexpr int kStudyPathPoints = 30;
std::vector<calibration::DatasetConfig> StudyPathDatasets(const std::string& directory,
                                                          std::vector<std::string>* notes);

// The selection of a calibration: quasi_static with a rate study's
// quasi-static set or a finite bound on I(d_max), else all.
CalibrationSelection SelectionOf(const QuasiStaticSelection* quasi_static,
                                 double max_inertial_number);

// The calibration of `model` to the study in `directory`, as the file
// calibration.toml in its selection's folder (SelectionFolder:
// DIR/calibration/<model>/ for the study's default selection,
// DIR/calibration/<selection>/<model>/ for the other) would give it; `quasi_static`
// (null for other studies) selects a rate study's quasi-static cases, and a
// finite `max_inertial_number` only the states with I(d_max) below it.
calibration::CalibrationConfig StudyCalibrationConfig(
    const std::string& directory, ModelKind model, const QuasiStaticSelection* quasi_static,
    double max_inertial_number = std::numeric_limits<double>::infinity());

// Fig. 5 for a fitted model (its [model] block, calibration::ModelTomlBlock):
// element tests along the paths A (ψ_ε = 45°), B (90°) and C (120°) from a
// normally and an overconsolidated (OCR 4) state at 100 kPa, as the
// programme's [[model_run]] of the clay model (A stops at 2000 kPa, C at
// 1 kPa), in FOLDER/paths/psi<ψ>_ocr<k>/ (test.toml, result.h5, result.csv,
// done.toml). A path that ends at a limit point or fails is left without
// done.toml and said on standard error; returns the number of finished paths.
int WriteModelPaths(const std::string& folder, const std::string& model_block);

// What `study calibrate` prints of one model and its status.
struct StudyModelCalibration {
  std::string text;  // the parameters, the number of warnings, the fit's time,
                     // the Fig. 5 paths; then a line with the status and reason
  calibration::FitOutcome outcome;
};

// Calibrates one model and writes its folder. Throws RuntimeError when no
// fit succeeded, and rethrows what stopped the calibration (an InputError
// for data no state of which passes the selections), in both cases after
// writing fit_status.toml as failed with the reason.
StudyModelCalibration CalibrateStudyModel(
    const std::string& directory, ModelKind model, const QuasiStaticSelection* quasi_static,
    double max_inertial_number = std::numeric_limits<double>::infinity());

}  // namespace granasym::analysis
