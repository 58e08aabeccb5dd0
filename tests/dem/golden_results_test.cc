// The results version (common/results_version.h) tied to golden outputs: a
// short run of each contact law and each stage type from a generated
// sample, whose final state must match tests/data/golden_results_v<N>.csv of
// the current kResultsVersion. A change of the code that changes results
// fails here until the version is raised (which recomputes every cached
// study case) and the golden values of the new version are written:
//
//   GRANASYM_WRITE_GOLDEN=1 build/tests/dem_tests --gtest_filter='GoldenResults.*'
//
// writes tests/data/golden_results_v<N>.csv (refused when it exists: a
// version's golden values never change). The tolerances (relative 1e-4 on
// the final stresses and ln(1+e), 0.01° on ψ_σ, 1 % on the steps) admit the
// rounding of another compiler or instruction set over these few thousand
// steps (a build without -march=native stays within them), not a change of
// the physics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/hdf5_file.h"
#include "common/results_version.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

using testing::SampleToml;
using testing::TempPath;

std::string GoldenPath() {
  return std::string(GRANASYM_TEST_DATA_DIR) + "/golden_results_v" +
         std::to_string(kResultsVersion) + ".csv";
}

// The quantities compared: the final row of the run's series, its steps.
std::map<std::string, double> Run(const std::string& name, const std::string& text) {
  const Scene scene = Scene::Parse(text, name + ".toml", "");
  RunOptions options;
  options.output_path = TempPath("golden_" + name + ".h5");
  const RunSummary summary = RunScene(scene, options);
  EXPECT_EQ(summary.termination, Termination::kCompleted) << name << ": " << summary.message;
  const Hdf5File file = Hdf5File::OpenRead(options.output_path);
  const TimeSeries series = TimeSeries::Read(file, "/series");
  std::map<std::string, double> out;
  for (const char* column : {"p_kpa", "q_kpa", "ln_1_plus_e", "psi_sigma_deg"}) {
    out[column] = series.Values(column).back();
  }
  out["steps"] = static_cast<double>(summary.steps);
  return out;
}

// 300 spheres of the default GSD at the reference porosity.
std::string Sample() { return SampleToml(300, 3.88, 7); }

const char* kNcl =
    "[[stage]]\nname = \"ncl\"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
    "[stage.stop]\nmean_stress_kpa = 100.0\n";

std::map<std::string, std::map<std::string, double>> RunAll() {
  std::map<std::string, std::map<std::string, double>> runs;
  runs["linear_strain_path"] = Run("linear_strain_path", Sample() + kNcl);
  runs["linear_triaxial"] =
      Run("linear_triaxial", Sample() + kNcl + testing::TriaxialStage(100.0, 0.01));
  runs["linear_rest"] =
      Run("linear_rest", Sample() + kNcl +
                             "[[stage]]\nname = \"rest\"\ntype = \"rest\"\n"
                             "mean_stress_kpa = 50.0\n[stage.stop]\nsteps = 20000\n");
  runs["hertz_mindlin_strain_path"] =
      Run("hertz_mindlin_strain_path",
          Sample() + "[material]\ncontact_law = \"hertz_mindlin\"\npoissons_ratio = 0.2\n" + kNcl);
  return runs;
}

TEST(GoldenResults, TheResultsVersionsGoldenOutputsAreReproduced) {
  const auto runs = RunAll();
  if (std::getenv("GRANASYM_WRITE_GOLDEN")) {
    ASSERT_FALSE(std::filesystem::exists(GoldenPath()))
        << GoldenPath() << " exists: the golden values of a results version never change";
    std::string text = "# golden results of results version " + std::to_string(kResultsVersion) +
                       " (tests/dem/golden_results_test.cc)\nrun,quantity,value\n";
    for (const auto& [run, values] : runs) {
      for (const auto& [quantity, value] : values) {
        char number[64];
        std::snprintf(number, sizeof number, "%.17g", value);
        text += run + "," + quantity + "," + number + "\n";
      }
    }
    WriteTextFileAtomically(GoldenPath(), text);
    GTEST_SKIP() << "wrote " << GoldenPath();
  }
  ASSERT_TRUE(std::filesystem::exists(GoldenPath()))
      << "no golden values for results version " << kResultsVersion << " (" << GoldenPath()
      << "): write them with GRANASYM_WRITE_GOLDEN=1 (see this test's header)";
  std::istringstream lines(ReadTextFile(GoldenPath()));
  int compared = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#' || line == "run,quantity,value") continue;
    std::istringstream fields(line);
    std::string run, quantity, value;
    std::getline(fields, run, ',');
    std::getline(fields, quantity, ',');
    std::getline(fields, value);
    ASSERT_TRUE(runs.count(run) && runs.at(run).count(quantity)) << "golden row " << line;
    const double golden = std::stod(value), now = runs.at(run).at(quantity);
    const double tolerance = quantity == "steps"           ? 0.01 * golden
                             : quantity == "psi_sigma_deg" ? 0.01
                                                           : 1e-4 * std::abs(golden);
    EXPECT_NEAR(now, golden, tolerance)
        << run << " " << quantity << ": the results changed without a new results version: "
        << "raise kResultsVersion in common/results_version.h (every cached study case is then "
           "computed again) and write the new version's golden values";
    ++compared;
  }
  EXPECT_EQ(compared, 20);
}

}  // namespace
}  // namespace granasym::dem
