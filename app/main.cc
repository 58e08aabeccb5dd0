// granasym: the command-line program. It parses and validates arguments and
// calls the libraries; errors in user input end with a message and status 2.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/keys_command.h"
#include "app/progress.h"
#include "app/signals.h"
#include "app/study_commands.h"
#include "app/thread_count.h"
#include "common/blas_threads.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/output_path.h"
#include "common/time_series.h"
#include "dem/packing.h"
#include "dem/run_record.h"
#include "dem/scene.h"
#include "dem/simulation.h"

#ifdef GRANASYM_HAVE_CONSTITUTIVE
#include "app/model_commands.h"
#endif
#ifdef GRANASYM_HAVE_CALIBRATION
#include "app/calibrate_command.h"
#endif

namespace granasym {
namespace {

void RegisterDemCommands(CLI::App& app) {
  CLI::App* dem = app.add_subcommand("dem", "discrete element runs on a periodic cell");
  dem->require_subcommand(1);

  // granasym dem generate
  CLI::App* generate = dem->add_subcommand(
      "generate", "generate a packing from a grain-size table and write it as plain text");
  static dem::GenerationOptions generation;
  static std::string gsd_path, packing_out;
  static double cell_mm = 31.0;
  static int64_t count = 150000;
  generate->add_option("--count", count, "number of spheres")
      ->check(CLI::Range(int64_t{2}, int64_t{2000000000}));
  generate->add_option("--cell-mm", cell_mm, "side of the periodic cube (mm)")
      ->check(CLI::PositiveNumber);
  generate->add_option("--gsd", gsd_path,
                       "grain-size table (CSV: diameter_mm,percent_passing_by_mass); default: "
                       "the reduced GSD of Zbraslav sand");
  generate->add_option("--seed", generation.seed, "random placement seed");
  generate->add_option("--out", packing_out, "packing file to write (N Lx Ly Lz / x y z r, metres)")
      ->required();
  generate->callback([] {
    CheckOutputs({{"--out", packing_out}}, {{"--gsd", gsd_path}});
    const dem::GrainSizeDistribution gsd = gsd_path.empty()
                                               ? dem::GrainSizeDistribution::Default()
                                               : dem::GrainSizeDistribution::ReadCsv(gsd_path);
    generation.count = static_cast<size_t>(count);
    generation.cell_size = cell_mm * 1e-3;
    dem::GenerationReport report;
    const dem::Packing packing = dem::GeneratePacking(gsd, generation, &report);
    packing.WriteText(packing_out);
    std::printf("%swritten to %s\n", report.Table().c_str(), packing_out.c_str());
  });

  // granasym dem run
  CLI::App* run = dem->add_subcommand("run", "run a scene file (TOML) and write one HDF5 result");
  static std::string scene_path;
  static dem::RunOptions run_options;
  static bool quiet = false;
  run->add_option("scene", scene_path, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  run->add_option("--out", run_options.output_path,
                  "result file (HDF5; default: run.h5 in the current folder); the checkpoint "
                  "goes next to it (FILE.ckpt)");
  run->add_option("--threads", run_options.threads,
                  "OpenMP threads (default: the scene's; at most the hardware threads)")
      ->check(CLI::Range(1, 1024));
  run->add_flag("--restart", run_options.restart,
                "continue from the checkpoint written next to --out");
  run->add_flag("--quiet", quiet, "no progress output");
  run->add_flag("--keep-checkpoint", run_options.keep_checkpoint,
                "keep the checkpoint after a completed run");
  run->callback([] {
    const dem::Scene scene = dem::Scene::Load(scene_path);
    CheckOutputs({{"--out", run_options.output_path},
                  {"the checkpoint (--out + .ckpt)", run_options.output_path + ".ckpt"}},
                 scene.InputFiles());
    if (run_options.threads > 0) run_options.threads = CapThreads(run_options.threads, "--threads");
    Progress::Options progress_options;
    progress_options.plain_interval_s = scene.output.progress_interval_s;
    progress_options.quiet = quiet;
    Progress progress(progress_options);
    const SignalGuard signals;
    run_options.stop_requested = [](int64_t) { return InterruptRequested(); };
    if (!quiet) {
      run_options.log = [&progress](const std::string& line) {
        progress.Finish();
        std::fprintf(stderr, "%s%s", line.c_str(),
                     !line.empty() && line.back() == '\n' ? "" : "\n");
      };
      run_options.progress = [&progress](const dem::RunProgress& state) {
        if (progress.Due()) progress.Report(state.OneLine());
      };
    }
    const dem::RunSummary summary = dem::RunScene(scene, run_options);
    progress.Finish();
    std::printf("%s\nresults: %s\n", summary.OneLine().c_str(), run_options.output_path.c_str());
    if (summary.termination == dem::Termination::kInterrupted) throw CLI::RuntimeError(130);
    if (summary.termination == dem::Termination::kFailed) throw CLI::RuntimeError(3);
  });
}

void RegisterExportCommand(CLI::App& app) {
  CLI::App* exporter = app.add_subcommand(
      "export",
      "export a result file: time series as CSV, final packing as text, or what it holds");
  static std::string input, csv_path, packing_path;
  static bool info = false;
  exporter->add_option("result", input, "result file (HDF5)")->required()->check(CLI::ExistingFile);
  exporter->add_option("--csv", csv_path, "write the time series as CSV with a header row");
  exporter->add_option("--packing", packing_path,
                       "write the final particle state as a plain-text packing");
  exporter->add_flag("--info", info,
                     "print what the result holds, one line per item: scene, termination, "
                     "whether it is final, stages with their stop reasons and asymptotes");
  exporter->callback([] {
    if (csv_path.empty() && packing_path.empty() && !info) {
      throw InputError("export: give --csv FILE, --packing FILE and/or --info");
    }
    CheckOutputs({{"--csv", csv_path}, {"--packing", packing_path}}, {{"the result file", input}});
    const Hdf5File file = Hdf5File::OpenRead(input);
    if (info) std::printf("%s", dem::DescribeResult(file).c_str());
    // A partial result sits under the final name while a run goes on and
    // after it was interrupted: say so (the export goes ahead; --info says
    // it in its line "final").
    if ((!csv_path.empty() || !packing_path.empty()) && file.Exists("/summary")) {
      const std::string note = dem::PartialResultNote(file);
      if (!note.empty()) std::fprintf(stderr, "warning: %s\n", note.c_str());
    }
    if (!csv_path.empty()) {
      const std::string group = file.Exists("/series") ? "/series" : "";
      if (group.empty()) throw InputError(input + ": no /series group to export");
      TimeSeries::Read(file, group).WriteCsv(csv_path);
      std::printf("time series written to %s\n", csv_path.c_str());
    }
    if (!packing_path.empty()) {
      const dem::Packing packing = dem::ReadResultPacking(input, "/final_state");
      packing.WriteText(packing_path);
      std::printf("final packing written to %s\n", packing_path.c_str());
    }
  });
}

}  // namespace
}  // namespace granasym

int main(int argc, char** argv) {
  // Before any thread of granasym's own: OpenBLAS's pool, if the system BLAS
  // is OpenBLAS, would spin on the cores the DEM's threads need.
  granasym::KeepBlasSerial();
  // A file-size limit (ulimit -f) is a full disk to granasym: the write fails
  // with EFBIG and is reported (status 1), instead of the kernel killing the
  // process with SIGXFSZ and leaving its temporary files.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "granasym: asymptotic behaviour of granular materials (DEM, constitutive models, "
      "calibration)"};
  app.require_subcommand(1);
  granasym::RegisterDemCommands(app);
  granasym::RegisterExportCommand(app);
  granasym::RegisterStudyCommands(app);
  granasym::RegisterKeysCommand(app);
#ifdef GRANASYM_HAVE_CONSTITUTIVE
  granasym::RegisterModelCommands(app);
#endif
#ifdef GRANASYM_HAVE_CALIBRATION
  granasym::RegisterCalibrateCommand(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& done) {
    return app.exit(done);  // --help
  } catch (const CLI::RuntimeError& status) {
    return status.get_exit_code();  // a failed (3) or interrupted (130) run, already reported
  } catch (const CLI::ParseError& error) {
    // Bad flags are bad input: the message, a hint, and status 2.
    std::fprintf(stderr, "error: %s\nRun with --help for the valid flags.\n", error.what());
    return 2;
  } catch (const granasym::InputError& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "failure: %s\n", error.what());
    return 1;
  }
  return 0;
}
