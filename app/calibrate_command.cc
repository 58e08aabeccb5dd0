// `granasym calibrate CONFIG.toml [--out FILE.h5] [--summary FILE.txt]
// [--plot-data DIR] [--status FILE.toml] [--quiet]`: parse, validate, call
// the calibration library, write the HDF5 record atomically, the readable
// summary, the status file and the plot data with the profile and Pareto
// figures (app/figure_drawing.h); exit with the fit's status
// (calibration/fit_status.h: 0 only when it converged).
#include "app/calibrate_command.h"

#include <cstdio>
#include <filesystem>
#include <string>

#include "app/figure_drawing.h"
#include "calibration/calibration_config.h"
#include "calibration/calibration_report.h"
#include "common/error.h"
#include "common/output_path.h"
#include "common/text_file.h"

namespace granasym {

namespace {

struct CalibrateFlags {
  std::string config, out, summary, plot_data, status;
  bool quiet = false;
};

void RunCalibrate(const CalibrateFlags& flags) {
  calibration::CalibrationConfig config = calibration::ReadCalibrationConfigFile(flags.config);
  if (!flags.out.empty()) config.hdf5_path = flags.out;
  if (!flags.summary.empty()) config.summary_path = flags.summary;
  if (!flags.plot_data.empty()) config.plot_data_dir = flags.plot_data;
  if (!flags.status.empty()) config.status_path = flags.status;
  std::vector<NamedPath> inputs = {{"the calibration file", flags.config}};
  for (const calibration::DatasetConfig& dataset : config.datasets) {
    for (const std::string& path : dataset.paths) {
      inputs.push_back({"the data file of [[dataset]] '" + dataset.name + "'", path});
    }
  }
  // The fitted model as `granasym model run` reads it, beside the record.
  const std::string model_toml =
      std::filesystem::path(config.hdf5_path).replace_extension("").string() + "_model.toml";
  CheckOutputs({{"the HDF5 record (--out / [output] hdf5)", config.hdf5_path},
                {"the fitted model (beside the HDF5 record)", model_toml},
                {"the summary (--summary / [output] summary)", config.summary_path},
                {"the status file (--status / [output] status)", config.status_path}},
               inputs);
  CheckOutputFolder(
      {"the plot data folder (--plot-data / [output] plot_data)", config.plot_data_dir}, inputs);
  const calibration::CalibrationRun run = calibration::RunCalibration(config);
  const std::string summary = calibration::SummaryText(run);
  calibration::WriteCalibrationHdf5(run, config.hdf5_path);
  WriteTextFileAtomically(config.summary_path, summary);
  WriteTextFileAtomically(config.status_path, calibration::FitStatusToml(run.outcome));
  const calibration::FitResult* kept = run.kept_fit();
  const bool plotted = kept && kept->summary.success();
  if (plotted) {
    calibration::WritePlotData(run, *kept, config.plot_data_dir);
    WriteTextFileAtomically(model_toml, calibration::ModelToml(run, *kept));
  } else {
    std::filesystem::remove(model_toml);  // none of an earlier fit stays
  }
  if (!flags.quiet) std::printf("%s\n", summary.c_str());
  std::printf("status: %s: %s\nrecord: %s\nsummary: %s\nstatus file: %s\n",
              calibration::ToString(run.outcome.status), run.outcome.reason.c_str(),
              config.hdf5_path.c_str(), config.summary_path.c_str(), config.status_path.c_str());
  if (plotted) {
    std::printf("model: %s (granasym model run)\n", model_toml.c_str());
    std::printf("plot data: %s (see plots/calibration_*.gp)\n", config.plot_data_dir.c_str());
    for (const std::string& line : DrawCalibrationFigures(config.plot_data_dir)) {
      std::printf("figure: %s\n", line.c_str());
    }
  }
  const int exit_status = calibration::ExitStatus(run.outcome.status);
  if (exit_status != 0) throw CLI::RuntimeError(exit_status);
}

}  // namespace

void RegisterCalibrateCommand(CLI::App& app) {
  static CalibrateFlags flags;
  CLI::App* calibrate = app.add_subcommand(
      "calibrate",
      "fit a constitutive model to asymptotic states (TOML: [model], [parameters.*], "
      "[[dataset]], [fitter], [output]); exits 0 when the fit converged, else with its status "
      "(3 failed, 5 at_bound, 6 converged_inadmissible, 7 no_convergence)");
  calibrate->add_option("config", flags.config, "calibration file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  calibrate->add_option("--out", flags.out, "HDF5 record (default: [output] hdf5 or CONFIG.h5)");
  calibrate->add_option("--summary", flags.summary, "readable summary (default: CONFIG.txt)");
  calibrate->add_option("--plot-data", flags.plot_data,
                        "folder for the figure data (default: CONFIG_plots)");
  calibrate->add_option("--status", flags.status,
                        "the fit's status and reason, TOML (default: CONFIG_status.toml)");
  calibrate->add_flag("--quiet", flags.quiet, "print only the output paths");
  calibrate->callback([] { RunCalibrate(flags); });
}

}  // namespace granasym
