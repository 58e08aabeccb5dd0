#include "analysis/study_calibration.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/calibration_report.h"
#include "calibration/fit_status.h"
#include "calibration/model_parameters.h"
#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"
#include "constitutive/model_config.h"
#include "study/study_folder.h"

namespace granasym::analysis {
namespace fs = std::filesystem;
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
        "(their psi_epsilon = 0 deg states also when drifting), and the drained triaxial cases "
        "at the slowest axial rate of each sigma_r.\n",
        quasi_static->inertial_number, quasi_static->youngs_modulus_mpa);
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

}  // namespace

calibration::CalibrationConfig StudyCalibrationConfig(const std::string& directory, ModelKind model,
                                                      const QuasiStaticSelection* quasi_static,
                                                      double max_inertial_number) {
  calibration::CalibrationConfig config;
  const std::string folder =
      (fs::path(directory) / "calibration" / calibration::ToString(model)).string();
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
    d.paths = {resolve("../..")};
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
    ncl.study.cases = quasi_static->cases;
    calibration::DatasetConfig other = study_dataset("quasi_static");
    other.study.kinds = {ToString(TableKind::kCsl), ToString(TableKind::kCompression),
                         ToString(TableKind::kExtension), ToString(TableKind::kTriaxial)};
    other.study.statuses = {ToString(TableStatus::kDetected)};
    other.study.cases = quasi_static->cases;
    other.study.cases.insert(other.study.cases.end(), quasi_static->drained_cases.begin(),
                             quasi_static->drained_cases.end());
    config.datasets = {ncl, other};
  } else {
    calibration::DatasetConfig d = study_dataset("study");
    const std::string ncl = study::StudyNclCase(directory).value_or("");
    if (!ncl.empty()) d.study.ncl_references = {ncl};
    d.study.max_inertial_number = max_inertial_number;
    config.datasets = {d};
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
  WriteTextFileAtomically(config.summary_path, calibration::SummaryText(run));
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
