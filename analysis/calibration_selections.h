// A study's calibrations by selection (issue 36 §2): `study calibrate`
// fits either every detected state (`--select all`: for a study at the
// paper's rate, the paper-rate states) or a quasi-static selection
// (`--select quasi_static`), and each keeps its own folder:
//   DIR/calibration/<model>/               the study's default selection:
//                                          quasi_static for a rate study,
//                                          all otherwise (unchanged, so the
//                                          figures' and the report's files
//                                          stay where they were)
//   DIR/calibration/<selection>/<model>/   the other one (quasi_static/ for
//                                          a paper-rate study, all/ for a
//                                          rate study)
//   DIR/calibration/<...>/selection.toml   which selection the folder holds
//                                          (selection = "all" or "quasi_static")
//   DIR/calibration/parameters_by_selection.csv   per model and parameter,
//                                          both selections side by side,
//                                          written when a model has both
// Reads only the folders' text files (parameters.csv, fit_status.toml),
// so the report and the figures need no calibration library.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace granasym::analysis {

enum class CalibrationSelection { kAll, kQuasiStatic };

// "all" or "quasi_static" (the flag's and the file's spelling).
const char* SelectionName(CalibrationSelection selection);
// The default selection of the study in `directory`: quasi_static for a
// rate study (with rate_states.csv or drained_states.csv), all otherwise.
CalibrationSelection DefaultSelection(const std::string& directory);
// The folder of `model`'s calibration with `selection`, relative to the
// study folder: calibration/<model> for the default selection, else
// calibration/<selection>/<model>.
std::string SelectionFolder(const std::string& directory, const std::string& model,
                            CalibrationSelection selection);
// What the selection fits, for a table's heading: "paper rate (all detected
// states)" or "quasi-static" ("all rates (--select all)" for a rate study).
std::string SelectionTitle(const std::string& directory, CalibrationSelection selection);
// Which selection a paper should use, and why (one sentence; the guide's
// docs/guide/calibration.md "Which one a paper should use").
std::string SelectionAdvice(const std::string& directory);
// selection.toml's text for a folder of `selection`.
std::string SelectionToml(CalibrationSelection selection, const std::string& description);

// A model's calibrated selections (those whose folder holds
// fit_status.toml), the default first.
struct SelectionCalibration {
  CalibrationSelection selection = CalibrationSelection::kAll;
  std::string folder;  // relative to the study
  bool is_default = true;
};
std::vector<SelectionCalibration> CalibratedSelections(const std::string& directory,
                                                       const std::string& model);

// One parameter of one selection's calibration, from its parameters.csv.
struct SelectionParameter {
  double value = 0.0;
  // The 95 % interval: the profile's where it crossed on both sides, else
  // the Jacobian's where reported, else none ("" source).
  std::optional<double> low, high;
  std::string interval;  // "profile", "jacobian" or ""
  std::string status;    // parameters.csv's status: fitted, fixed, at_bound, undetermined
  std::string profile;   // determined, flat or "" (not profiled)
  // "fitted", "undetermined (profile flat)", "undetermined (fixed at its
  // start value)", "at a bound", "fixed".
  std::string Verdict() const;
  // "24.3 [23.7, 24.8]" or "1.33" (no interval).
  std::string ValueText() const;
};

// Per model and parameter, both selections side by side.
struct SelectionComparisonRow {
  std::string model, parameter, units;
  std::optional<SelectionParameter> all, quasi_static;
};
struct SelectionComparison {
  std::vector<std::string> models;  // those with both selections calibrated
  std::vector<std::string> fit_status_all, fit_status_quasi_static;  // per model
  std::vector<SelectionComparisonRow> rows;
  bool empty() const { return rows.empty(); }
};
// The models of `models` calibrated with both selections (each with its
// parameters.csv); InputError naming the file for a malformed parameters.csv.
SelectionComparison CompareSelections(const std::string& directory,
                                      const std::vector<std::string>& models);
// parameters_by_selection.csv: model,parameter,units, then for all and
// quasi_static each: <s>_value,<s>_low,<s>_high,<s>_interval,<s>_status,
// <s>_profile,<s>_verdict, and fit_status_all, fit_status_quasi_static.
inline constexpr char kParametersBySelectionFile[] = "calibration/parameters_by_selection.csv";
std::string ParametersBySelectionCsv(const SelectionComparison& comparison);
// Writes DIR/calibration/parameters_by_selection.csv when some model has
// both selections (removes a stale one otherwise); returns its path or "".
std::string WriteParametersBySelection(const std::string& directory,
                                       const std::vector<std::string>& models);

}  // namespace granasym::analysis
