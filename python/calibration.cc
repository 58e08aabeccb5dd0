// Calibration from Python data: a DataFrame of asymptotic states (the
// columns of calibration/csv_state_reader.h) and the calibration file's other
// tables as dicts. The states are written to a CSV file and the tables to
// the calibration file's TOML text, read by ReadCalibrationConfig (its checks
// and messages); the C++ reads datasets from files only (paths: dem_path and
// study_path datasets of DEM results). Then RunCalibration, and the files
// that `study calibrate` writes when an output folder is given.
#include <fmt/format.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/calibration_selections.h"
#include "calibration/calibration_config.h"
#include "calibration/calibration_report.h"
#include "calibration/fit_status.h"
#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/text_file.h"
#include "python/bindings.h"
#include "python/calibration_result.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace granasym::python {

CalibrationResult ReadCalibrationFolder(const std::string& folder) {
  CalibrationResult result;
  result.folder = folder;
  const std::string status = folder + "/" + calibration::kFitStatusFile;
  if (!fs::exists(status)) {
    throw InputError(folder + ": no " + calibration::kFitStatusFile +
                     ": not the folder of a calibration (DIR/calibration/<model>/ of `granasym "
                     "study calibrate`)");
  }
  result.outcome = calibration::ReadFitStatusToml(status);
  if (fs::exists(folder + "/calibration.h5")) {
    const Hdf5File file = Hdf5File::OpenRead(folder + "/calibration.h5");
    result.model = file.ReadStringAttribute("/calibration", "model");
  }
  if (fs::exists(folder + "/parameters.csv")) {
    result.parameters_csv = ReadTextFile(folder + "/parameters.csv");
  }
  if (fs::exists(folder + "/warnings.txt"))
    result.warnings = ReadTextFile(folder + "/warnings.txt");
  if (fs::exists(folder + "/summary.txt")) result.summary = ReadTextFile(folder + "/summary.txt");
  if (fs::exists(folder + "/selection.toml")) {
    result.selection = ConfigTable::ParseFile(folder + "/selection.toml")
                           .GetChoice("selection", {"all", "quasi_static"}, "");
  }
  return result;
}

namespace {

// A folder of its own below the system's temporary folder.
std::string TemporaryFolder() {
  std::string pattern = (fs::temp_directory_path() / "granasym-calibrate-XXXXXX").string();
  if (!mkdtemp(pattern.data())) {
    throw RuntimeError("cannot create a temporary folder " + pattern + ": " + std::strerror(errno));
  }
  return pattern;
}

std::string Absolute(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

// The calibration file's text of the arguments of calibrate().
std::string CalibrationText(const std::string& model, const py::dict& model_options,
                            const py::dict& parameters, const std::string& states_csv,
                            const py::dict& states_options, const py::list& datasets,
                            const py::dict& fitter, const std::string& out) {
  std::string text =
      "[model]\nkind = " + TomlQuoted(model) + "\n" + TomlTable(model_options, "model");
  for (const auto& [name, choice] : parameters) {
    const std::string key = py::str(name).cast<std::string>();
    if (!py::isinstance<py::dict>(choice)) {
      throw InputError(
          fmt::format("parameters['{}'] = {}: expected a dict of free, value, lower and upper", key,
                      py::repr(choice).cast<std::string>()));
    }
    text += "\n[parameters." + TomlQuoted(key) + "]\n" +
            TomlTable(choice.cast<py::dict>(), "parameters." + key);
  }
  if (!states_csv.empty()) {
    text += "\n[[dataset]]\nname = \"states\"\ncsv = " + TomlQuoted(states_csv) + "\n" +
            TomlTable(states_options, "dataset");
  }
  int k = 0;
  for (const py::handle dataset : datasets) {
    if (!py::isinstance<py::dict>(dataset)) {
      throw InputError(fmt::format("datasets[{}]: expected a dict of a [[dataset]] table", k));
    }
    text += "\n[[dataset]]\n" + TomlTable(dataset.cast<py::dict>(), fmt::format("datasets[{}]", k));
    ++k;
  }
  text += "\n[fitter]\n" + TomlTable(fitter, "fitter");
  text += fmt::format("\n[output]\nhdf5 = {}\nsummary = {}\nplot_data = {}\nstatus = {}\n",
                      TomlQuoted(out + "/calibration.h5"), TomlQuoted(out + "/summary.txt"),
                      TomlQuoted(out + "/plot_data"),
                      TomlQuoted(out + "/" + calibration::kFitStatusFile));
  return text;
}

CalibrationResult Calibrate(const std::string& model, const py::object& states,
                            const py::dict& parameters, const py::dict& dataset,
                            const py::list& datasets, const py::dict& fitter,
                            const py::dict& model_options, const std::optional<std::string>& out,
                            bool raise_on_failure) {
  const bool keep = out.has_value();
  const std::string folder = keep ? Absolute(*out) : TemporaryFolder();
  fs::create_directories(folder);
  struct Cleanup {
    std::string folder;
    bool keep;
    ~Cleanup() {
      std::error_code ignored;
      if (!keep) fs::remove_all(folder, ignored);
    }
  } cleanup{folder, keep};
  std::string states_csv;
  if (!states.is_none()) {
    states_csv = folder + "/states.csv";
    states.attr("to_csv")(states_csv, py::arg("index") = false);
  }
  // Relative paths of the datasets are the caller's: against the working folder.
  const std::string origin = Absolute("calibration.toml");
  const std::string text = CalibrationText(model, model_options, parameters, states_csv, dataset,
                                           datasets, fitter, folder);
  if (keep) WriteTextFileAtomically(folder + "/calibration.toml", text);
  const calibration::CalibrationConfig config =
      calibration::ReadCalibrationConfig(ConfigTable::ParseString(text, origin));
  CalibrationResult result;
  result.model = calibration::ToString(config.model);
  calibration::CalibrationRun run;
  {
    py::gil_scoped_release release;
    run = calibration::RunCalibration(config);
  }
  result.outcome = run.outcome;
  result.summary = calibration::SummaryText(run);
  result.warnings = calibration::WarningsText(run);
  const calibration::FitResult* kept = run.kept_fit();
  if (kept && kept->summary.success()) {
    result.parameters_csv = calibration::ParametersCsv(run, *kept);
  }
  if (keep) {
    result.folder = folder;
    calibration::WriteCalibrationHdf5(run, config.hdf5_path);
    WriteTextFileAtomically(config.summary_path, result.summary);
    WriteTextFileAtomically(folder + "/warnings.txt", result.warnings);
    WriteTextFileAtomically(config.status_path, calibration::FitStatusToml(run.outcome));
    if (!result.parameters_csv.empty()) {
      WriteTextFileAtomically(folder + "/parameters.csv", result.parameters_csv);
      calibration::WritePlotData(run, *kept, config.plot_data_dir);
    } else {
      fs::remove(folder + "/parameters.csv");
    }
  }
  if (raise_on_failure && result.outcome.status == calibration::FitStatus::kFailed) {
    throw RuntimeError("the calibration failed: " + result.outcome.reason);
  }
  return result;
}

py::object Parameters(const CalibrationResult& r) {
  if (r.parameters_csv.empty()) return py::none();
  return DataFrameFromCsv(r.parameters_csv);
}

}  // namespace

void BindCalibration(py::module_& module) {
  py::class_<CalibrationResult>(
      module, "Calibration",
      "A calibration's outcome: its status and reason, the parameters with their standard "
      "errors and 95 % intervals, the warnings and the summary.")
      .def_readonly("model", &CalibrationResult::model, "the model kind")
      .def_property_readonly(
          "status",
          [](const CalibrationResult& r) { return calibration::ToString(r.outcome.status); },
          "converged, converged_inadmissible, at_bound, no_convergence or failed")
      .def_property_readonly(
          "reason", [](const CalibrationResult& r) { return r.outcome.reason; },
          "the status's reason, one sentence")
      .def_property_readonly(
          "converged",
          [](const CalibrationResult& r) {
            return r.outcome.status == calibration::FitStatus::kConverged;
          },
          "True only for the status converged")
      .def_property_readonly(
          "exit_status",
          [](const CalibrationResult& r) { return calibration::ExitStatus(r.outcome.status); },
          "the exit status `granasym calibrate` gives it (0 only when converged)")
      .def_property_readonly("parameters", &Parameters,
                             "parameters.csv as a DataFrame (parameter, value, std_error, "
                             "ci95_low, ci95_high, status, profile_low, profile_high, profile); "
                             "None after a failed fit")
      .def_property_readonly(
          "values",
          [](const CalibrationResult& r) -> py::object {
            if (r.parameters_csv.empty()) return py::none();
            const py::object frame = DataFrameFromCsv(r.parameters_csv);
            return py::dict(
                py::module_::import("builtins")
                    .attr("zip")(frame["parameter"], frame["value"].attr("astype")("float")));
          },
          "the fitted parameter vector as {name: value} (granasym.Model(model, values)); None "
          "after a failed fit")
      .def_property_readonly(
          "warnings",
          [](const CalibrationResult& r) {
            std::vector<std::string> lines;
            size_t start = 0;
            while (start < r.warnings.size()) {
              size_t end = r.warnings.find('\n', start);
              if (end == std::string::npos) end = r.warnings.size();
              if (end > start) lines.push_back(r.warnings.substr(start, end - start));
              start = end + 1;
            }
            return lines;
          },
          "the warnings, one 'code: message' each (warnings.txt)")
      .def_readonly("summary", &CalibrationResult::summary, "the readable summary (summary.txt)")
      .def_readonly("folder", &CalibrationResult::folder, "where its files are ('' when none)")
      .def_readonly("selection", &CalibrationResult::selection,
                    "the study calibration's selection, 'all' or 'quasi_static' "
                    "(selection.toml; '' when the folder has none)")
      .def("__repr__", [](const CalibrationResult& r) {
        return "<granasym.Calibration " + r.model + ": " + calibration::ToString(r.outcome.status) +
               ">";
      });

  module.def("read_calibration", &ReadCalibrationFolder, py::arg("folder"),
             "A calibration's folder (DIR/calibration/<model>/ of `granasym study calibrate`, or "
             "the `out` of calibrate()): status, reason, parameters, warnings and summary.");

  module.def(
      "read_study_calibrations",
      [](const std::string& directory) {
        if (!fs::is_directory(directory)) {
          throw InputError(directory + ": not a folder (a study folder of `granasym study run`)");
        }
        py::dict out;
        for (analysis::CalibrationSelection selection :
             {analysis::CalibrationSelection::kAll, analysis::CalibrationSelection::kQuasiStatic}) {
          py::dict models;
          for (const char* model : {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"}) {
            const std::string folder =
                (fs::path(directory) / analysis::SelectionFolder(directory, model, selection))
                    .string();
            if (fs::exists(folder + "/" + calibration::kFitStatusFile)) {
              models[model] = ReadCalibrationFolder(folder);
            }
          }
          if (!models.empty()) out[analysis::SelectionName(selection)] = models;
        }
        return out;
      },
      py::arg("directory"),
      "A study's calibrations by selection: {'all': {model: Calibration}, 'quasi_static': "
      "{...}}, each selection's folder as `study calibrate` writes it (DIR/calibration/<model>/ "
      "for the study's default selection, DIR/calibration/<selection>/<model>/ for the other); "
      "a selection without calibrations is absent.");

  module.def(
      "calibrate", &Calibrate, py::arg("model"), py::arg("states") = py::none(), py::kw_only(),
      py::arg("parameters") = py::dict(), py::arg("dataset") = py::dict(),
      py::arg("datasets") = py::list(), py::arg("fitter") = py::dict(),
      py::arg("model_options") = py::dict(), py::arg("out") = py::none(),
      py::arg("raise_on_failure") = true,
      R"(Fits a model (hypoplastic_clay, modified_cam_clay, hypoplastic_sand) to asymptotic states.

states: a DataFrame with the columns of a CSV dataset (p_kpa, e or ln_1_plus_e,
  psi_sigma_deg, psi_epsilon_deg; optional weight, psi_sigma_uncertainty_deg,
  ln_1_plus_e_uncertainty); it becomes a [[dataset]] with csv = its file.
dataset: that dataset's other keys (kind, weight, psi_sigma_uncertainty_deg, ...).
datasets: further [[dataset]] tables as dicts (study, dem, dem_path, study_path, ...;
  relative paths against the working folder).
parameters: {name: {free, value, lower, upper}}; fitter: the [fitter] keys
  (nlopt as a dict); model_options: other [model] keys (asymptotes).
out: a folder for the calibration file, the states and the files of `study
  calibrate` (read_calibration reads it); None: nothing is kept.
A failed fit raises granasym.RuntimeError (raise_on_failure=False: returned with
status failed); any other status is returned: check .converged and .status.)");
}

}  // namespace granasym::python
