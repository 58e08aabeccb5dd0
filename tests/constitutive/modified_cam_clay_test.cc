// Modified Cam clay: NCL, CSL, OCR_c, the elastic line, Jacobians, and the
// agreement of the rate form with both stress-point algorithms.
#include "constitutive/modified_cam_clay.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/cam_clay_stress_point.h"
#include "constitutive/element_driver.h"
#include "tests/common/enum_spellings.h"
#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

using testing_models::CamClay;

ElementTestOptions RateOptions() {
  ElementTestOptions options;
  // BDF: the asymptote stop at 1e-8 needs a smooth interpolant near the CSL,
  // which ERK's dense output at this tolerance does not give.
  options.integrator.kind = IntegratorKind::kCvodeBdf;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-12;
  return options;
}

ElementTestOptions StressPointOptions(CamClayStressPoint::Method method, double increment) {
  ElementTestOptions options;
  options.method = DriveMethod::kStressPoint;
  options.stress_point.method = method;
  options.stress_point.tolerance = 1e-8;
  options.max_strain_increment = increment;
  return options;
}

std::vector<ElementTestOptions> AllDrives() {
  return {RateOptions(), StressPointOptions(CamClayStressPoint::Method::kModifiedEuler, 1e-2),
          StressPointOptions(CamClayStressPoint::Method::kReturnMapping, 1e-3)};
}

TEST(ModifiedCamClay, RejectsInvalidParameters) {
  std::string why;
  ModifiedCamClay::Parameters p = CamClay();
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.kappa = 0.2;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("kappa"), std::string::npos);
  p = CamClay();
  p.poisson_ratio = 0.5;
  EXPECT_FALSE(p.IsValid(&why));
}

// Model files ([model] form, [integration] stress_point) use these spellings.
TEST(ModifiedCamClay, NamesAreSpelledAsInFiles) {
  ExpectSpellings<ModifiedCamClay::CompressionForm>(
      {{ModifiedCamClay::CompressionForm::kLogLog, "log_log"},
       {ModifiedCamClay::CompressionForm::kSemiLog, "semi_log"}});
  ExpectSpellings<CamClayStressPoint::Method>(
      {{CamClayStressPoint::Method::kModifiedEuler, "modified_euler"},
       {CamClayStressPoint::Method::kReturnMapping, "return_mapping"}});
}

TEST(CamClayStressPointOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(CamClayStressPoint::Options().IsValid(&why)) << why;
}

TEST(ElementTestOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(ElementTestOptions().IsValid(&why)) << why;
}

TEST(ModifiedCamClay, IsotropicLoadingFollowsTheNclWithEveryDrive) {
  for (auto form :
       {ModifiedCamClay::CompressionForm::kLogLog, ModifiedCamClay::CompressionForm::kSemiLog}) {
    ModifiedCamClay::Parameters parameters = CamClay();
    parameters.form = form;
    if (form == ModifiedCamClay::CompressionForm::kSemiLog) {
      parameters.lambda = 0.2;
      parameters.kappa = 0.03;
      parameters.n_intercept = 2.8;  // e_N
    }
    const ModifiedCamClay model(parameters);
    for (const ElementTestOptions& options : AllDrives()) {
      const ModelState initial = InitialStateFromOcr(model, 40.0, 0.0, 1.0);
      LoadingStage stage = LoadingStage::IsotropicToMeanStress(600.0, 1.0);
      stage.duration = 2.0;
      const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
      ASSERT_TRUE(result.summary.success()) << result.summary.Report();
      const ElementTestRecord& last = result.history.back();
      const double p = RecordStress(last).mean();
      EXPECT_NEAR(p, 600.0, 1e-6) << ToString(options.method);
      const double volume = form == ModifiedCamClay::CompressionForm::kLogLog
                                ? std::log1p(last.void_ratio)
                                : last.void_ratio;
      EXPECT_NEAR(volume, parameters.n_intercept - parameters.lambda * std::log(p), 1e-6)
          << ToString(form) << " " << ToString(options.method) << " "
          << ToString(options.stress_point.method);
      EXPECT_NEAR(last.internal[0], p, 1e-5 * p);
      EXPECT_NEAR(last.ocr, 1.0, 1e-6);
    }
  }
}

TEST(ModifiedCamClay, DrainedAndUndrainedShearEndOnTheCslWithOcrC) {
  const ModifiedCamClay model(CamClay());
  const double ocr_c = std::pow(2.0, (CamClay().lambda - CamClay().kappa) / CamClay().lambda);
  for (bool drained : {true, false}) {
    const ModelState initial = InitialStateFromOcr(model, 200.0, 0.0, 1.0);
    LoadingStage stage =
        drained ? LoadingStage::ConstantRadialStress(1.0, 6.0) : LoadingStage::Isochoric(1.0, 6.0);
    stage.stops.push_back({StopKind::kAsymptote, 1e-8});
    const ElementTestResult result = ElementTest(model, RateOptions()).Run(initial, {stage});
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    ASSERT_EQ(result.summary.stages[0].integration.root_index, 0) << result.summary.Report();
    const AxisymmetricStress stress = RecordStress(result.history.back());
    EXPECT_NEAR(stress.deviator() / stress.mean(), CamClay().critical_state_ratio, 1e-6);
    EXPECT_NEAR(result.history.back().ocr, ocr_c, 1e-6);
    EXPECT_NEAR(result.history.back().internal[0], 2.0 * stress.mean(), 1e-5 * stress.mean());
  }
}

TEST(ModifiedCamClay, StatesStayOnTheElasticLineAndInsideTheYieldSurface) {
  const ModifiedCamClay model(CamClay());
  for (const ElementTestOptions& options : AllDrives()) {
    const ModelState initial = InitialStateFromOcr(model, 100.0, 0.1, 2.5);
    std::vector<LoadingStage> stages = {LoadingStage::ConstantRadialStress(1.0, 0.1),
                                        LoadingStage::Proportional(150 * kDegree, 1.0, 0.05),
                                        LoadingStage::Proportional(30 * kDegree, 1.0, 0.2)};
    const ElementTestResult result = ElementTest(model, options).Run(initial, stages);
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    for (const ElementTestRecord& record : result.history) {
      const double p = RecordStress(record).mean();
      EXPECT_NEAR(record.internal[0], model.PreconsolidationFromElasticLine(p, record.void_ratio),
                  2e-5 * record.internal[0]);
      const Vector6 stress = ToVector(FlipSign(record.stress));
      const double scale = std::pow(CamClay().critical_state_ratio * record.internal[0], 2);
      EXPECT_LE(model.YieldFunction(stress, record.internal[0]) / scale, 1e-6);
    }
  }
}

TEST(ModifiedCamClay, JacobianMatchesFiniteDifferencesOnTheYieldSurface) {
  const ModifiedCamClay model(CamClay());
  // A state on the yield surface: p_c = 150, p = 100, q from f = 0.
  const double q = CamClay().critical_state_ratio * std::sqrt(100.0 * 50.0);
  ModelState state;
  state.stress = AxisymmetricStressTensor(100.0, std::atan(std::sqrt(2.0) / 3.0 * q / 100.0));
  state.void_ratio = 0.8;
  state.internal = Eigen::VectorXd::Constant(1, 150.0);
  Vector6 d;
  d << -1.0, 0.3, 0.2, 0.05, 0.0, -0.02;
  RateJacobian jacobian;
  std::string why;
  ASSERT_TRUE(model.Jacobian(state, d, &jacobian, &why)) << why;
  auto rates = [&](const ModelState& s, const Vector6& stretching) {
    ModelRate rate;
    EXPECT_TRUE(model.Rate(s, stretching, &rate, nullptr, &why)) << why;
    Eigen::Matrix<double, 7, 1> out;
    out << rate.stress_rate, rate.internal_rate[0];
    return out;
  };
  for (int j = 0; j < 8; ++j) {
    ModelState plus = state, minus = state;
    const double h = j == 6 ? 1e-7 : 1e-5;
    if (j < 6) {
      plus.stress[j] += h;
      minus.stress[j] -= h;
    } else if (j == 6) {
      plus.void_ratio = std::expm1(std::log1p(state.void_ratio) + h);
      minus.void_ratio = std::expm1(std::log1p(state.void_ratio) - h);
    } else {
      plus.internal[0] += h;
      minus.internal[0] -= h;
    }
    const Eigen::Matrix<double, 7, 1> column = (rates(plus, d) - rates(minus, d)) / (2 * h);
    EXPECT_LT((column - jacobian.d_state.col(j)).norm(), 1e-5 * (1 + column.norm())) << j;
  }
  Matrix6 tangent;
  ModelRate rate;
  ASSERT_TRUE(model.Rate(state, d, &rate, &tangent, &why));
  EXPECT_LT((tangent - jacobian.d_stretching.topRows<6>()).norm(), 1e-10 * tangent.norm());
}

TEST(CamClayStressPoint, ReturnMappingTangentIsConsistent) {
  const ModifiedCamClay model(CamClay());
  CamClayStressPoint::Options options;
  const CamClayStressPoint update(model, options);
  const ModelState start = InitialStateFromOcr(model, 100.0, 0.2, 1.3);
  Vector6 increment;
  increment << -0.01, 0.004, 0.003, 0.001, 0.0, 0.002;
  ModelState end = start;
  Matrix6 tangent;
  const CamClayStressPoint::Summary summary = update.Update(increment, &end, &tangent);
  ASSERT_TRUE(summary.success) << summary.message;
  ASSERT_TRUE(summary.plastic);
  for (int j = 0; j < 6; ++j) {
    const double h = 1e-7;
    Vector6 plus = increment, minus = increment;
    plus[j] += h;
    minus[j] -= h;
    ModelState end_plus = start, end_minus = start;
    ASSERT_TRUE(update.Update(plus, &end_plus, nullptr).success);
    ASSERT_TRUE(update.Update(minus, &end_minus, nullptr).success);
    const Vector6 column = (end_plus.stress - end_minus.stress) / (2 * h);
    EXPECT_LT((column - tangent.col(j)).norm(), 1e-6 * tangent.norm()) << "column " << j;
  }
}

TEST(CamClayStressPoint, ReturnMappingConvergesAtFirstOrderAndModifiedEulerToItsTolerance) {
  const ModifiedCamClay model(CamClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 1.5);
  // Strain controlled, so that a strain increment follows the path exactly.
  LoadingStage stage = LoadingStage::Isochoric(1.0, 0.08);
  ElementTestOptions reference_options =
      StressPointOptions(CamClayStressPoint::Method::kModifiedEuler, 1e-3);
  reference_options.stress_point.tolerance = 1e-11;
  const ElementTestResult reference = ElementTest(model, reference_options).Run(initial, {stage});
  ASSERT_TRUE(reference.summary.success()) << reference.summary.Report();
  // The rate form (CVODE, drift-stabilised) follows the same path.
  const ElementTestResult rate = ElementTest(model, RateOptions()).Run(initial, {stage});
  ASSERT_TRUE(rate.summary.success()) << rate.summary.Report();
  EXPECT_LT((rate.final_state.stress - reference.final_state.stress).norm() /
                reference.final_state.stress.norm(),
            2e-5);
  auto error = [&](const ElementTestOptions& options) {
    const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
    EXPECT_TRUE(result.summary.success()) << result.summary.Report();
    return (result.final_state.stress - reference.final_state.stress).norm() /
           reference.final_state.stress.norm();
  };
  const double coarse = error(StressPointOptions(CamClayStressPoint::Method::kReturnMapping, 2e-3));
  const double fine = error(StressPointOptions(CamClayStressPoint::Method::kReturnMapping, 1e-3));
  EXPECT_LT(fine, 5e-3);
  EXPECT_NEAR(std::log2(coarse / fine), 1.0, 0.25) << coarse << " " << fine;
  const double euler = error(StressPointOptions(CamClayStressPoint::Method::kModifiedEuler, 1e-2));
  EXPECT_LT(euler, 1e-6);
}

TEST(CamClayStressPoint, FailureLeavesTheStateUnchanged) {
  const ModifiedCamClay model(CamClay());
  const CamClayStressPoint update(model, CamClayStressPoint::Options());
  ModelState state = InitialStateFromOcr(model, 100.0, 0.0, 1.0);
  const ModelState start = state;
  Vector6 increment = Vector6::Constant(std::nan(""));
  const CamClayStressPoint::Summary summary = update.Update(increment, &state, nullptr);
  EXPECT_FALSE(summary.success);
  EXPECT_FALSE(summary.message.empty());
  EXPECT_EQ(state.stress, start.stress);
}

TEST(ModifiedCamClay, InitialStateOutsideTheYieldSurfaceIsRejected) {
  const ModifiedCamClay model(CamClay());
  EXPECT_THROW(InitialStateFromOcr(model, 100.0, 0.4, 1.0), InputError);
  EXPECT_NO_THROW(InitialStateFromOcr(model, 100.0, 0.0, 1.0));
}

}  // namespace
}  // namespace granasym
