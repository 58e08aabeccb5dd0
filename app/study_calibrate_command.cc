// `granasym study calibrate DIR [--models hypoplastic_clay,modified_cam_clay,hypoplastic_sand]
// [--select all|quasi_static] [--inertial-number I*] [--max-inertial-number I]`:
// calibrates each model to the study's asymptotic states
// (analysis/study_calibration.h), draws its profile and Pareto figures
// (app/figure_drawing.h), prints a line per model with its status
// and exits with the worst status (calibration/fit_status.h).
#include "app/study_calibrate_command.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/calibration_selections.h"
#include "analysis/quasi_static_selection.h"
#include "analysis/rate_cases.h"
#include "analysis/rate_files.h"
#include "analysis/study_calibration.h"
#include "app/figure_drawing.h"
#include "calibration/fit_status.h"
#include "calibration/model_parameters.h"
#include "common/error.h"

namespace granasym {
namespace fs = std::filesystem;

void RegisterStudyCalibrateCommand(CLI::App* study) {
  static std::string directory;
  static std::vector<std::string> models = {"hypoplastic_clay", "modified_cam_clay",
                                            "hypoplastic_sand"};
  static std::string select;
  static double inertial_number = 0;
  static double max_inertial_number = 0;
  CLI::App* calibrate = study->add_subcommand(
      "calibrate",
      "fit the constitutive models to the study's asymptotic states; writes "
      "DIR/calibration/<model>/ for the study's default selection (quasi_static for a rate study, "
      "all otherwise), DIR/calibration/<selection>/<model>/ for the other (calibration.toml, "
      "calibration.h5, summary.txt, parameters.csv, warnings.txt, model.toml, fit_status.toml, "
      "selection.toml, plot_data/ with profiles.png and pareto.png), and "
      "DIR/calibration/parameters_by_selection.csv when a model has both; "
      "exits 0 when every model "
      "converged, else with the worst model's status (3 failed, 5 at_bound, 6 "
      "converged_inadmissible, 7 no_convergence)");
  calibrate->add_option("dir", directory, "study folder (with asymptotic_states.h5)")
      ->required()
      ->check(CLI::ExistingDirectory);
  calibrate
      ->add_option("--models", models,
                   "comma-separated: hypoplastic_clay, modified_cam_clay, hypoplastic_sand "
                   "(default all three)")
      ->delimiter(',');
  calibrate
      ->add_option("--select", select,
                   "all: every detected state; quasi_static: a rate study's quasi-static set, "
                   "else the states with I(d_max) below --max-inertial-number (default: "
                   "quasi_static for a rate study, all otherwise)")
      ->check(CLI::IsMember({"all", "quasi_static"}));
  static CLI::Option* inertial_number_option = nullptr;
  static CLI::Option* max_inertial_number_option = nullptr;
  inertial_number_option = calibrate->add_option(
      "--inertial-number", inertial_number,
      "a rate study (with rate_states.csv), --select quasi_static: fit the rate cases at this I* "
      "only (default: the smallest I* with usable psi_epsilon = 90 deg states from two starts)");
  max_inertial_number_option = calibrate->add_option(
      "--max-inertial-number", max_inertial_number,
      fmt::format("a study without rate cases, --select quasi_static: fit the states with "
                  "I(d_max) below this (default {:g})",
                  analysis::kQuasiStaticInertialNumber));
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
    // An inertial number given is a positive, finite number (0, a negative
    // value or NaN would select nothing, or everything, silently).
    for (const auto& [option, value] :
         {std::make_pair(inertial_number_option, inertial_number),
          std::make_pair(max_inertial_number_option, max_inertial_number)}) {
      if (option->count() > 0 && !(std::isfinite(value) && value > 0)) {
        throw InputError(fmt::format(
            "{} {}: expected a positive inertial number (e.g. 1e-3): it selects the states the "
            "models are fitted to",
            option->get_name(), option->as<std::string>()));
      }
    }
    const std::optional<analysis::RateStudy> rate = analysis::ReadRateStudy(directory);
    const bool quasi_static_set = select.empty() ? rate.has_value() : select == "quasi_static";
    if (inertial_number > 0 && !(rate && quasi_static_set)) {
      throw InputError(
          "--inertial-number " + fmt::format("{:g}", inertial_number) + ": " +
          (rate ? "only with --select quasi_static"
                : directory +
                      " is not a rate study (no rate_states.csv): --inertial-number selects a "
                      "rate study's quasi-static rate cases; here the states are selected by "
                      "--select quasi_static and --max-inertial-number (I(d_max) below it, "
                      "default " +
                      fmt::format("{:g}", analysis::kQuasiStaticInertialNumber) + ")"));
    }
    if (max_inertial_number > 0 && !(quasi_static_set && !rate)) {
      throw InputError("--max-inertial-number " + fmt::format("{:g}", max_inertial_number) + ": " +
                       (rate ? directory + " is a rate study: its quasi-static set is chosen by "
                                           "--inertial-number"
                             : std::string("only with --select quasi_static")));
    }
    // A rate study: the models are fitted to its quasi-static states only.
    std::optional<analysis::QuasiStaticSelection> quasi_static;
    double bound = std::numeric_limits<double>::infinity();
    if (rate && quasi_static_set) {
      quasi_static = analysis::SelectQuasiStatic(
          *rate, inertial_number > 0 ? std::optional<double>(inertial_number) : std::nullopt);
      if (!quasi_static->valid()) {
        throw InputError(directory + ": a rate study, but " + quasi_static->reason +
                         (inertial_number > 0 ? "" : "; choose one with --inertial-number"));
      }
      quasi_static->other_cases = analysis::QuasiStaticCompanions(
          directory, analysis::ReadStateTable(directory), *rate, *quasi_static);
      analysis::WriteQuasiStaticSelection(directory, *quasi_static);
      std::string others;
      for (const std::string& name : quasi_static->other_cases) {
        others += (others.empty() ? "" : ", ") + name;
      }
      std::printf(
          "rate study: fitting the %zu rate cases at I* = %g and the %zu drained cases at the "
          "slowest axial rates, E = %g MPa%s\n",
          quasi_static->cases.size(), quasi_static->inertial_number,
          quasi_static->drained_cases.size(), quasi_static->youngs_modulus_mpa,
          others.empty() ? ""
                         : fmt::format(", and {} other cases at I* or slower ({})",
                                       quasi_static->other_cases.size(), others)
                               .c_str());
    } else {
      // Not a rate study: no quasi-static set of one (a rate study's --select
      // all leaves its quasi-static calibrations, and their record, in place).
      if (!rate) fs::remove(fs::path(directory) / analysis::kQuasiStaticSelectionFile);
      if (quasi_static_set) {
        bound =
            max_inertial_number > 0 ? max_inertial_number : analysis::kQuasiStaticInertialNumber;
        std::printf("quasi-static selection: fitting the states with I(d_max) below %g\n", bound);
      }
    }
    const analysis::QuasiStaticSelection* selection = quasi_static ? &*quasi_static : nullptr;
    // The worst status among the models decides the exit status.
    calibration::FitStatus worst = calibration::FitStatus::kConverged;
    std::string statuses;
    for (ModelKind kind : kinds) {
      calibration::FitStatus status = calibration::FitStatus::kFailed;
      try {
        const analysis::StudyModelCalibration done =
            analysis::CalibrateStudyModel(directory, kind, selection, bound);
        std::printf("%s\n", done.text.c_str());
        status = done.outcome.status;
        const std::string plot_data =
            (fs::path(directory) /
             analysis::SelectionFolder(directory, calibration::ToString(kind),
                                       analysis::SelectionOf(selection, bound)) /
             "plot_data")
                .string();
        for (const std::string& line : DrawCalibrationFigures(plot_data)) {
          std::printf("  figure: %s\n", line.c_str());
        }
      } catch (const FileError&) {
        throw;  // an output that cannot be written: status 1 (README), not a failed fit
      } catch (const fs::filesystem_error& error) {
        throw FileError(fmt::format("cannot write the calibration of {} in {}: {}",
                                    calibration::ToString(kind), directory, error.what()));
      } catch (const std::exception& error) {
        std::printf("%s: FAILED: %s\n  status: failed\n", calibration::ToString(kind),
                    error.what());
      }
      statuses += fmt::format("{}{} {}", statuses.empty() ? "" : ", ", calibration::ToString(kind),
                              calibration::ToString(status));
      worst = calibration::Worst(worst, status);
      std::fflush(stdout);
    }
    // Both selections side by side, where some model has both.
    const std::string by_selection = analysis::WriteParametersBySelection(
        directory, {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"});
    if (!by_selection.empty()) {
      std::printf("both selections side by side: %s\n", by_selection.c_str());
    }
    std::printf("%s\n", analysis::SelectionAdvice(directory).c_str());
    const int exit_status = calibration::ExitStatus(worst);
    std::printf("study calibrate: %s; exit status %d (%s)\n", statuses.c_str(), exit_status,
                worst == calibration::FitStatus::kConverged
                    ? "every model converged"
                    : fmt::format("the worst status, {}", calibration::ToString(worst)).c_str());
    if (exit_status != 0) throw CLI::RuntimeError(exit_status);
  });
}

}  // namespace granasym
