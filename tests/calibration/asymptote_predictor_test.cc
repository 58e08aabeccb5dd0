// The calibration's asymptote predictions against the constitutive library:
// the hypoplastic inversion against AnalyticAsymptoteForStretching, the Cam
// clay closed form against integrated proportional stretching.
#include "calibration/asymptote_predictor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/model_parameters.h"
#include "common/state_measures.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/element_driver.h"
#include "constitutive/hypoplastic_clay.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {

TEST(AsymptotePredictor, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(PredictorOptions().IsValid(&why)) << why;
  PredictorOptions bad;
  bad.curve_points = 3;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("curve_points"), std::string::npos);
}

TEST(AsymptotePredictor, HypoplasticInversionMatchesTheConstitutiveLibrary) {
  const std::vector<double> truth = testing::LondonClay();
  std::string why;
  const auto model = MakeModel(ModelKind::kHypoplasticClay, truth, &why);
  ASSERT_TRUE(model) << why;
  AsymptotePredictor predictor(ModelKind::kHypoplasticClay, PredictorOptions());
  const std::vector<double> directions = {-40 * kDegree, 0.0,           30 * kDegree, 60 * kDegree,
                                          90 * kDegree,  105 * kDegree, 120 * kDegree};
  std::vector<Prediction> by_e, by_s;
  ASSERT_TRUE(predictor.Predict(truth, directions, {}, &by_e, &by_s, &why)) << why;
  for (size_t k = 0; k < directions.size(); ++k) {
    AsymptoticState state;
    ASSERT_TRUE(AnalyticAsymptoteForStretching(static_cast<const HypoplasticClay&>(*model),
                                               directions[k], &state, &why))
        << why;
    EXPECT_FALSE(by_e[k].clamped);
    EXPECT_NEAR(by_e[k].psi_sigma, state.psi_sigma, 1e-10) << directions[k] / kDegree;
    EXPECT_NEAR(by_e[k].ln_ocr, std::log(state.ocr), 1e-9) << directions[k] / kDegree;
  }
  // Isotropic: OCR 1; critical state: OCR 2 and ψ_σ of φ_c (SPEC §6.1).
  EXPECT_NEAR(by_e[1].ln_ocr, 0.0, 1e-9);
  EXPECT_NEAR(by_e[1].psi_sigma, 0.0, 1e-9);
  EXPECT_NEAR(by_e[4].ln_ocr, std::log(2.0), 1e-8);
  EXPECT_NEAR(by_e[4].psi_sigma, CriticalStatePsiSigma(truth[0] * kDegree), 1e-9);
}

TEST(AsymptotePredictor, CamClayClosedFormMatchesIntegratedAsymptotes) {
  const std::vector<double> truth = testing::CamClayTruth();
  PredictorOptions integrated;
  integrated.method = AsymptoteMethod::kIntegrated;
  AsymptotePredictor slow(ModelKind::kModifiedCamClay, integrated);
  AsymptotePredictor fast(ModelKind::kModifiedCamClay, PredictorOptions());
  const std::vector<double> directions = {0.0, 20 * kDegree, 45 * kDegree, 70 * kDegree,
                                          -20 * kDegree};
  std::vector<Prediction> a, b, unused;
  std::string why;
  ASSERT_TRUE(fast.Predict(truth, directions, {}, &a, &unused, &why)) << why;
  ASSERT_TRUE(slow.Predict(truth, directions, {}, &b, &unused, &why)) << why;
  for (size_t k = 0; k < directions.size(); ++k) {
    EXPECT_NEAR(a[k].psi_sigma, b[k].psi_sigma, 1e-5) << directions[k] / kDegree;
    EXPECT_NEAR(a[k].ln_ocr, b[k].ln_ocr, 1e-5) << directions[k] / kDegree;
  }
}

TEST(AsymptotePredictor, CamClayCriticalStateHasTheClosedFormOcr) {
  const std::vector<double> v = testing::CamClayTruth();
  AsymptotePredictor predictor(ModelKind::kModifiedCamClay, PredictorOptions());
  std::vector<Prediction> by_e, by_s;
  std::string why;
  ASSERT_TRUE(predictor.Predict(v, {90 * kDegree}, {}, &by_e, &by_s, &why)) << why;
  EXPECT_NEAR(by_e[0].psi_sigma, CriticalStatePsiSigma(v[0] * kDegree), 1e-10);
  EXPECT_NEAR(by_e[0].ln_ocr, (1 - v[2] / v[1]) * std::log(2.0), 1e-10);
}

TEST(AsymptotePredictor, RejectsInvalidParameters) {
  std::vector<double> v = testing::LondonClay();
  v[kKappaStar] = 0.2;  // κ* > λ*
  AsymptotePredictor predictor(ModelKind::kHypoplasticClay, PredictorOptions());
  std::vector<Prediction> by_e, by_s;
  std::string why;
  EXPECT_FALSE(predictor.Predict(v, {0.0}, {}, &by_e, &by_s, &why));
  EXPECT_NE(why.find("kappa_star"), std::string::npos) << why;
}

TEST(AsymptotePredictor, ClampsDirectionsOutsideTheModelRange) {
  AsymptotePredictor predictor(ModelKind::kHypoplasticClay, PredictorOptions());
  std::vector<Prediction> by_e, by_s;
  std::string why;
  ASSERT_TRUE(predictor.Predict(testing::LondonClay(), {179 * kDegree}, {}, &by_e, &by_s, &why));
  EXPECT_TRUE(by_e[0].clamped);
}

}  // namespace
}  // namespace granasym::calibration
