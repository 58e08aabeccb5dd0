// Asymptotic states: analytic ASBS against integration, and the paper's
// Fig. 5 paths A (compression), B (isochoric), C (extension) reaching their
// asymptotes from different initial states.
#include "constitutive/asymptotic_states.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

TEST(AsymptoteSearchOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(AsymptoteSearchOptions().IsValid(&why)) << why;
}

TEST(AnalyticAsymptotes, CurveIsMonotoneFromExtensionToTheLimitD) {
  const HypoplasticClay model(testing_models::LondonClay());
  const std::vector<AsymptoticState> curve = AnalyticAsymptoteCurve(model, 200);
  ASSERT_EQ(curve.size(), 200u);
  for (size_t i = 1; i < curve.size(); ++i) {
    EXPECT_GT(curve[i].psi_epsilon, curve[i - 1].psi_epsilon) << i;
    EXPECT_GT(curve[i].ocr, 0.99);
  }
  double lowest, highest;
  AnalyticStretchingRange(model, &lowest, &highest);
  EXPECT_GT(highest, kPi / 2);  // extension states beyond the critical state
  EXPECT_LT(lowest, -kPi / 2);
}

TEST(AnalyticAsymptotes, InversionRecoversTheStressDirection) {
  const HypoplasticClay model(testing_models::LondonClay());
  for (double psi_sigma : {-0.3, 0.0, 0.2, 0.5, 0.9}) {
    AsymptoticState forward, inverse;
    std::string why;
    ASSERT_TRUE(AnalyticAsymptoteForStress(model, psi_sigma, &forward, &why)) << why;
    ASSERT_TRUE(AnalyticAsymptoteForStretching(model, forward.psi_epsilon, &inverse, &why)) << why;
    EXPECT_NEAR(inverse.psi_sigma, psi_sigma, 1e-12);
    EXPECT_NEAR(inverse.ocr, forward.ocr, 1e-10 * forward.ocr);
  }
  AsymptoticState none;
  std::string why;
  EXPECT_FALSE(AnalyticAsymptoteForStretching(model, kPi, &none, &why));  // isotropic unloading
  EXPECT_FALSE(why.empty());
}

struct PathCase {
  const char* name;
  double psi_epsilon_deg;
};

class Fig5Paths : public ::testing::TestWithParam<PathCase> {};

// Paths A (45°), B (90°), C (100°) from a normally consolidated and two
// overconsolidated states (one of them anisotropic) reach the analytic
// asymptote to 1e-6 in ψ_σ (rad) and in relative OCR.
TEST_P(Fig5Paths, ReachTheAnalyticAsymptoteFromDifferentInitialStates) {
  const HypoplasticClay model(testing_models::LondonClay());
  const double psi_epsilon = GetParam().psi_epsilon_deg * kDegree;
  AsymptoticState analytic;
  std::string why;
  ASSERT_TRUE(AnalyticAsymptoteForStretching(model, psi_epsilon, &analytic, &why)) << why;
  AsymptoteSearchOptions options;
  struct Start {
    double p, psi_sigma, ocr;
  };
  for (const Start& start :
       {Start{100.0, 0.0, 1.0}, Start{100.0, 0.0, 8.0}, Start{300.0, -0.2, 3.0}}) {
    const ModelState initial = InitialStateFromOcr(model, start.p, start.psi_sigma, start.ocr);
    const IntegratedAsymptote integrated = IntegrateAsymptote(model, initial, psi_epsilon, options);
    ASSERT_TRUE(integrated.found) << GetParam().name << ": " << integrated.summary.Report();
    EXPECT_NEAR(integrated.state.psi_sigma, analytic.psi_sigma, 1e-6)
        << GetParam().name << " from OCR " << start.ocr;
    EXPECT_NEAR(integrated.state.ocr / analytic.ocr, 1.0, 1e-6)
        << GetParam().name << " from OCR " << start.ocr;
  }
}

INSTANTIATE_TEST_SUITE_P(Paper, Fig5Paths,
                         ::testing::Values(PathCase{"A_compression", 45.0},
                                           PathCase{"B_isochoric", 90.0},
                                           PathCase{"C_extension", 100.0}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(IntegratedAsymptotes, CamClayCriticalStateIsReachedFromBothSides) {
  const ModifiedCamClay model(testing_models::CamClay());
  const double ocr_c =
      std::pow(2.0, (testing_models::CamClay().lambda - testing_models::CamClay().kappa) /
                        testing_models::CamClay().lambda);
  AsymptoteSearchOptions options;
  options.tolerance = 1e-8;
  for (double ocr : {1.0, 1.5}) {  // wet side of the critical state only: no softening
    const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, ocr);
    const IntegratedAsymptote integrated = IntegrateAsymptote(model, initial, kPi / 2, options);
    ASSERT_TRUE(integrated.found) << integrated.summary.Report();
    EXPECT_NEAR(integrated.state.stress_ratio, testing_models::CamClay().critical_state_ratio,
                1e-6);
    EXPECT_NEAR(integrated.state.ocr, ocr_c, 1e-6);
  }
}

}  // namespace
}  // namespace granasym
