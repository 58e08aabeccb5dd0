// Integrators: options, convergence order, root location, agreement on a
// hypoplastic path.
#include "constitutive/integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "constitutive/element_driver.h"
#include "tests/common/enum_spellings.h"
#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

// y1' = y2, y2' = −y1 (harmonic oscillator) with the root y1 = 0.5.
class Oscillator : public OdeSystem {
 public:
  int dimension() const override { return 2; }
  void ComponentScales(double* scale) const override { scale[0] = scale[1] = 1.0; }
  bool Rhs(double, const double* y, double* y_dot) override {
    y_dot[0] = y[1];
    y_dot[1] = -y[0];
    return true;
  }
  bool has_jacobian() const override { return true; }
  bool Jacobian(double, const double*, double* j) override {
    j[0] = 0;   // (0,0)
    j[1] = -1;  // (1,0)
    j[2] = 1;   // (0,1)
    j[3] = 0;   // (1,1)
    return true;
  }
  int num_roots() const override { return with_root_ ? 1 : 0; }
  bool Roots(double, const double* y, double* g) override {
    g[0] = y[0] - 0.5;
    return true;
  }
  const std::string& last_failure() const override { return failure_; }
  bool with_root_ = false;

 private:
  std::string failure_;
};

double FinalError(const IntegratorOptions& options) {
  Oscillator oscillator;
  double y[2] = {0.0, 1.0};
  const IntegrationSummary summary =
      Integrator::Create(options)->Integrate(oscillator, 0.0, 1.0, y, {}, nullptr);
  EXPECT_TRUE(summary.success()) << summary.Report();
  return std::hypot(y[0] - std::sin(1.0), y[1] - std::cos(1.0));
}

TEST(IntegratorOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(IntegratorOptions().IsValid(&why)) << why;
  IntegratorOptions bad;
  bad.relative_tolerance = 0.0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("relative_tolerance"), std::string::npos);
}

TEST(Integrator, NamesRoundTrip) {
  for (IntegratorKind kind : AllIntegratorKinds()) {
    IntegratorKind parsed;
    ASSERT_TRUE(FromString(ToString(kind), &parsed));
    EXPECT_EQ(parsed, kind);
  }
  IntegratorKind unused;
  EXPECT_FALSE(FromString("euler", &unused));
}

// Test files, HDF5 attributes and the benchmark scripts use these spellings.
TEST(Integrator, NamesAreSpelledAsInFilesAndResults) {
  ExpectSpellings<IntegratorKind>({{IntegratorKind::kCvodeBdf, "cvode_bdf"},
                                   {IntegratorKind::kCvodeAdams, "cvode_adams"},
                                   {IntegratorKind::kArkodeErk, "arkode_erk"},
                                   {IntegratorKind::kArkodeDirk, "arkode_dirk"},
                                   {IntegratorKind::kRkf23, "rkf23"}});
  EXPECT_EQ(AllIntegratorKinds(), EnumValues<IntegratorKind>());
  ExpectSpellings<JacobianKind>(
      {{JacobianKind::kExact, "exact"}, {JacobianKind::kFiniteDifference, "finite_difference"}});
  ExpectSpellings<TerminationType>({{TerminationType::kReachedEnd, "reached_end"},
                                    {TerminationType::kRootFound, "root_found"},
                                    {TerminationType::kFailure, "failure"},
                                    {TerminationType::kNotRun, "not_run"}});
}

struct OrderCase {
  IntegratorKind kind;
  int order;  // method order requested
  double expected;
};

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ConvergenceOrder, FixedStepErrorsShrinkAtTheMethodOrder) {
  const OrderCase c = GetParam();
  IntegratorOptions options;
  options.kind = c.kind;
  options.arkode_order = c.order;
  options.cvode_max_order = c.order;
  options.fixed_step = 1.0 / 20;
  const double coarse = FinalError(options);
  options.fixed_step = 1.0 / 40;
  const double fine = FinalError(options);
  const double observed = std::log2(coarse / fine);
  EXPECT_NEAR(observed, c.expected, 0.35)
      << ToString(c.kind) << " errors " << coarse << " " << fine;
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, ConvergenceOrder,
                         ::testing::Values(OrderCase{IntegratorKind::kRkf23, 3, 3.0},
                                           OrderCase{IntegratorKind::kArkodeErk, 4, 4.0},
                                           OrderCase{IntegratorKind::kArkodeErk, 2, 2.0},
                                           OrderCase{IntegratorKind::kArkodeDirk, 3, 3.0},
                                           OrderCase{IntegratorKind::kCvodeBdf, 1, 1.0},
                                           OrderCase{IntegratorKind::kCvodeAdams, 1, 1.0}));

TEST(Integrator, AdaptiveErrorFollowsTheTolerance) {
  for (IntegratorKind kind : AllIntegratorKinds()) {
    IntegratorOptions options;
    options.kind = kind;
    options.relative_tolerance = 1e-4;
    options.absolute_tolerance = 1e-4;
    const double loose = FinalError(options);
    options.relative_tolerance = 1e-8;
    options.absolute_tolerance = 1e-8;
    const double tight = FinalError(options);
    EXPECT_LT(tight, 1e-5) << ToString(kind);
    EXPECT_LT(tight, loose) << ToString(kind);
  }
}

TEST(Integrator, StopsAtTheExactRootCrossing) {
  for (IntegratorKind kind : AllIntegratorKinds()) {
    IntegratorOptions options;
    options.kind = kind;
    options.relative_tolerance = 1e-9;
    options.absolute_tolerance = 1e-10;
    Oscillator oscillator;
    oscillator.with_root_ = true;
    double y[2] = {0.0, 1.0};
    const IntegrationSummary summary =
        Integrator::Create(options)->Integrate(oscillator, 0.0, 2.0, y, {}, nullptr);
    ASSERT_EQ(summary.termination, TerminationType::kRootFound) << ToString(kind);
    EXPECT_EQ(summary.root_index, 0);
    EXPECT_NEAR(summary.final_time, std::asin(0.5), 1e-7) << ToString(kind);
    EXPECT_NEAR(y[0], 0.5, 1e-7) << ToString(kind);
  }
}

TEST(Integrator, CallsTheObserverAtOutputTimes) {
  for (IntegratorKind kind : AllIntegratorKinds()) {
    IntegratorOptions options;
    options.kind = kind;
    Oscillator oscillator;
    double y[2] = {0.0, 1.0};
    std::vector<double> seen;
    Integrator::Create(options)->Integrate(oscillator, 0.0, 1.0, y, {0.25, 0.5, 0.75},
                                           [&](double t, const double* state) {
                                             seen.push_back(t);
                                             EXPECT_NEAR(state[0], std::sin(t), 1e-4);
                                           });
    ASSERT_EQ(seen.size(), 3u) << ToString(kind);
    EXPECT_DOUBLE_EQ(seen[1], 0.5);
  }
}

// All integrators follow the same hypoplastic path (drained triaxial from an
// overconsolidated state, with stress-controlled radial components).
TEST(Integrator, AllAgreeOnAHypoplasticDrainedTriaxialPath) {
  const HypoplasticClay model(testing_models::LondonClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 3.0);
  LoadingStage stage = LoadingStage::ConstantRadialStress(1.0, 0.15);
  auto run = [&](IntegratorKind kind, double tolerance) {
    ElementTestOptions options;
    options.integrator.kind = kind;
    options.integrator.relative_tolerance = tolerance;
    options.integrator.absolute_tolerance = tolerance * 1e-2;
    const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
    EXPECT_TRUE(result.summary.success()) << ToString(kind) << ": " << result.summary.Report();
    return result.final_state;
  };
  const ModelState reference = run(IntegratorKind::kCvodeBdf, 1e-12);
  EXPECT_NEAR(reference.stress[1], -100.0, 1e-9);  // radial stress held
  for (IntegratorKind kind : AllIntegratorKinds()) {
    for (JacobianKind jacobian : {JacobianKind::kExact, JacobianKind::kFiniteDifference}) {
      ElementTestOptions options;
      options.integrator.kind = kind;
      options.integrator.jacobian = jacobian;
      options.integrator.relative_tolerance = 1e-8;
      options.integrator.absolute_tolerance = 1e-10;
      const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
      ASSERT_TRUE(result.summary.success()) << result.summary.Report();
      const double difference =
          (result.final_state.stress - reference.stress).norm() / reference.stress.norm();
      EXPECT_LT(difference, 1e-6) << ToString(kind) << " " << ToString(jacobian);
      EXPECT_NEAR(result.final_state.void_ratio, reference.void_ratio, 1e-7) << ToString(kind);
    }
  }
}

}  // namespace
}  // namespace granasym

namespace granasym {
namespace {

// ERKStep cannot recover when a stage leaves the model's domain; on Cam clay
// isochoric shear from OCR 8 (softening, p_c falling) a stage reached p_c < 0
// and ARKODE ERK failed at every tolerance. It now restarts from the last
// accepted step (and every integrator rejects steps that break the sign
// constraints).
TEST(Integrator, ArkodeErkRecoversWhenAStageLeavesTheDomain) {
  const ModifiedCamClay model(testing_models::CamClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 8.0);
  const LoadingStage stage = LoadingStage::Isochoric(1.0, 0.3);
  ElementTestOptions reference_options;
  reference_options.integrator.kind = IntegratorKind::kCvodeBdf;
  reference_options.integrator.relative_tolerance = 1e-11;
  reference_options.integrator.absolute_tolerance = 1e-13;
  const ElementTestResult reference = ElementTest(model, reference_options).Run(initial, {stage});
  ASSERT_TRUE(reference.summary.success()) << reference.summary.Report();
  for (double tolerance : {1e-5, 1e-7}) {
    ElementTestOptions options;
    options.integrator.kind = IntegratorKind::kArkodeErk;
    options.integrator.arkode_order = 4;
    options.integrator.relative_tolerance = options.integrator.absolute_tolerance = tolerance;
    const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    EXPECT_LT((result.final_state.stress - reference.final_state.stress).norm() /
                  reference.final_state.stress.norm(),
              1e3 * tolerance);
  }
}

}  // namespace
}  // namespace granasym
