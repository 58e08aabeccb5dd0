// Mašín (2005) clay hypoplasticity: every property of SPEC §6.1.
#include "constitutive/hypoplastic_clay.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/state_measures.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/element_driver.h"
#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

using testing_models::LondonClay;

ElementTestOptions TightOptions() {
  ElementTestOptions options;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-13;
  return options;
}

TEST(HypoplasticClay, RejectsInvalidParameters) {
  std::string why;
  HypoplasticClay::Parameters p = LondonClay();
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.kappa_star = p.lambda_star;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("kappa_star"), std::string::npos);
  p = LondonClay();
  p.bulk_shear_ratio = 0.0;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("bulk_shear_ratio"), std::string::npos);
  p = LondonClay();
  p.critical_friction_angle = 95 * kDegree;
  EXPECT_FALSE(p.IsValid(&why));
}

TEST(HypoplasticClay, IsotropicNormalCompressionFollowsTheNcl) {
  const HypoplasticClay model(LondonClay());
  const ModelState initial = InitialStateFromOcr(model, 50.0, 0.0, 1.0);
  LoadingStage stage = LoadingStage::IsotropicToMeanStress(800.0, 1.0);
  stage.duration = 0.2;  // ln 16 λ*/√3 ≈ 0.176 s reach the target
  const ElementTestResult result = ElementTest(model, TightOptions()).Run(initial, {stage});
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  ASSERT_GT(result.history.size(), 10u);
  const auto& p = model.parameters();
  for (const ElementTestRecord& record : result.history) {
    const double mean = RecordStress(record).mean();
    EXPECT_NEAR(std::log1p(record.void_ratio), p.n_intercept - p.lambda_star * std::log(mean),
                1e-8);
    EXPECT_NEAR(RecordStress(record).deviator() / mean, 0.0, 1e-12);
  }
  // The stop lands on the target, not the nearest step.
  EXPECT_NEAR(RecordStress(result.history.back()).mean(), 800.0, 1e-8);
}

TEST(HypoplasticClay, IsotropicUnloadingStartsWithSlopeKappaStar) {
  const HypoplasticClay model(LondonClay());
  const ModelState state = InitialStateFromOcr(model, 200.0, 0.0, 1.0);
  ModelRate rate;
  std::string why;
  const Vector6 expansion = IdentityVoigt();  // tension positive: volume increase
  ASSERT_TRUE(model.Rate(state, expansion, &rate, nullptr, &why)) << why;
  const double log_volume_rate = Trace<double>(expansion);
  const double log_p_rate = -Trace<double>(rate.stress_rate) / 3.0 / MeanStress(state.stress);
  EXPECT_NEAR(log_volume_rate / log_p_rate, -model.parameters().kappa_star, 1e-12);
}

TEST(HypoplasticClay, BulkShearRatioOnTheNclIsR) {
  const HypoplasticClay model(LondonClay());
  const ModelState state = InitialStateFromOcr(model, 100.0, 0.0, 1.0);
  std::string why;
  ModelRate compression, shear;
  // K on the NCL from isotropic loading; G from a pure deviatoric stretching.
  ASSERT_TRUE(model.Rate(state, -IdentityVoigt(), &compression, nullptr, &why)) << why;
  Vector6 deviatoric;
  deviatoric << 0, 0, 0, 1e-3, 0, 0;
  ASSERT_TRUE(model.Rate(state, deviatoric, &shear, nullptr, &why)) << why;
  const double bulk = (-Trace<double>(compression.stress_rate) / 3.0) / 3.0;  // ṗ / ε̇_v
  const double shear_modulus = shear.stress_rate[3] / (2.0 * deviatoric[3]);
  EXPECT_NEAR(bulk, 100.0 / model.parameters().lambda_star, 1e-9);
  EXPECT_NEAR(bulk / shear_modulus, model.parameters().bulk_shear_ratio, 1e-12);
}

TEST(HypoplasticClay, SbsPyknotropyIsTwoToAlphaIsotropicAndOneAtCriticalState) {
  const HypoplasticClay model(LondonClay());
  std::string why;
  HypoplasticClay::Asymptote isotropic, critical;
  ASSERT_TRUE(model.AsymptoteForStress(AxisymmetricStressTensor(100, 0.0), &isotropic, &why));
  EXPECT_NEAR(isotropic.pyknotropy_sbs, std::pow(2.0, model.alpha()), 1e-12);
  EXPECT_NEAR(isotropic.ocr, 1.0, 1e-12);
  const double psi_c = CriticalStatePsiSigma(model.critical_friction_angle());
  ASSERT_TRUE(model.AsymptoteForStress(AxisymmetricStressTensor(100, psi_c), &critical, &why));
  EXPECT_NEAR(critical.pyknotropy_sbs, 1.0, 1e-12);
  EXPECT_NEAR(critical.ocr, 2.0, 1e-11);
  // Critical state: isochoric asymptotic stretching (ψ_ε = 90°).
  AsymptoticState state;
  ASSERT_TRUE(AnalyticAsymptoteForStress(model, psi_c, &state, &why));
  EXPECT_NEAR(state.psi_epsilon, kPi / 2, 1e-10);
}

TEST(HypoplasticClay, CriticalStateInExtensionHasTheMatsuokaNakaiAngle) {
  const HypoplasticClay model(LondonClay());
  AsymptoticState state;
  std::string why;
  ASSERT_TRUE(AnalyticAsymptoteForStretching(model, -kPi / 2, &state, &why)) << why;
  // Triaxial extension: q/p = −6 sin φ/(3 + sin φ).
  const double s = std::sin(model.critical_friction_angle());
  EXPECT_NEAR(state.stress_ratio, -6.0 * s / (3.0 + s), 1e-10);
  EXPECT_NEAR(state.ocr, 2.0, 1e-9);
}

TEST(HypoplasticClay, IsochoricShearReachesTheCriticalState) {
  const HypoplasticClay model(LondonClay());
  AsymptoteSearchOptions options;
  for (double ocr : {1.0, 4.0}) {
    const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, ocr);
    const IntegratedAsymptote asymptote = IntegrateAsymptote(model, initial, kPi / 2, options);
    ASSERT_TRUE(asymptote.found) << asymptote.summary.Report();
    EXPECT_NEAR(asymptote.state.stress_ratio, CriticalStateRatio(model.critical_friction_angle()),
                1e-7);
    EXPECT_NEAR(asymptote.state.ocr, 2.0, 1e-7);  // p = p_e/2
  }
}

TEST(HypoplasticClay, TangentMatchesFiniteDifferences) {
  const HypoplasticClay model(LondonClay());
  const ModelState state = InitialStateFromOcr(model, 120.0, 0.3, 1.7);
  Vector6 d;
  d << -0.3, 0.1, 0.05, 0.02, -0.04, 0.07;
  ModelRate rate;
  Matrix6 tangent;
  std::string why;
  ASSERT_TRUE(model.Rate(state, d, &rate, &tangent, &why)) << why;
  for (int j = 0; j < 6; ++j) {
    const double h = 1e-6;
    Vector6 plus = d, minus = d;
    plus[j] += h;
    minus[j] -= h;
    ModelRate rate_plus, rate_minus;
    ASSERT_TRUE(model.Rate(state, plus, &rate_plus, nullptr, &why));
    ASSERT_TRUE(model.Rate(state, minus, &rate_minus, nullptr, &why));
    const Vector6 column = (rate_plus.stress_rate - rate_minus.stress_rate) / (2 * h);
    EXPECT_LT((column - tangent.col(j)).norm(), 1e-6 * tangent.norm()) << "column " << j;
  }
}

TEST(HypoplasticClay, JacobianMatchesFiniteDifferences) {
  const HypoplasticClay model(LondonClay());
  ModelState state = InitialStateFromOcr(model, 120.0, 0.3, 1.7);
  state.stress[3] = -4.0;
  state.stress[5] = 2.5;
  Vector6 d;
  d << -0.3, 0.1, 0.05, 0.02, -0.04, 0.07;
  RateJacobian jacobian;
  std::string why;
  ASSERT_TRUE(model.Jacobian(state, d, &jacobian, &why)) << why;
  ASSERT_EQ(jacobian.d_state.rows(), 6);
  ASSERT_EQ(jacobian.d_state.cols(), 7);
  for (int j = 0; j < 7; ++j) {
    ModelState plus = state, minus = state;
    const double h = j < 6 ? 1e-5 * 120.0 : 1e-7;
    if (j < 6) {
      plus.stress[j] += h;
      minus.stress[j] -= h;
    } else {
      plus.void_ratio = std::expm1(std::log1p(state.void_ratio) + h);
      minus.void_ratio = std::expm1(std::log1p(state.void_ratio) - h);
    }
    ModelRate rate_plus, rate_minus;
    ASSERT_TRUE(model.Rate(plus, d, &rate_plus, nullptr, &why)) << why;
    ASSERT_TRUE(model.Rate(minus, d, &rate_minus, nullptr, &why)) << why;
    const Vector6 column = (rate_plus.stress_rate - rate_minus.stress_rate) / (2 * h);
    EXPECT_LT((column - jacobian.d_state.col(j)).norm(),
              1e-6 * (1.0 + jacobian.d_state.col(j).norm()))
        << "column " << j << "\nFD " << column.transpose() << "\nAD "
        << jacobian.d_state.col(j).transpose();
  }
  Matrix6 tangent;
  ModelRate rate;
  ASSERT_TRUE(model.Rate(state, d, &rate, &tangent, &why));
  EXPECT_LT((tangent - jacobian.d_stretching).norm(), 1e-12 * tangent.norm());
}

TEST(HypoplasticClay, RejectsTensileStates) {
  const HypoplasticClay model(LondonClay());
  ModelState state = InitialStateFromOcr(model, 100.0, 0.0, 1.0);
  state.stress[0] = 10.0;  // tension in direction 1
  std::string why;
  EXPECT_FALSE(model.IsAdmissible(state, &why));
  ModelRate rate;
  EXPECT_FALSE(model.Rate(state, Vector6::Ones(), &rate, nullptr, &why));
  EXPECT_NE(why.find("tension"), std::string::npos);
}

}  // namespace
}  // namespace granasym
