// `granasym study calibrate DIR [--models hypoplastic_clay,modified_cam_clay,hypoplastic_sand]`:
// writes a calibration file per model that reads the study's state table,
// runs it through the calibration library and writes the outputs whose names
// the figures and the report read (app/study_calibrate_command.h).
#include "app/study_calibrate_command.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"
#include "study/rate_study.h"
#ifdef GRANASYM_HAVE_CALIBRATION
#include "calibration/calibration_config.h"
#include "calibration/calibration_report.h"
#include "calibration/model_parameters.h"
#include "constitutive/model_config.h"
#endif

namespace granasym {

namespace {

namespace fs = std::filesystem;

#ifdef GRANASYM_HAVE_CALIBRATION

// The generated input: the study's table two folders up, the default
// selections spelled out so that a user sees (and can edit) them. A rate
// study's quasi-static set is two datasets: its ψ_ε = 0° states also when
// drifting (the rate study's rule for the isotropic path, study/rate_study.h)
// and its other states, with the drained cases, when detected; the case
// names select them, so no NCL reference does (the rate states' OCR refers
// to NCLs that a short NCL stage may leave undetermined).
std::string CalibrationToml(const std::string& directory, const std::string& model,
                            const study::QuasiStaticSelection* quasi_static) {
  std::string s = fmt::format(
      "# Written by `granasym study calibrate`; edit and rerun with\n"
      "#   granasym calibrate calibration.toml\n"
      "# (calibration/calibration_config.h documents every key).\n"
      "[model]\nkind = \"{}\"\n\n",
      model);
  const std::string common =
      "study = \"../..\"\nexclude_flags = [\"overlap_above_10pct\", \"gas\"]\n"
      "psi_sigma_uncertainty_deg = 0.5\nln_1_plus_e_uncertainty = 0.002\n";
  auto names = [](const std::vector<std::string>& cases) {
    std::string list;
    for (const std::string& c : cases) list += (list.empty() ? "" : ", ") + TomlQuoted(c);
    return "[" + list + "]";
  };
  if (quasi_static) {
    std::vector<std::string> all = quasi_static->cases;
    all.insert(all.end(), quasi_static->drained_cases.begin(), quasi_static->drained_cases.end());
    s += fmt::format(
        "# a rate study: only its quasi-static states (calibration/quasi_static.toml; `study "
        "calibrate --inertial-number` chooses I*): the rate cases at I* = {:g} and E = {:g} MPa, "
        "and the drained triaxial cases at the slowest axial rate of each sigma_r\n"
        "[[dataset]]\nname = \"quasi_static_ncl\"\n{}kinds = [\"ncl\"]\n"
        "statuses = [\"detected\", \"drifting\"]  # the isotropic path: drifting too\n"
        "cases = {}\n\n"
        "[[dataset]]\nname = \"quasi_static\"\n{}"
        "kinds = [\"csl\", \"compression\", \"extension\", \"triaxial\"]\n"
        "statuses = [\"detected\"]\ncases = {}\n",
        quasi_static->inertial_number, quasi_static->youngs_modulus_mpa, common,
        names(quasi_static->cases), common, names(all));
  } else {
    std::string ncl;
    const std::string study_file = directory + "/study.toml";
    if (fs::exists(study_file)) ncl = ConfigTable::ParseFile(study_file).GetString("ncl", "");
    s += "[[dataset]]\nname = \"study\"\n" + common +
         "kinds = [\"ncl\", \"csl\", \"compression\", \"extension\", \"triaxial\"]\n"
         "statuses = [\"detected\"]  # add \"drifting\" for more NCL states\n";
    if (!ncl.empty()) {
      s += fmt::format(
          "# only states whose OCR refers to the study's NCL (other samples, e.g. phi = 0, stay "
          "out)\nncl_references = [{}]\n",
          TomlQuoted(ncl));
    }
  }
  // A rate study's quasi-static states lie on nearly flat lines (frictional
  // spheres do not crush) where a local fit from the starting values can
  // leave the models' domain: the global NLopt search as well, the better fit used.
  s += fmt::format("\n[fitter]\nmethod = \"{}\"\nfix_undetermined = true\n\n",
                   quasi_static ? "both" : "ceres");
  s += "[output]\nhdf5 = \"calibration.h5\"\nsummary = \"summary.txt\"\nplot_data = \"plot_data\"\n";
  return s;
}

// Fig. 5 for a fitted model: element tests along the paths A (ψ_ε = 45°),
// B (90°) and C (120°) from a normally and an overconsolidated (OCR 4) state
// at 100 kPa, as the programme's [[model_run]] of the clay model (A stops at
// 2000 kPa, C at 1 kPa), in FOLDER/paths/psi<ψ>_ocr<k>/ (test.toml,
// result.h5, result.csv, done.toml).
// A path that ends at a limit point or fails is left without done.toml and
// said on standard error; returns the number of finished paths.
int WriteModelPaths(const std::string& folder, const std::string& model_block) {
  int finished = 0;
  for (int psi : {45, 90, 120}) {
    for (int ocr : {1, 4}) {
      const std::string dir = fmt::format("{}/paths/psi{}_ocr{}", folder, psi, ocr);
      fs::create_directories(dir);
      fs::remove(dir + "/done.toml");
      const std::string text = model_block + fmt::format(
          "\n[initial]\nmean_stress_kpa = 100.0\npsi_sigma_deg = 0.0\nocr = {}.0\n\n"
          "[[stage]]\nname = \"path\"\ntype = \"proportional\"\npsi_epsilon_deg = {}.0\n"
          "stretching_rate = 1.0\nduration_s = 1.0\noutput_points = 200\n[stage.stop]\n"
          "asymptote = 1e-7\n{}",
          ocr, psi,
          psi < 90 ? "mean_stress_kpa = 2000.0\n" : psi > 90 ? "mean_stress_kpa = 1.0\n" : "");
      const std::string input = dir + "/test.toml";
      WriteTextFileAtomically(input, text);
      try {
        const ConfigTable root = ConfigTable::ParseString(text, input);
        const ElementTestResult result =
            RunElementTestInput(root, input, dir + "/result.h5", dir + "/result.csv");
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

// One model: writes its folder and returns the line to print.
std::string CalibrateOne(const std::string& directory, ModelKind model,
                         const study::QuasiStaticSelection* quasi_static) {
  const std::string name = calibration::ToString(model);
  const std::string folder = (fs::path(directory) / "calibration" / name).string();
  fs::create_directories(folder);
  const std::string config_path = folder + "/calibration.toml";
  WriteTextFileAtomically(config_path, CalibrationToml(directory, name, quasi_static));
  const calibration::CalibrationConfig config =
      calibration::ReadCalibrationConfigFile(config_path);
  const calibration::CalibrationRun run = calibration::RunCalibration(config);
  calibration::WriteCalibrationHdf5(run, config.hdf5_path);
  WriteTextFileAtomically(config.summary_path, calibration::SummaryText(run));
  const std::string warnings = calibration::WarningsText(run);
  WriteTextFileAtomically(folder + "/warnings.txt", warnings);
  // The successful fit of lowest cost (a rate study runs Ceres and NLopt:
  // CalibrationToml).
  const calibration::FitResult* best = nullptr;
  for (const calibration::FitResult& f : run.fits) {
    if (f.summary.success() && (!best || f.summary.final_cost < best->summary.final_cost)) best = &f;
  }
  if (!best) {
    throw RuntimeError(fmt::format("{}: the fit failed: {} (see {})", name,
                                   run.fits.empty() ? "no fit" : run.fits.front().summary.Report(),
                                   config.summary_path));
  }
  const calibration::FitResult& fit = *best;
  WriteTextFileAtomically(folder + "/parameters.csv", calibration::ParametersCsv(run, fit));
  WriteTextFileAtomically(folder + "/model.toml", calibration::ModelToml(run, fit));
  calibration::WritePlotData(run, fit, config.plot_data_dir);
  const int paths = WriteModelPaths(folder, calibration::ModelTomlBlock(
                                                run.problem->parameters().kind(), fit.values));
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
  return line;
}

#endif

}  // namespace

void RegisterStudyCalibrateCommand(CLI::App* study) {
  static std::string directory;
  static std::vector<std::string> models = {"hypoplastic_clay", "modified_cam_clay",
                                            "hypoplastic_sand"};
  static double inertial_number = 0;
  CLI::App* calibrate = study->add_subcommand(
      "calibrate",
      "fit the constitutive models to the study's asymptotic states; writes "
      "DIR/calibration/<model>/ (calibration.toml, calibration.h5, summary.txt, parameters.csv, "
      "warnings.txt, model.toml, plot_data/)");
  calibrate->add_option("dir", directory, "study folder (with asymptotic_states.h5)")
      ->required()
      ->check(CLI::ExistingDirectory);
  calibrate
      ->add_option("--models", models,
                   "comma-separated: hypoplastic_clay, modified_cam_clay, hypoplastic_sand "
                   "(default all three)")
      ->delimiter(',');
  calibrate->add_option(
      "--inertial-number", inertial_number,
      "a rate study (with rate_states.csv): fit the rate cases at this I* only (default: the "
      "smallest I* with usable psi_epsilon = 90 deg states from two starts)");
  calibrate->callback([] {
#ifdef GRANASYM_HAVE_CALIBRATION
    std::vector<ModelKind> kinds;
    for (const std::string& m : models) {
      const auto kind = calibration::FromString<ModelKind>(m);
      if (!kind || !calibration::IsCalibrated(*kind)) {
        throw InputError("--models: '" + m +
                         "' is not valid: expected hypoplastic_clay, modified_cam_clay, "
                         "hypoplastic_sand (comma-separated)");
      }
      kinds.push_back(*kind);
    }
    if (!fs::exists(directory + "/asymptotic_states.h5")) {
      throw InputError(directory +
                       ": no asymptotic_states.h5 (run `granasym study run` or `granasym study "
                       "merge` first)");
    }
    // A rate study: the models are fitted to its quasi-static states only.
    std::optional<study::QuasiStaticSelection> quasi_static;
    if (const std::optional<study::RateStudy> rate = study::ReadRateStudy(directory)) {
      quasi_static = study::SelectQuasiStatic(
          *rate, inertial_number > 0 ? std::optional<double>(inertial_number) : std::nullopt);
      if (!quasi_static->valid()) {
        throw InputError(directory + ": a rate study, but " + quasi_static->reason +
                         (inertial_number > 0 ? "" : "; choose one with --inertial-number"));
      }
      study::WriteQuasiStaticSelection(directory, *quasi_static);
      std::printf(
          "rate study: fitting the %zu rate cases at I* = %g and the %zu drained cases at the "
          "slowest axial rates, E = %g MPa\n",
          quasi_static->cases.size(), quasi_static->inertial_number,
          quasi_static->drained_cases.size(), quasi_static->youngs_modulus_mpa);
    } else if (inertial_number > 0) {
      throw InputError("--inertial-number " + fmt::format("{:g}", inertial_number) + ": " +
                       directory + " is not a rate study (no rate_states.csv)");
    }
    const study::QuasiStaticSelection* selection = quasi_static ? &*quasi_static : nullptr;
    bool failed = false;
    for (ModelKind kind : kinds) {
      try {
        std::printf("%s\n", CalibrateOne(directory, kind, selection).c_str());
      } catch (const std::exception& error) {
        std::printf("%s: FAILED: %s\n", calibration::ToString(kind), error.what());
        failed = true;
      }
      std::fflush(stdout);
    }
    if (failed) throw CLI::RuntimeError(3);
#else
    throw RuntimeError("this granasym was built without the calibration library");
#endif
  });
}

}  // namespace granasym
