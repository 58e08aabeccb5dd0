#include "analysis/study_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/calibration_report.h"
#include "calibration/fit_status.h"
#include "calibration/model_parameters.h"
#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/text_file.h"
#include "constitutive/model_config.h"
#include "dem/run_record_names.h"
#include "study/study_folder.h"

namespace granasym::analysis {
namespace fs = std::filesystem;

CalibrationSelection SelectionOf(const QuasiStaticSelection* quasi_static,
                                 double max_inertial_number) {
  return quasi_static || std::isfinite(max_inertial_number) ? CalibrationSelection::kQuasiStatic
                                                            : CalibrationSelection::kAll;
}

namespace {

// What the file says of its data, above the keys.
std::string Header(const QuasiStaticSelection* quasi_static, double max_inertial_number) {
  std::string text =
      "# Written by `granasym study calibrate`; edit and rerun with\n"
      "#   granasym calibrate calibration.toml\n"
      "# (calibration/calibration_config.h documents every key).\n";
  if (quasi_static) {
    text += fmt::format(
        "# A rate study: only its quasi-static states (calibration/quasi_static.toml; `study "
        "calibrate --inertial-number` chooses I*): the rate cases at I* = {:g} and E = {:g} MPa "
        "(their psi_epsilon = 0 deg states also when drifting), the drained triaxial cases "
        "at the slowest axial rate of each sigma_r{}.\n",
        quasi_static->inertial_number, quasi_static->youngs_modulus_mpa,
        quasi_static->other_cases.empty()
            ? std::string()
            : fmt::format(" and {} other cases at I* or slower (other_cases)",
                          quasi_static->other_cases.size()));
  } else {
    text +=
        "# The study's detected states whose OCR refers to the study's NCL (other samples, "
        "e.g. phi = 0, stay out).\n";
    if (std::isfinite(max_inertial_number)) {
      text += fmt::format(
          "# A quasi-static selection (`study calibrate --select quasi_static`): only the "
          "states with I(d_max) below {:g} (max_inertial_number; rows without an inertial "
          "number are left out).\n",
          max_inertial_number);
    }
  }
  return text + "\n";
}

// A case's result, classified by its stages for a whole-path dataset.
struct CasePath {
  std::string name;  // the case
  std::vector<std::string> stages;
  calibration::PathKind kind = calibration::PathKind::kGeneral;
  bool overconsolidated = false;  // an isochoric path from an OC state (case name oc...)
  double start_p = 0.0;           // kPa, at the path's first row
};

// The case at `folder` (DIR/cases/r1/<case>) as a path of Fig. 9 (unload and
// reload stages at psi_epsilon = 180/0 deg), Fig. 11 (one stage at 90 deg)
// or Fig. 12 (one drained triaxial stage); nullopt for other cases.
std::optional<CasePath> ClassifyCase(const std::string& folder) {
  namespace record = dem::record;
  const std::string result = folder + "/result.h5";
  if (!fs::exists(result) || !fs::exists(folder + "/done.toml")) return std::nullopt;
  try {
    const Hdf5File file = Hdf5File::OpenRead(result);
    if (!file.Exists(record::kStages)) return std::nullopt;
    CasePath path;
    path.name = fs::path(folder).filename().string();
    int unload = 0, reload = 0, isochoric = 0, triaxial = 0, other = 0;
    int64_t first_row = -1;
    for (const std::string& stage : file.List(record::kStages)) {
      const std::string group = std::string(record::kStages) + "/" + stage;
      path.stages.push_back(file.ReadStringAttribute(group, record::kStageName));
      if (first_row < 0) first_row = file.ReadIntAttribute(group, record::kStageFirstRow);
      const std::string type = file.HasAttribute(group, record::kStageType)
                                   ? file.ReadStringAttribute(group, record::kStageType)
                                   : "";
      if (type == "triaxial") {
        ++triaxial;
      } else if (file.HasAttribute(group, record::kStagePsiEpsilonDeg)) {
        const double psi = file.ReadDoubleAttribute(group, record::kStagePsiEpsilonDeg);
        if (std::abs(psi - 180.0) < 0.5) {
          ++unload;
        } else if (std::abs(psi) < 0.5) {
          ++reload;
        } else if (std::abs(psi - 90.0) < 0.5) {
          ++isochoric;
        } else {
          ++other;
        }
      } else {
        ++other;
      }
    }
    const int stages = static_cast<int>(path.stages.size());
    if (unload > 0 && reload > 0 && unload + reload == stages) {
      path.kind = calibration::PathKind::kUnloadReload;
    } else if (stages == 1 && isochoric == 1) {
      path.kind = calibration::PathKind::kIsochoric;
      path.overconsolidated = path.name.rfind("oc", 0) == 0;
    } else if (stages == 1 && triaxial == 1) {
      path.kind = calibration::PathKind::kDrained;
    } else {
      return std::nullopt;
    }
    const std::vector<double> p =
        file.ReadDoubles(std::string(record::kSeries) + "/" + record::kColumnMeanStress);
    const size_t row = static_cast<size_t>(std::max<int64_t>(0, first_row));
    if (row >= p.size()) return std::nullopt;
    path.start_p = p[row];
    return path;
  } catch (const std::exception&) {
    return std::nullopt;  // not a readable result: no path from it
  }
}

// At most `count` of `paths`, spread over their starting p (one: the
// median; more: lowest to highest).
std::vector<CasePath> Spread(std::vector<CasePath> paths, size_t count) {
  std::sort(paths.begin(), paths.end(),
            [](const CasePath& a, const CasePath& b) { return a.start_p < b.start_p; });
  if (paths.size() <= count) return paths;
  std::vector<CasePath> chosen;
  for (size_t k = 0; k < count; ++k) {
    chosen.push_back(paths[count == 1 ? paths.size() / 2 : k * (paths.size() - 1) / (count - 1)]);
  }
  return chosen;
}

}  // namespace

std::vector<calibration::DatasetConfig> StudyPathDatasets(const std::string& directory,
                                                          std::vector<std::string>* notes) {
  std::vector<CasePath> cycles, oc_isochoric, nc_isochoric, drained;
  const fs::path replicate = fs::path(directory) / "cases" / "r1";
  for (const std::string& folder : study::CaseFolders(directory, false)) {
    if (fs::path(folder).parent_path() != replicate) continue;
    const std::optional<CasePath> path = ClassifyCase(folder);
    if (!path || path->start_p < kStudyPathMinStartKpa) continue;
    switch (path->kind) {
      case calibration::PathKind::kUnloadReload:
        cycles.push_back(*path);
        break;
      case calibration::PathKind::kIsochoric:
        (path->overconsolidated ? oc_isochoric : nc_isochoric).push_back(*path);
        break;
      default:
        drained.push_back(*path);
        break;
    }
  }
  std::vector<CasePath> chosen = Spread(cycles, kStudyPathsPerKind);
  for (const auto& group :
       {Spread(oc_isochoric, kStudyPathsPerKind), Spread(nc_isochoric, kStudyPathsPerKind),
        Spread(drained, kStudyPathsPerKind)}) {
    chosen.insert(chosen.end(), group.begin(), group.end());
  }
  std::vector<calibration::DatasetConfig> datasets;
  for (const CasePath& path : chosen) {
    calibration::DatasetConfig d;
    d.name = path.name + " path";
    d.is_path = true;
    d.study_path = fs::path(directory).lexically_normal().string();
    d.path_case = path.name;
    d.path_replicate = 1;
    d.paths = {calibration::StudyCaseResult(d.study_path, 1, path.name)};
    d.path = d.paths.front();
    d.path_read.stages = path.stages;
    d.path_read.kind = path.kind;
    d.path_read.points = kStudyPathPoints;
    // Fig. 12: σ_r held by the DEM, followed by the model.
    if (path.kind == calibration::PathKind::kDrained) {
      d.path_read.control = calibration::PathControl::kDrained;
    }
    try {
      calibration::ReadPathDem(d.path, d.name, d.path_read);
    } catch (const std::exception& error) {
      if (notes)
        notes->push_back(fmt::format("{}: not used as a path: {}", path.name, error.what()));
      continue;
    }
    datasets.push_back(d);
  }
  return datasets;
}

calibration::CalibrationConfig StudyCalibrationConfig(const std::string& directory, ModelKind model,
                                                      const QuasiStaticSelection* quasi_static,
                                                      double max_inertial_number) {
  calibration::CalibrationConfig config;
  // Each selection in its own folder (analysis/calibration_selections.h).
  // A rate study's quasi-static set is that study's default selection.
  const std::string relative =
      quasi_static ? "calibration/" + std::string(calibration::ToString(model))
                   : SelectionFolder(directory, calibration::ToString(model),
                                     SelectionOf(quasi_static, max_inertial_number));
  const std::string folder = (fs::path(directory) / relative).string();
  // The study folder from the calibration's: "../.." or "../../..".
  std::string up;
  const fs::path parts(relative);
  for (auto part = parts.begin(); part != parts.end(); ++part) up += up.empty() ? ".." : "/..";
  config.origin = folder + "/calibration.toml";
  config.model = model;
  // Paths as the file's reader resolves them (against the file's folder).
  const auto resolve = [&](const std::string& relative) {
    return (fs::path(config.origin).parent_path() / relative).lexically_normal().string();
  };
  const auto study_dataset = [&](const std::string& name) {
    calibration::DatasetConfig d;
    d.name = name;
    d.is_study = true;
    d.paths = {resolve(up)};
    d.path = d.paths.front();
    return d;
  };
  if (quasi_static) {
    // A rate study's quasi-static set: its ψ_ε = 0° states also when drifting
    // (the rate study's rule for the isotropic path) and its other states,
    // with the drained cases, when detected. The case names select them, so
    // no NCL reference does (a short NCL stage may leave the rate states' NCL
    // undetermined).
    calibration::DatasetConfig ncl = study_dataset("quasi_static_ncl");
    using study::TableKind;
    using study::TableStatus;
    ncl.study.kinds = {ToString(TableKind::kNcl)};
    ncl.study.statuses = {ToString(TableStatus::kDetected), ToString(TableStatus::kDrifting)};
    ncl.study.cases = quasi_static->cases;  // with the other cases (e.g. the study's NCL)
    ncl.study.cases.insert(ncl.study.cases.end(), quasi_static->other_cases.begin(),
                           quasi_static->other_cases.end());
    calibration::DatasetConfig other = study_dataset("quasi_static");
    other.study.kinds = {ToString(TableKind::kCsl), ToString(TableKind::kCompression),
                         ToString(TableKind::kExtension), ToString(TableKind::kTriaxial)};
    other.study.statuses = {ToString(TableStatus::kDetected)};
    other.study.cases = quasi_static->AllCases();
    config.datasets = {ncl, other};
  } else {
    calibration::DatasetConfig d = study_dataset("study");
    const std::string ncl = study::StudyNclCase(directory).value_or("");
    if (!ncl.empty()) d.study.ncl_references = {ncl};
    d.study.max_inertial_number = max_inertial_number;
    config.datasets = {d};
    // The DEM's own whole paths (issue 36 §3): cycles, isochoric, drained;
    // not at the tiny scale, whose 800-sphere paths check the machinery, not
    // the physics (their misfit is noise), and whose fits with paths,
    // profiles and Pareto fronts took over ten minutes for the sand model.
    const std::string study_toml = directory + "/study.toml";
    const bool tiny = fs::exists(study_toml) &&
                      ConfigTable::ParseFile(study_toml).GetString("scale", "") == "tiny";
    for (calibration::DatasetConfig& path :
         tiny ? std::vector<calibration::DatasetConfig>{} : StudyPathDatasets(directory, nullptr)) {
      path.study_path = resolve(up);
      path.paths = {calibration::StudyCaseResult(path.study_path, 1, path.path_case)};
      path.path = path.paths.front();
      config.datasets.push_back(path);
    }
  }
  // A rate study's quasi-static states lie on nearly flat lines (frictional
  // spheres do not crush) where a local fit from the starting values can
  // leave the models' domain: the global NLopt search as well, the better fit used.
  config.method = quasi_static ? calibration::FitMethod::kBoth : calibration::FitMethod::kCeres;
  config.fix_undetermined = true;
  config.nlopt.uncertainty = config.ceres.uncertainty;
  config.nlopt.ceres = config.ceres;
  config.hdf5_path = resolve("calibration.h5");
  config.summary_path = resolve("summary.txt");
  config.plot_data_dir = resolve("plot_data");
  config.status_path = resolve(calibration::kFitStatusFile);
  return config;
}

int WriteModelPaths(const std::string& folder, const std::string& model_block) {
  int finished = 0;
  for (int psi : {45, 90, 120}) {
    for (int ocr : {1, 4}) {
      const std::string dir = fmt::format("{}/paths/psi{}_ocr{}", folder, psi, ocr);
      fs::create_directories(dir);
      fs::remove(dir + "/done.toml");
      // 200 points over the path: a stiff model reaches its stop within a
      // small part of the first run's duration, which is then run again
      // over the duration it took (the stop still ends it).
      auto text_for = [&](double duration_s) {
        return model_block +
               fmt::format(
                   "\n[initial]\nmean_stress_kpa = 100.0\npsi_sigma_deg = 0.0\nocr = {}.0\n\n"
                   "[[stage]]\nname = \"path\"\ntype = \"proportional\"\npsi_epsilon_deg = {}.0\n"
                   "stretching_rate = 1.0\nduration_s = {:.9g}\noutput_points = 200\n"
                   "[stage.stop]\nasymptote = 1e-7\n{}",
                   ocr, psi, duration_s,
                   psi < 90   ? "mean_stress_kpa = 2000.0\n"
                   : psi > 90 ? "mean_stress_kpa = 1.0\n"
                              : "");
      };
      const std::string input = dir + "/test.toml";
      try {
        std::string text = text_for(1.0);
        WriteTextFileAtomically(input, text);
        ElementTestResult result = RunElementTestInput(ConfigTable::ParseString(text, input), input,
                                                       dir + "/result.h5", dir + "/result.csv");
        if (result.summary.success() && result.history.size() < 100 &&
            result.history.back().time > 0) {
          text = text_for(1.02 * result.history.back().time);
          WriteTextFileAtomically(input, text);
          result = RunElementTestInput(ConfigTable::ParseString(text, input), input,
                                       dir + "/result.h5", dir + "/result.csv");
        }
        if (!result.summary.success()) {
          std::fprintf(stderr, "%s: %s\n", input.c_str(), result.summary.Report().c_str());
          continue;
        }
        WriteTextFileAtomically(dir + "/done.toml", "termination = \"completed\"\n");
        ++finished;
      } catch (const std::exception& error) {
        std::fprintf(stderr, "%s: %s\n", input.c_str(), error.what());
      }
    }
  }
  return finished;
}

StudyModelCalibration CalibrateStudyModel(const std::string& directory, ModelKind model,
                                          const QuasiStaticSelection* quasi_static,
                                          double max_inertial_number) {
  const calibration::CalibrationConfig config =
      StudyCalibrationConfig(directory, model, quasi_static, max_inertial_number);
  const std::string name = calibration::ToString(model);
  const std::string folder = fs::path(config.origin).parent_path().string();
  fs::create_directories(folder);
  {
    std::istringstream header(Header(quasi_static, max_inertial_number));
    std::string description;
    for (std::string line; std::getline(header, line);) {
      if (line.rfind("# ", 0) == 0 && line.find("granasym") == std::string::npos &&
          line.find("calibration_config.h") == std::string::npos) {
        description += (description.empty() ? "" : " ") + line.substr(2);
      }
    }
    WriteTextFileAtomically(
        folder + "/selection.toml",
        SelectionToml(SelectionOf(quasi_static, max_inertial_number), description));
  }
  WriteTextFileAtomically(config.origin, calibration::CalibrationConfigText(
                                             config, Header(quasi_static, max_inertial_number)));
  // A failed calibration leaves no parameters of an earlier one behind.
  const auto failed = [&](const std::string& reason) {
    for (const char* stale : {"parameters.csv", "model.toml"}) fs::remove(folder + "/" + stale);
    fs::remove_all(config.plot_data_dir);
    WriteTextFileAtomically(config.status_path,
                            calibration::FitStatusToml({calibration::FitStatus::kFailed, reason}));
  };
  calibration::CalibrationRun run;
  try {
    run = calibration::RunCalibration(config);
  } catch (const std::exception& error) {
    failed(std::string("the calibration could not be run: ") + error.what());
    throw;
  }
  calibration::WriteCalibrationHdf5(run, config.hdf5_path);
  // The selection, after the status and reason lines: which data, and which
  // selection a paper uses.
  const CalibrationSelection selection = SelectionOf(quasi_static, max_inertial_number);
  const std::string selection_line = fmt::format(
      "selection: {} ({}; `study calibrate --select {}`, in {}). {}", SelectionName(selection),
      SelectionTitle(directory, selection), SelectionName(selection),
      SelectionFolder(directory, name, selection), SelectionAdvice(directory));
  std::string summary = calibration::SummaryText(run);
  size_t after = 0;
  for (int line = 0; line < 3 && after != std::string::npos; ++line) {
    after = summary.find('\n', after);
    if (after != std::string::npos) ++after;
  }
  summary.insert(after == std::string::npos ? summary.size() : after, selection_line + "\n");
  WriteTextFileAtomically(config.summary_path, summary);
  const std::string warnings = calibration::WarningsText(run);
  WriteTextFileAtomically(folder + "/warnings.txt", warnings);
  const calibration::FitResult* kept = run.kept_fit();
  if (!kept || !kept->summary.success()) {
    failed(run.outcome.reason);
    throw RuntimeError(fmt::format("{}: the fit failed: {} (see {})", name,
                                   kept ? kept->summary.Report() : "no fit", config.summary_path));
  }
  WriteTextFileAtomically(config.status_path, calibration::FitStatusToml(run.outcome));
  const calibration::FitResult& fit = *kept;
  WriteTextFileAtomically(folder + "/parameters.csv", calibration::ParametersCsv(run, fit));
  WriteTextFileAtomically(folder + "/model.toml", calibration::ModelToml(run, fit));
  calibration::WritePlotData(run, fit, config.plot_data_dir);
  const int paths = WriteModelPaths(
      folder, calibration::ModelTomlBlock(run.problem->parameters().kind(), fit.values));
  int count = 0;
  for (char c : warnings) count += c == '\n' ? 1 : 0;
  std::string line = name + ":";
  const auto& specs = run.problem->parameters().specs();
  for (size_t i = 0; i < specs.size(); ++i) {
    line += fmt::format(" {}={:.4g}{}", specs[i].name, fit.values[i],
                        run.status[i] == calibration::ParameterStatus::kFitted
                            ? std::string()
                            : "(" + std::string(calibration::ToString(run.status[i])) + ")");
  }
  line += fmt::format("; {} warnings; fit {:.2f} s; {} of 6 Fig. 5 paths; {}", count,
                      fit.summary.wall_seconds, paths, folder);
  line += fmt::format("\n  status: {}: {}", calibration::ToString(run.outcome.status),
                      run.outcome.reason);
  return {line, run.outcome};
}

}  // namespace granasym::analysis
