// The inertial-number rate rule of strain-path stages (issue 10 §1): ‖D‖
// follows the measured p so that I(d) stays at its target, under a cap.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "dem/strain_path_stage.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

using testing::SampleToml;
using testing::TempPath;

TimeSeries RunNcl(const std::string& rate_table, double cap, const std::string& name) {
  const std::string text = SampleToml(300, 3.9, 7) +
                           "[output]\ninterval_steps = 200\n[[stage]]\nname = \"ncl\"\n"
                           "psi_epsilon_deg = 0.0\nstretching_rate = " +
                           std::to_string(cap) + "\n" + rate_table +
                           "[stage.stop]\nmean_stress_kpa = 100.0\n";
  RunOptions options;
  options.output_path = TempPath(name + ".h5");
  const RunSummary summary = RunScene(Scene::Parse(text, name + ".toml", ""), options);
  EXPECT_EQ(summary.termination, Termination::kCompleted) << summary.OneLine();
  return TimeSeries::Read(Hdf5File::OpenRead(options.output_path), "/series");
}

TEST(InertialRate, HoldsTheInertialNumberOfTheLargestDiameterOnceInContact) {
  const TimeSeries series =
      RunNcl("[stage.rate]\nrule = \"inertial\"\ninertial_number = 0.01\ncheck_interval = 1\n", 1e4,
             "inertial_dmax");
  const std::vector<double>& p = series.Values(record::kColumnMeanStress);
  const std::vector<double>& inertial = series.Values(record::kColumnInertialNumberDmax);
  int checked = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    if (p[k] < 2.0) continue;  // below the floor of 1 kPa (and its approach) the floor rules
    EXPECT_NEAR(inertial[k], 0.01, 0.01 * 0.05) << "row " << k << " at p = " << p[k] << " kPa";
    ++checked;
  }
  EXPECT_GT(checked, 3);
  EXPECT_GE(p.back(), 100.0);
  // Every row reports the stiffness number: the linear law's E/(2p), E = 500 MPa.
  const std::vector<double>& kappa = series.Values("stiffness_number");
  EXPECT_NEAR(kappa.back(), 500e6 / (2 * p.back() * 1e3), 1e-9 * kappa.back());
}

TEST(InertialRate, TheCapBoundsTheRateAndTheInertialNumberFallsBelowItsTarget) {
  // A target of I = 0.5 would need ‖D‖ of thousands of 1/s: the cap of 50 holds.
  const TimeSeries series =
      RunNcl("[stage.rate]\nrule = \"inertial\"\ninertial_number = 0.5\ncheck_interval = 5\n", 50.0,
             "inertial_cap");
  const std::vector<double>& p = series.Values(record::kColumnMeanStress);
  const std::vector<double>& inertial = series.Values(record::kColumnInertialNumberDmax);
  for (size_t k = 1; k < p.size(); ++k) {
    if (p[k] > 2.0) {
      EXPECT_LT(inertial[k], 0.5) << "row " << k;
    }
  }
}

TEST(InertialRate, RateFollowsTheFormulaWithItsFloorAndCap) {
  InertialRate rule;
  rule.inertial_number = 1e-3;
  rule.min_mean_stress_kpa = 1.0;
  StageContext context;
  context.max_diameter = 1e-3;
  context.median_diameter = 0.5e-3;
  context.min_diameter = 0.25e-3;
  context.density = 2650;
  // I d^-1 sqrt(p / 2ρ): 100 kPa, d_max = 1 mm → 1e-3 · sqrt(1e5/5300) / 1e-3 = 4.34 1/s.
  EXPECT_NEAR(rule.Rate(100.0, context, 1e6), std::sqrt(1e5 / 5300.0), 1e-12);
  EXPECT_NEAR(rule.Rate(0.0, context, 1e6), std::sqrt(1e3 / 5300.0), 1e-12);  // the floor
  EXPECT_NEAR(rule.Rate(std::nan(""), context, 1e6), std::sqrt(1e3 / 5300.0), 1e-12);
  EXPECT_EQ(rule.Rate(100.0, context, 1.0), 1.0);  // the cap
  rule.diameter = InertialDiameter::kMin;
  EXPECT_NEAR(rule.Rate(100.0, context, 1e6), 4 * std::sqrt(1e5 / 5300.0), 1e-11);
}

TEST(InertialRate, KeysAreValidatedAndBelongToTheInertialRule) {
  auto error = [](const std::string& rate) {
    const std::string text =
        "[sample.generate]\ncount = 100\n[[stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = "
        "100.0\n" +
        rate + "[stage.stop]\nmean_stress_kpa = 100.0\n";
    try {
      Scene::Parse(text, "rate.toml", "");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("[stage.rate]\nrule = \"inertial\"\n").find("stage[0].rate.inertial_number"),
            std::string::npos);
  EXPECT_NE(error("[stage.rate]\nrule = \"inertial\"\ninertial_number = 2.0\n")
                .find("'stage[0].rate.inertial_number' = 2"),
            std::string::npos);
  EXPECT_NE(error("[stage.rate]\nrule = \"inertial\"\ninertial_number = 0.01\ndiameter = "
                  "\"d_84\"\n")
                .find("d_max, d_50 or d_min"),
            std::string::npos);
  EXPECT_NE(error("[stage.rate]\nrule = \"constant\"\ninertial_number = 0.01\n")
                .find("stage[0].rate.inertial_number' is not a known key"),
            std::string::npos);
  EXPECT_EQ(error("[stage.rate]\nrule = \"inertial\"\ninertial_number = 0.01\n"), "");
}

}  // namespace
}  // namespace granasym::dem
