// `granasym model run TEST.toml [--out FILE.h5] [--csv FILE.csv]` and
// `granasym model asymptotes MODEL.toml [--out FILE.h5]`: parse, validate,
// call the constitutive library, write HDF5 atomically.
#include "app/model_commands.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/output_path.h"
#include "constitutive/model_config.h"

namespace granasym {

namespace {

std::string DefaultOutput(const std::string& input) {
  return std::filesystem::path(input).replace_extension(".h5").string();
}

void RunTest(const std::string& path, std::string out, const std::string& csv) {
  const ConfigTable root = ConfigTable::ParseFile(path);
  if (out.empty()) out = DefaultOutput(path);
  CheckOutputs({{"--out", out}, {"--csv", csv}}, {{"the test file", path}});
  const ElementTestResult result = RunElementTestInput(root, path, out, csv);
  std::printf("%s\n", result.summary.Report().c_str());
  for (const StageSummary& stage : result.summary.stages) {
    std::printf("  %s: stop %s; %s\n", stage.name.c_str(), stage.stop.c_str(),
                stage.integration.Report().c_str());
  }
  std::printf("results: %s\n", out.c_str());
  if (!result.summary.success()) throw CLI::RuntimeError(3);
}

void RunAsymptotes(const std::string& path, std::string out) {
  const ConfigTable root = ConfigTable::ParseFile(path);
  if (out.empty()) out = DefaultOutput(path);
  CheckOutputs({{"--out", out}}, {{"the model file", path}});
  const std::unique_ptr<ConstitutiveModel> model = ReadModel(root.GetTable("model"));
  const AsymptoteTable table = ComputeAsymptotes(*model, root);
  root.CheckNoUnknownKeys();
  Hdf5File file = Hdf5File::CreateAtomic(out);
  WriteAsymptotes(*model, table, "/asymptotes", &file);
  file.Commit();
  std::printf("%s\n", model->Describe().c_str());
  if (!table.analytic.empty()) {
    std::printf("analytic asymptotes: %zu stress directions\n", table.analytic.size());
  }
  bool all_found = true;
  for (const IntegratedAsymptote& a : table.integrated) {
    all_found = all_found && a.found;
    std::printf(
        "psi_epsilon %8.3f deg: %s psi_sigma %.9f deg, OCR %.9g, q/p %.9g (strain path %.3g)\n",
        a.state.psi_epsilon / kDegree, a.found ? "asymptote" : "NOT FOUND",
        a.state.psi_sigma / kDegree, a.state.ocr, a.state.stress_ratio, a.strain_path);
    if (!a.found) std::printf("  %s\n", a.summary.Report().c_str());
  }
  std::printf("results: %s\n", out.c_str());
  if (!all_found) throw CLI::RuntimeError(3);
}

}  // namespace

void RegisterModelCommands(CLI::App& app) {
  CLI::App* model = app.add_subcommand("model", "constitutive models: element tests, asymptotes");
  model->require_subcommand(1);

  CLI::App* run = model->add_subcommand("run", "run an element test file (TOML)");
  static std::string test_path, run_out, run_csv;
  run->add_option("test", test_path, "test file (TOML: [model], [initial], [[stage]])")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out", run_out, "result file (HDF5; default: the test file with .h5)");
  run->add_option("--csv", run_csv, "also write the history as CSV");
  run->callback([] { RunTest(test_path, run_out, run_csv); });

  CLI::App* asymptotes =
      model->add_subcommand("asymptotes", "asymptotic states of a model file (TOML)");
  static std::string model_path, asymptotes_out;
  asymptotes->add_option("model", model_path, "model file (TOML: [model], [asymptotes])")
      ->required()
      ->check(CLI::ExistingFile);
  asymptotes->add_option("--out", asymptotes_out, "result file (HDF5)");
  asymptotes->callback([] { RunAsymptotes(model_path, asymptotes_out); });
}

}  // namespace granasym
