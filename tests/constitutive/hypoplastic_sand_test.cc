// von Wolffersdorff (1996) sand hypoplasticity, SPEC §6.3: the formulas at a
// state against an independent 3x3 evaluation, Bauer's law, the limit lines
// (isotropic compression along e_i, critical state on the Matsuoka–Nakai cone
// at e = e_c), rate independence and the exact Jacobian.
#include "constitutive/hypoplastic_sand.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/eigen.h"
#include "constitutive/element_driver.h"
#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

using testing_models::HochstettenSand;

ElementTestOptions TightOptions() {
  ElementTestOptions options;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-13;
  return options;
}

Eigen::Matrix3d ToMatrix(const Vector6& v) {
  Eigen::Matrix3d m;
  m << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return m;
}

Vector6 ToVoigt(const Eigen::Matrix3d& m) {
  Vector6 v;
  v << m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2);
  return v;
}

// The rate written out with 3x3 matrices straight from von Wolffersdorff's
// formulas, sharing nothing with the model's Voigt code.
Eigen::Matrix3d HandRate(const HypoplasticSand::Parameters& p, const Eigen::Matrix3d& t, double e,
                         const Eigen::Matrix3d& d) {
  const Eigen::Matrix3d one = Eigen::Matrix3d::Identity();
  const double mean = -t.trace() / 3.0;
  const Eigen::Matrix3d t_hat = t / t.trace();
  const Eigen::Matrix3d t_star = t_hat - one / 3.0;
  const double tan_psi = std::sqrt(3.0) * t_star.norm();
  const double cos3theta =
      -std::sqrt(6.0) * (t_star * t_star * t_star).trace() / std::pow(t_star.squaredNorm(), 1.5);
  const double f =
      std::sqrt(tan_psi * tan_psi / 8.0 +
                (2.0 - tan_psi * tan_psi) / (2.0 + std::sqrt(2.0) * tan_psi * cos3theta)) -
      tan_psi / (2.0 * std::sqrt(2.0));
  const double s = std::sin(p.critical_friction_angle);
  const double a = std::sqrt(3.0) * (3.0 - s) / (2.0 * std::sqrt(2.0) * s);
  const double bauer =
      std::exp(-std::pow(3.0 * mean / p.granular_hardness, p.compression_exponent));
  const double e_i = p.loosest_void_ratio0 * bauer;
  const double e_c = p.critical_void_ratio0 * bauer;
  const double e_d = p.densest_void_ratio0 * bauer;
  const double f_e = std::pow(e_c / e, p.stiffness_exponent);
  const double f_d = std::pow((e - e_d) / (e_c - e_d), p.pyknotropy_exponent);
  const double f_b =
      p.granular_hardness / p.compression_exponent * (1.0 + e_i) / e_i *
      std::pow(p.loosest_void_ratio0 / p.critical_void_ratio0, p.stiffness_exponent) *
      std::pow(3.0 * mean / p.granular_hardness, 1.0 - p.compression_exponent) /
      (3.0 + a * a -
       a * std::sqrt(3.0) *
           std::pow((p.loosest_void_ratio0 - p.densest_void_ratio0) /
                        (p.critical_void_ratio0 - p.densest_void_ratio0),
                    p.pyknotropy_exponent));
  return f_b * f_e / t_hat.squaredNorm() *
         (f * f * d + a * a * t_hat * t_hat.cwiseProduct(d).sum() +
          f_d * a * f * (t_hat + t_star) * d.norm());
}

// A general (non-axisymmetric, sheared) compressive state of medium density.
ModelState GeneralState(const HypoplasticSand& model) {
  Vector6 stress;
  stress << -180.0, -120.0, -95.0, 14.0, -9.0, 6.0;
  return model.MakeState(stress, 0.70);
}

Vector6 GeneralStretching() {
  Vector6 d;
  d << -0.3, 0.1, 0.05, 0.02, -0.04, 0.07;
  return d;
}

TEST(HypoplasticSand, ReferenceParametersAreValid) {
  std::string why;
  EXPECT_TRUE(HochstettenSand().IsValid(&why)) << why;
  const HypoplasticSand model(HochstettenSand());
  // a = √3 (3 − sin 33°)/(2√2 sin 33°).
  EXPECT_NEAR(model.a(), 2.7607191, 1e-6);
  EXPECT_GT(model.barotropy_denominator(), 0.0);
  EXPECT_EQ(model.kind(), ModelKind::kHypoplasticSand);
  ModelKind kind;
  ASSERT_TRUE(FromString("hypoplastic_sand", &kind));
  EXPECT_EQ(kind, ModelKind::kHypoplasticSand);
  EXPECT_STREQ(ToString(ModelKind::kHypoplasticSand), "hypoplastic_sand");
}

TEST(HypoplasticSand, RejectsInvalidParametersNamingTheField) {
  auto rejected = [](HypoplasticSand::Parameters p, const std::string& field) {
    std::string why;
    EXPECT_FALSE(p.IsValid(&why)) << field;
    EXPECT_NE(why.find(field), std::string::npos) << why;
    return why;
  };
  HypoplasticSand::Parameters p = HochstettenSand();
  p.critical_friction_angle = 95 * kDegree;
  rejected(p, "critical_friction_angle");
  p = HochstettenSand();
  p.granular_hardness = 0.0;
  rejected(p, "granular_hardness");
  p = HochstettenSand();
  p.compression_exponent = 1.0;
  rejected(p, "compression_exponent");
  p = HochstettenSand();
  p.densest_void_ratio0 = 0.96;  // above e_c0
  const std::string order = rejected(p, "critical_void_ratio0");
  EXPECT_NE(order.find("densest_void_ratio0"), std::string::npos) << order;
  p = HochstettenSand();
  p.loosest_void_ratio0 = 0.95;  // equal to e_c0
  rejected(p, "loosest_void_ratio0");
  p = HochstettenSand();
  p.pyknotropy_exponent = -0.1;
  rejected(p, "pyknotropy_exponent");
  p = HochstettenSand();
  p.stiffness_exponent = 0.0;
  rejected(p, "stiffness_exponent");
  p = HochstettenSand();
  p.minimum_mean_stress = 0.0;
  rejected(p, "minimum_mean_stress");
  // ((e_i0 − e_d0)/(e_c0 − e_d0))^α = 1.25^4 = 2.44 > (3 + a²)/(√3 a) = 2.22: f_b < 0.
  p = HochstettenSand();
  p.pyknotropy_exponent = 4.0;
  const std::string denominator = rejected(p, "pyknotropy_exponent");
  EXPECT_NE(denominator.find("f_b"), std::string::npos) << denominator;
}

TEST(HypoplasticSand, RateAtAGeneralStateMatchesAnIndependentEvaluation) {
  const HypoplasticSand model(HochstettenSand());
  const ModelState state = GeneralState(model);
  const Vector6 d = GeneralStretching();
  ModelRate rate;
  std::string why;
  ASSERT_TRUE(model.Rate(state, d, &rate, nullptr, &why)) << why;
  const Eigen::Matrix3d expected =
      HandRate(HochstettenSand(), ToMatrix(state.stress), state.void_ratio, ToMatrix(d));
  EXPECT_LT((rate.stress_rate - ToVoigt(expected)).norm(), 1e-10 * expected.norm())
      << "model " << rate.stress_rate.transpose() << "\nhand  " << ToVoigt(expected).transpose();
  EXPECT_NEAR(rate.void_ratio_rate, (1.0 + state.void_ratio) * d.head<3>().sum(), 1e-15);
  // Also along a principal, triaxial extension and an isotropic state.
  for (const Vector6& stress :
       {AxisymmetricStressTensor(300.0, 0.4), AxisymmetricStressTensor(50.0, -0.3)}) {
    const ModelState s = model.MakeState(stress, 0.8);
    ASSERT_TRUE(model.Rate(s, d, &rate, nullptr, &why)) << why;
    const Eigen::Matrix3d hand = HandRate(HochstettenSand(), ToMatrix(stress), 0.8, ToMatrix(d));
    EXPECT_LT((rate.stress_rate - ToVoigt(hand)).norm(), 1e-10 * hand.norm());
  }
}

TEST(HypoplasticSand, IsotropicStateHasLodeFactorOne) {
  const HypoplasticSand model(HochstettenSand());
  HypoplasticSand::Terms terms;
  std::string why;
  ASSERT_TRUE(
      model.EvaluateTerms(model.MakeState(AxisymmetricStressTensor(100.0, 0.0), 0.8), &terms, &why))
      << why;
  EXPECT_EQ(terms.lode_factor, 1.0);
  // Isotropic compression at unit rate: ṗ = f_b f_e (3 + a² − √3 a f_d)/√3 for ‖D‖ = 1.
  ModelRate rate;
  const Vector6 compression = -IdentityVoigt() / std::sqrt(3.0);
  ASSERT_TRUE(model.Rate(model.MakeState(AxisymmetricStressTensor(100.0, 0.0), 0.8), compression,
                         &rate, nullptr, &why));
  const double a = model.a();
  const double expected = terms.barotropy * terms.density *
                          (3.0 + a * a - std::sqrt(3.0) * a * terms.pyknotropy) / std::sqrt(3.0);
  EXPECT_NEAR(MeanStress(rate.stress_rate), expected, 1e-10 * expected);
}

TEST(HypoplasticSand, BauerLawGivesTheLimitVoidRatios) {
  const HypoplasticSand model(HochstettenSand());
  // 3p/h_s = 3e-4 at p = 100 kPa: exp(−(3e-4)^0.25) = 0.8766851.
  const HypoplasticSand::LimitVoidRatios at100 = model.LimitVoidRatiosAt(100.0);
  EXPECT_NEAR(at100.loosest, 1.05 * 0.8766851, 1e-6);
  EXPECT_NEAR(at100.critical, 0.95 * 0.8766851, 1e-6);
  EXPECT_NEAR(at100.densest, 0.55 * 0.8766851, 1e-6);
  for (double p : {1e-3, 1.0, 100.0, 1e4, 1e6}) {
    const HypoplasticSand::LimitVoidRatios limits = model.LimitVoidRatiosAt(p);
    const double bauer = std::exp(-std::pow(3.0 * p / 1e6, 0.25));
    EXPECT_NEAR(limits.loosest, 1.05 * bauer, 1e-14);
    EXPECT_NEAR(limits.critical / limits.densest, 0.95 / 0.55, 1e-13);  // same shape
    // p_e inverts e_i: OCR = 1 on the isotropic limit line, and VoidRatioForOcr agrees.
    EXPECT_NEAR(model.EquivalentPressure(limits.loosest), p, 1e-9 * p);
    EXPECT_NEAR(model.VoidRatioForOcr(p, 2.0), model.LimitVoidRatiosAt(2.0 * p).loosest, 1e-15);
    EXPECT_NEAR(model.EquivalentPressure(model.VoidRatioForOcr(p, 3.0)), 3.0 * p, 1e-9 * p);
  }
  EXPECT_EQ(model.EquivalentPressure(1.05), 0.0);  // at and above e_i0 no pressure
  EXPECT_EQ(model.EquivalentPressure(1.2), 0.0);
}

TEST(HypoplasticSand, DensityFactorsHaveTheirLimits) {
  const HypoplasticSand model(HochstettenSand());
  const double p = 250.0;
  const HypoplasticSand::LimitVoidRatios limits = model.LimitVoidRatiosAt(p);
  const Vector6 stress = AxisymmetricStressTensor(p, 0.2);
  HypoplasticSand::Terms terms;
  std::string why;
  // e = e_c: f_d = f_e = 1.
  ASSERT_TRUE(model.EvaluateTerms(model.MakeState(stress, limits.critical), &terms, &why)) << why;
  EXPECT_NEAR(terms.pyknotropy, 1.0, 1e-14);
  EXPECT_NEAR(terms.density, 1.0, 1e-14);
  // e = e_i: f_e = (e_c0/e_i0)^β, f_d = ((e_i0 − e_d0)/(e_c0 − e_d0))^α.
  ASSERT_TRUE(model.EvaluateTerms(model.MakeState(stress, limits.loosest), &terms, &why)) << why;
  EXPECT_NEAR(terms.density, std::pow(0.95 / 1.05, 1.5), 1e-14);
  EXPECT_NEAR(terms.pyknotropy, std::pow(0.5 / 0.4, 0.25), 1e-14);
  // e → e_d: f_d → 0 like (e − e_d)^α, f_e → (e_c0/e_d0)^β.
  const double gap = 1e-8 * (limits.critical - limits.densest);
  ASSERT_TRUE(model.EvaluateTerms(model.MakeState(stress, limits.densest + gap), &terms, &why))
      << why;
  EXPECT_NEAR(terms.pyknotropy, std::pow(1e-8, 0.25), 1e-10);
  EXPECT_NEAR(terms.density, std::pow(0.95 / 0.55, 1.5), 1e-6);
  // f_b: (h_s/n)(1 + e_i)/e_i (e_i0/e_c0)^β (3p/h_s)^{1−n}/denominator, any e.
  const double expected_barotropy = 1e6 / 0.25 * (1.0 + limits.loosest) / limits.loosest *
                                    std::pow(1.05 / 0.95, 1.5) * std::pow(3.0 * p / 1e6, 0.75) /
                                    model.barotropy_denominator();
  EXPECT_NEAR(terms.barotropy, expected_barotropy, 1e-10 * expected_barotropy);
  // At and below e_d the state is outside the domain, with the values named.
  EXPECT_FALSE(model.IsAdmissible(model.MakeState(stress, limits.densest), &why));
  EXPECT_NE(why.find("e_d"), std::string::npos) << why;
  ModelRate rate;
  EXPECT_FALSE(model.Rate(model.MakeState(stress, limits.densest - 0.01), GeneralStretching(),
                          &rate, nullptr, &why));
  EXPECT_NE(why.find("e_d"), std::string::npos) << why;
}

TEST(HypoplasticSand, CriticalStateIsStationaryOnTheMatsuokaNakaiCone) {
  // At f_d = 1 the isochoric stretching D ∝ −T̂* leaves T unchanged exactly
  // where ‖T̂*‖ = F/a, von Wolffersdorff's construction of the Matsuoka–Nakai
  // cone of φ_c: triaxial compression q/p = 6 sin φ/(3 − sin φ), extension
  // q/p = −6 sin φ/(3 + sin φ).
  const HypoplasticSand model(HochstettenSand());
  const double s = std::sin(model.critical_friction_angle());
  const double p = 400.0;
  const double e_c = model.LimitVoidRatiosAt(p).critical;
  for (double ratio : {6.0 * s / (3.0 - s), -6.0 * s / (3.0 + s)}) {
    const double psi = std::atan(std::sqrt(2.0) / 3.0 * ratio);
    const ModelState state = model.MakeState(AxisymmetricStressTensor(p, psi), e_c);
    HypoplasticSand::Terms terms;
    std::string why;
    ASSERT_TRUE(model.EvaluateTerms(state, &terms, &why)) << why;
    const Vector6 t_star = Deviator<double>(state.stress) / Trace<double>(state.stress);
    EXPECT_NEAR(FrobeniusNorm<double>(t_star), terms.lode_factor / model.a(), 1e-12) << ratio;
    ModelRate rate;
    ASSERT_TRUE(model.Rate(state, -t_star / FrobeniusNorm<double>(t_star), &rate, nullptr, &why));
    EXPECT_LT(rate.stress_rate.norm(), 1e-10 * p) << rate.stress_rate.transpose();
    // Slightly below the cone the same stretching still raises the obliquity.
    const ModelState inside = model.MakeState(AxisymmetricStressTensor(p, 0.97 * psi), e_c);
    ASSERT_TRUE(model.Rate(inside, -t_star / FrobeniusNorm<double>(t_star), &rate, nullptr, &why));
    EXPECT_GT(rate.stress_rate.norm(), 1e-3 * p);
  }
}

TEST(HypoplasticSand, IsotropicCompressionAtTheLoosestVoidRatioFollowsEi) {
  // f_b is defined so that e = e_i(p) is an exact solution of isotropic compression.
  const HypoplasticSand model(HochstettenSand());
  const ModelState initial = InitialStateFromOcr(model, 10.0, 0.0, 1.0);
  LoadingStage stage = LoadingStage::IsotropicToMeanStress(3e5, 1.0);
  stage.duration = 2.0;  // the stop at p = 3e5 kPa fires after ≈ 0.2 s
  stage.output_points = 200;
  const ElementTestResult result = ElementTest(model, TightOptions()).Run(initial, {stage});
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  ASSERT_GT(result.history.size(), 10u);
  double worst = 0.0;
  for (const ElementTestRecord& record : result.history) {
    const double p = RecordStress(record).mean();
    worst = std::max(worst, std::abs(record.void_ratio - model.LimitVoidRatiosAt(p).loosest));
    EXPECT_NEAR(record.ocr, 1.0, 1e-7);
    EXPECT_NEAR(RecordStress(record).deviator() / p, 0.0, 1e-12);
  }
  EXPECT_LT(worst, 1e-9);  // measured 9.7e-12 (e falls from 0.975 to 0.396)
  EXPECT_NEAR(RecordStress(result.history.back()).mean(), 3e5, 1e-6 * 3e5);
}

TEST(HypoplasticSand, IsotropicCompressionFromOtherDensitiesApproachesEi) {
  // Denser states (OCR > 1) converge to the e_i line, not to a line parallel
  // to it: |ln OCR| falls monotonically with p. Measured from p = 10 to
  // 3e5 kPa: OCR 3 → 1.029, 30 → 1.13. No test starts looser than e_i
  // (OCR < 1): there the model is outside its domain.
  const HypoplasticSand model(HochstettenSand());
  try {
    InitialStateFromOcr(model, 10.0, 0.0, 0.5);
    ADD_FAILURE() << "a start looser than e_i was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("above the loosest e_i"), std::string::npos)
        << error.what();
  }
  for (double ocr : {3.0, 30.0}) {
    const ModelState initial = InitialStateFromOcr(model, 10.0, 0.0, ocr);
    LoadingStage stage = LoadingStage::IsotropicToMeanStress(3e5, 1.0);
    stage.duration = 2.0;
    stage.output_points = 100;
    const ElementTestResult result = ElementTest(model, TightOptions()).Run(initial, {stage});
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    double previous = std::abs(std::log(ocr));
    for (const ElementTestRecord& record : result.history) {
      const double distance = std::abs(std::log(record.ocr));
      EXPECT_LE(distance, previous * (1.0 + 1e-12)) << "OCR " << ocr;
      previous = distance;
    }
    EXPECT_LT(previous, 0.05 * std::abs(std::log(ocr)))
        << "OCR " << ocr << " ends at " << result.history.back().ocr;
  }
}

TEST(HypoplasticSand, IsochoricShearReachesTheCriticalState) {
  // From loose and dense states, in triaxial compression and extension:
  // q/p → the Matsuoka–Nakai ratio of φ_c and p → the p at which e_c(p) = e.
  const HypoplasticSand model(HochstettenSand());
  const double s = std::sin(model.critical_friction_angle());
  AsymptoteSearchOptions options;
  for (double void_ratio : {0.85, 0.75}) {  // e_c(200 kPa) = 0.812
    for (double psi_epsilon : {kPi / 2, -kPi / 2}) {
      const ModelState initial = InitialStateFromVoidRatio(model, 200.0, 0.0, void_ratio);
      const IntegratedAsymptote asymptote =
          IntegrateAsymptote(model, initial, psi_epsilon, options);
      ASSERT_TRUE(asymptote.found) << asymptote.summary.Report();
      const double expected = psi_epsilon > 0 ? 6.0 * s / (3.0 - s) : -6.0 * s / (3.0 + s);
      // Measured within 1.3e-9 of the ratio and 1.7e-9 of e_c.
      EXPECT_NEAR(asymptote.state.stress_ratio, expected, 1e-7) << void_ratio;
      EXPECT_NEAR(asymptote.void_ratio, void_ratio, 1e-9);
      EXPECT_NEAR(model.LimitVoidRatiosAt(asymptote.mean_stress).critical, void_ratio, 1e-7)
          << "p = " << asymptote.mean_stress;
    }
  }
}

TEST(HypoplasticSand, DrainedTriaxialCompressionReachesTheCriticalState) {
  // Constant σ_r = 200 kPa from a loose and a dense state: the same critical
  // state, q/p = M, p = 3σ_r/(3 − M), e = e_c(p).
  const HypoplasticSand model(HochstettenSand());
  const double m = CriticalStateRatio(model.critical_friction_angle());
  for (double void_ratio : {0.85, 0.65}) {
    const ModelState initial = InitialStateFromVoidRatio(model, 200.0, 0.0, void_ratio);
    LoadingStage stage = LoadingStage::ConstantRadialStress(1.0, 20.0);
    stage.stops.push_back({StopKind::kAsymptote, 1e-7});
    const ElementTestResult result = ElementTest(model, TightOptions()).Run(initial, {stage});
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    ASSERT_EQ(result.summary.stages.back().integration.root_index, 0) << "no asymptote";
    const ElementTestRecord& last = result.history.back();
    const AxisymmetricStress stress = RecordStress(last);
    EXPECT_NEAR(stress.radial, 200.0, 1e-6);
    EXPECT_NEAR(stress.deviator() / stress.mean(), m, 1e-7) << void_ratio;  // measured 3.7e-9
    EXPECT_NEAR(stress.mean(), 600.0 / (3.0 - m), 1e-4);
    EXPECT_NEAR(last.void_ratio, model.LimitVoidRatiosAt(stress.mean()).critical, 1e-7);
  }
}

TEST(HypoplasticSand, DefaultIntegratorIsErkOrderFiveAsForTheClay) {
  // Chosen from the work-precision study on the sand's paths (bench/README.md).
  const IntegratorOptions defaults = DefaultIntegratorOptions(ModelKind::kHypoplasticSand);
  EXPECT_EQ(defaults.kind, IntegratorKind::kArkodeErk);
  EXPECT_EQ(defaults.arkode_order, 5);
  EXPECT_EQ(defaults.relative_tolerance, 1e-8);
  EXPECT_EQ(defaults.absolute_tolerance, 1e-8);
  // With the default an isochoric test of loose sand holds e and ends near e_c.
  const HypoplasticSand model(HochstettenSand());
  const ModelState initial = InitialStateFromVoidRatio(model, 200.0, 0.0, 0.85);
  LoadingStage stage = LoadingStage::Isochoric(1.0, 10.0);
  stage.stops.push_back({StopKind::kAsymptote, 1e-6});
  const ElementTestResult result = ElementTest(model, ElementTestOptions()).Run(initial, {stage});
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  EXPECT_NEAR(result.history.back().void_ratio, 0.85, 1e-8);
  EXPECT_NEAR(model.LimitVoidRatiosAt(RecordStress(result.history.back()).mean()).critical, 0.85,
              1e-5);
}

TEST(HypoplasticSand, RateIsPositivelyHomogeneousOfDegreeOneInD) {
  const HypoplasticSand model(HochstettenSand());
  const ModelState state = GeneralState(model);
  const Vector6 d = GeneralStretching();
  ModelRate base, scaled, reversed;
  std::string why;
  ASSERT_TRUE(model.Rate(state, d, &base, nullptr, &why)) << why;
  for (double factor : {1e-3, 0.1, 7.0, 1e4}) {
    ASSERT_TRUE(model.Rate(state, factor * d, &scaled, nullptr, &why)) << why;
    EXPECT_LT((scaled.stress_rate - factor * base.stress_rate).norm(),
              1e-13 * factor * base.stress_rate.norm())
        << factor;
    EXPECT_NEAR(scaled.void_ratio_rate, factor * base.void_ratio_rate,
                1e-14 * factor * std::abs(base.void_ratio_rate));
  }
  // Incrementally non-linear: reversing D does not reverse the rate.
  ASSERT_TRUE(model.Rate(state, -d, &reversed, nullptr, &why)) << why;
  EXPECT_GT((reversed.stress_rate + base.stress_rate).norm(), 1e-2 * base.stress_rate.norm());
}

TEST(HypoplasticSand, TangentMatchesFiniteDifferences) {
  const HypoplasticSand model(HochstettenSand());
  const ModelState state = GeneralState(model);
  const Vector6 d = GeneralStretching();
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

TEST(HypoplasticSand, JacobianMatchesFiniteDifferences) {
  const HypoplasticSand model(HochstettenSand());
  const Vector6 d = GeneralStretching();
  // A general state and a dense one near e_d, where f_d varies fastest.
  const ModelState general = GeneralState(model);
  ModelState dense = general;
  dense.void_ratio = model.LimitVoidRatiosAt(MeanStress(general.stress)).densest + 0.02;
  for (const ModelState& state : {general, dense}) {
    RateJacobian jacobian;
    std::string why;
    ASSERT_TRUE(model.Jacobian(state, d, &jacobian, &why)) << why;
    ASSERT_EQ(jacobian.d_state.rows(), 6);
    ASSERT_EQ(jacobian.d_state.cols(), 7);
    const double p = MeanStress(state.stress);
    for (int j = 0; j < 7; ++j) {
      ModelState plus = state, minus = state;
      const double h = j < 6 ? 1e-5 * p : 1e-7;
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
          << "e " << state.void_ratio << " column " << j << "\nFD " << column.transpose() << "\nAD "
          << jacobian.d_state.col(j).transpose();
    }
    Matrix6 tangent;
    ModelRate rate;
    ASSERT_TRUE(model.Rate(state, d, &rate, &tangent, &why));
    EXPECT_LT((tangent - jacobian.d_stretching).norm(), 1e-12 * tangent.norm());
  }
  // At an isotropic stress the Jacobian is finite (no derivative of sqrt at 0).
  RateJacobian jacobian;
  std::string why;
  EXPECT_TRUE(model.Jacobian(model.MakeState(AxisymmetricStressTensor(100.0, 0.0), 0.8), d,
                             &jacobian, &why))
      << why;
}

TEST(HypoplasticSand, RejectsTensileAndNonFiniteStates) {
  const HypoplasticSand model(HochstettenSand());
  ModelState state = model.MakeState(AxisymmetricStressTensor(100.0, 0.0), 0.8);
  std::string why;
  EXPECT_TRUE(model.IsAdmissible(state, &why)) << why;
  state.stress[0] = 10.0;  // tension in direction 1
  EXPECT_FALSE(model.IsAdmissible(state, &why));
  EXPECT_NE(why.find("tension"), std::string::npos) << why;
  ModelRate rate;
  EXPECT_FALSE(model.Rate(state, Vector6::Ones(), &rate, nullptr, &why));
  state = model.MakeState(AxisymmetricStressTensor(1e-12, 0.0), 0.8);
  EXPECT_FALSE(model.IsAdmissible(state, &why));
  EXPECT_NE(why.find("minimum"), std::string::npos) << why;
  state = model.MakeState(AxisymmetricStressTensor(100.0, 0.0), 0.8);
  state.stress[4] = NAN;
  EXPECT_FALSE(model.IsAdmissible(state, &why));
  EXPECT_NE(why.find("finite"), std::string::npos) << why;
}

TEST(HypoplasticSand, HasNoInternalVariablesAndDoesNotRescale) {
  const HypoplasticSand model(HochstettenSand());
  EXPECT_EQ(model.num_internal(), 0);
  Vector6 codes;
  Eigen::VectorXd internal_codes;
  model.SignConstraints(&codes, &internal_codes);
  EXPECT_EQ(codes.head<3>(), Vector6::Constant(-2).head<3>());
  EXPECT_EQ(codes.tail<3>(), Vector6::Zero().tail<3>());
  EXPECT_EQ(internal_codes.size(), 0);
  ModelState state = model.MakeState(AxisymmetricStressTensor(100.0, 0.1), 0.8);
  const ModelState before = state;
  EXPECT_FALSE(model.ScaleState(10.0, &state));
  EXPECT_EQ(state.stress, before.stress);
  EXPECT_NE(model.Describe().find("h_s=1e+06 kPa"), std::string::npos) << model.Describe();
}

}  // namespace
}  // namespace granasym
