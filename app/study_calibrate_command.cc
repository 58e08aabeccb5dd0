// `granasym study calibrate DIR [--models hypoplastic_clay,modified_cam_clay,hypoplastic_sand]`:
// calibrates each model to the study's asymptotic states
// (analysis/study_calibration.h) and prints a line per model.
#include "app/study_calibrate_command.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/quasi_static_selection.h"
#include "analysis/rate_files.h"
#include "analysis/study_calibration.h"
#include "calibration/model_parameters.h"
#include "common/error.h"

namespace granasym {
namespace fs = std::filesystem;

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
    std::vector<ModelKind> kinds;
    for (const std::string& m : models) {
      const auto kind = FromString<ModelKind>(m);
      if (!kind) {
        throw InputError("--models: '" + m + "' is not valid: expected " +
                         AllowedNames<ModelKind>() + " (comma-separated)");
      }
      kinds.push_back(*kind);
    }
    if (!fs::exists(directory + "/asymptotic_states.h5")) {
      throw InputError(directory +
                       ": no asymptotic_states.h5 (run `granasym study run` or `granasym study "
                       "merge` first)");
    }
    // A rate study: the models are fitted to its quasi-static states only.
    std::optional<analysis::QuasiStaticSelection> quasi_static;
    if (const std::optional<analysis::RateStudy> rate = analysis::ReadRateStudy(directory)) {
      quasi_static = analysis::SelectQuasiStatic(
          *rate, inertial_number > 0 ? std::optional<double>(inertial_number) : std::nullopt);
      if (!quasi_static->valid()) {
        throw InputError(directory + ": a rate study, but " + quasi_static->reason +
                         (inertial_number > 0 ? "" : "; choose one with --inertial-number"));
      }
      analysis::WriteQuasiStaticSelection(directory, *quasi_static);
      std::printf(
          "rate study: fitting the %zu rate cases at I* = %g and the %zu drained cases at the "
          "slowest axial rates, E = %g MPa\n",
          quasi_static->cases.size(), quasi_static->inertial_number,
          quasi_static->drained_cases.size(), quasi_static->youngs_modulus_mpa);
    } else if (inertial_number > 0) {
      throw InputError("--inertial-number " + fmt::format("{:g}", inertial_number) + ": " +
                       directory + " is not a rate study (no rate_states.csv)");
    }
    const analysis::QuasiStaticSelection* selection = quasi_static ? &*quasi_static : nullptr;
    bool failed = false;
    for (ModelKind kind : kinds) {
      try {
        std::printf("%s\n", analysis::CalibrateStudyModel(directory, kind, selection).c_str());
      } catch (const std::exception& error) {
        std::printf("%s: FAILED: %s\n", calibration::ToString(kind), error.what());
        failed = true;
      }
      std::fflush(stdout);
    }
    if (failed) throw CLI::RuntimeError(3);
  });
}

}  // namespace granasym
