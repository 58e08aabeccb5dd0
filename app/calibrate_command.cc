// `granasym calibrate CONFIG.toml [--out FILE.h5] [--summary FILE.txt]
// [--plot-data DIR] [--quiet]`: parse, validate, call the calibration library,
// write the HDF5 record atomically, the readable summary and the plot data.
#include "app/calibrate_command.h"

#include <cstdio>
#include <string>

#include "calibration/calibration_config.h"
#include "calibration/calibration_report.h"
#include "common/error.h"
#include "common/output_path.h"
#include "common/text_file.h"

namespace granasym {

namespace {

struct CalibrateFlags {
  std::string config, out, summary, plot_data;
  bool quiet = false;
};

void RunCalibrate(const CalibrateFlags& flags) {
  calibration::CalibrationConfig config = calibration::ReadCalibrationConfigFile(flags.config);
  if (!flags.out.empty()) config.hdf5_path = flags.out;
  if (!flags.summary.empty()) config.summary_path = flags.summary;
  if (!flags.plot_data.empty()) config.plot_data_dir = flags.plot_data;
  std::vector<NamedPath> inputs = {{"the calibration file", flags.config}};
  for (const calibration::DatasetConfig& dataset : config.datasets) {
    for (const std::string& path : dataset.paths) {
      inputs.push_back({"the data file of [[dataset]] '" + dataset.name + "'", path});
    }
  }
  CheckOutputs({{"the HDF5 record (--out / [output] hdf5)", config.hdf5_path},
                {"the summary (--summary / [output] summary)", config.summary_path}},
               inputs);
  CheckOutputFolder(
      {"the plot data folder (--plot-data / [output] plot_data)", config.plot_data_dir}, inputs);
  const calibration::CalibrationRun run = calibration::RunCalibration(config);
  const std::string summary = calibration::SummaryText(run);
  calibration::WriteCalibrationHdf5(run, config.hdf5_path);
  WriteTextFileAtomically(config.summary_path, summary);
  bool success = !run.fits.empty();
  for (const calibration::FitResult& fit : run.fits) success = success && fit.summary.success();
  if (success) calibration::WritePlotData(run, run.fits.front(), config.plot_data_dir);
  if (!flags.quiet) std::printf("%s\n", summary.c_str());
  std::printf("record: %s\nsummary: %s\n", config.hdf5_path.c_str(), config.summary_path.c_str());
  if (success)
    std::printf("plot data: %s (see plots/calibration_*.gp)\n", config.plot_data_dir.c_str());
  if (!success) throw CLI::RuntimeError(3);
}

}  // namespace

void RegisterCalibrateCommand(CLI::App& app) {
  static CalibrateFlags flags;
  CLI::App* calibrate = app.add_subcommand(
      "calibrate",
      "fit a constitutive model to asymptotic states (TOML: [model], [parameters.*], "
      "[[dataset]], [fitter], [output])");
  calibrate->add_option("config", flags.config, "calibration file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  calibrate->add_option("--out", flags.out, "HDF5 record (default: [output] hdf5 or CONFIG.h5)");
  calibrate->add_option("--summary", flags.summary, "readable summary (default: CONFIG.txt)");
  calibrate->add_option("--plot-data", flags.plot_data,
                        "folder for the figure data (default: CONFIG_plots)");
  calibrate->add_flag("--quiet", flags.quiet, "print only the output paths");
  calibrate->callback([] { RunCalibrate(flags); });
}

}  // namespace granasym
