// The mixed-control driver: control modes, sign convention, stops, failures.
#include "constitutive/element_driver.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/common/enum_spellings.h"
#include "tests/constitutive/test_models.h"

namespace granasym {
namespace {

// Test files ([integration] method) and the HDF5 stage attributes ("stop")
// use these spellings.
TEST(ElementTest, NamesAreSpelledAsInFilesAndResults) {
  ExpectSpellings<ComponentControl>({{ComponentControl::kStretching, "stretching"},
                                     {ComponentControl::kStressRate, "stress_rate"}});
  ExpectSpellings<StopKind>({{StopKind::kMeanStress, "mean_stress"},
                             {StopKind::kAxialStrain, "axial_strain"},
                             {StopKind::kVolumetricStrain, "volumetric_strain"},
                             {StopKind::kShearStrain, "shear_strain"},
                             {StopKind::kStrainPath, "strain_path"},
                             {StopKind::kStressRatio, "stress_ratio"},
                             {StopKind::kAsymptote, "asymptote"}});
  ExpectSpellings<DriveMethod>({{DriveMethod::kRateIntegration, "rate_integration"},
                                {DriveMethod::kStressPoint, "stress_point"}});
}

TEST(ElementTest, AxisymmetricStressTensorHasTheRequestedPAndPsi) {
  const Vector6 t = AxisymmetricStressTensor(150.0, 0.3);
  const AxisymmetricStress s = AxisymmetricFromTensor(FlipSign(ToSymTensor(t)));
  EXPECT_NEAR(s.mean(), 150.0, 1e-12);
  EXPECT_NEAR(s.psi(), 0.3, 1e-14);
  EXPECT_LT(t[0], 0.0);  // tension positive inside: compression is negative
}

TEST(ElementTest, DefaultIntegratorDependsOnTheModel) {
  for (ModelKind kind : {ModelKind::kHypoplasticClay, ModelKind::kModifiedCamClay}) {
    const IntegratorOptions defaults = DefaultIntegratorOptions(kind);
    EXPECT_EQ(defaults.kind, IntegratorKind::kArkodeErk);
    EXPECT_EQ(defaults.arkode_order, 5);
    const double expected = kind == ModelKind::kModifiedCamClay ? 1e-9 : 1e-8;
    EXPECT_EQ(defaults.relative_tolerance, expected);
    EXPECT_EQ(defaults.absolute_tolerance, expected);
    std::string why;
    EXPECT_TRUE(defaults.IsValid(&why)) << why;
  }
  // Options left at their defaults take the model's tolerances: the same run
  // as with those tolerances given, and not the run at the other model's.
  const ElementTestOptions unset;
  std::string why;
  EXPECT_TRUE(unset.IsValid(&why)) << why;
  EXPECT_EQ(unset.integrator.relative_tolerance, 0.0);
  const ModifiedCamClay model(testing_models::CamClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 1.0);
  const std::vector<LoadingStage> stages = {LoadingStage::Isochoric(1.0, 0.2)};
  auto final_q = [&](const ElementTestOptions& options) {
    const ElementTestResult result = ElementTest(model, options).Run(initial, stages);
    EXPECT_TRUE(result.summary.success()) << result.summary.Report();
    return RecordStress(result.history.back()).deviator();
  };
  ElementTestOptions given;
  given.integrator = DefaultIntegratorOptions(ModelKind::kModifiedCamClay);
  ElementTestOptions hypoplastic_default;
  hypoplastic_default.integrator = DefaultIntegratorOptions(ModelKind::kHypoplasticClay);
  EXPECT_EQ(final_q(unset), final_q(given));
  EXPECT_NE(final_q(unset), final_q(hypoplastic_default));
}

TEST(ElementTest, OedometricAndIsochoricKinematicsAreHonoured) {
  const HypoplasticClay model(testing_models::LondonClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 1.5);
  for (const LoadingStage& stage :
       {LoadingStage::Oedometric(1.0, 0.1), LoadingStage::Isochoric(1.0, 0.1)}) {
    const ElementTestResult result = ElementTest(model, ElementTestOptions()).Run(initial, {stage});
    ASSERT_TRUE(result.summary.success()) << result.summary.Report();
    const ElementTestRecord& last = result.history.back();
    EXPECT_NEAR(last.strain[0], 0.1, 1e-12);  // compression positive axial strain
    const double radial = 0.5 * (last.strain[1] + last.strain[2]);
    EXPECT_NEAR(radial, stage.name == "oedometric" ? 0.0 : -0.05, 1e-12) << stage.name;
    if (stage.name == "isochoric") {
      EXPECT_NEAR(last.void_ratio, initial.void_ratio, 1e-12);
    }
  }
}

TEST(ElementTest, GeneralMixedControlHoldsShearAndLateralStresses) {
  const HypoplasticClay model(testing_models::LondonClay());
  ModelState initial = InitialStateFromOcr(model, 100.0, 0.1, 2.0);
  initial.stress[3] = -5.0;  // a shear stress to hold
  LoadingStage stage;
  stage.name = "3D mixed";
  stage.control = {ComponentControl::kStretching, ComponentControl::kStressRate,
                   ComponentControl::kStressRate, ComponentControl::kStressRate,
                   ComponentControl::kStretching, ComponentControl::kStretching};
  stage.rate = {1.0, 0.0, -20.0, 0.0, 0.0, 0.0};  // σ_33 unloads at 20 kPa/s
  stage.duration = 0.05;
  const ElementTestResult result = ElementTest(model, ElementTestOptions()).Run(initial, {stage});
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  const ElementTestRecord& last = result.history.back();
  EXPECT_NEAR(last.stress[1], -initial.stress[1], 1e-6);
  EXPECT_NEAR(last.stress[2], -initial.stress[2] - 20.0 * 0.05, 1e-6);
  EXPECT_NEAR(last.stress[3], 5.0, 1e-6);
  EXPECT_GT(std::abs(last.strain[3]), 1e-6);  // the held shear stress needs shear strain
}

TEST(ElementTest, StopsAtTheRequestedStressRatio) {
  const HypoplasticClay model(testing_models::LondonClay());
  const ModelState initial = InitialStateFromOcr(model, 100.0, 0.0, 1.0);
  LoadingStage stage = LoadingStage::ConstantRadialStress(1.0, 1.0);
  stage.stops.push_back({StopKind::kStressRatio, 0.5});
  const ElementTestResult result = ElementTest(model, ElementTestOptions()).Run(initial, {stage});
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  EXPECT_EQ(result.summary.stages[0].stop, "stress_ratio=0.5");
  const AxisymmetricStress s = RecordStress(result.history.back());
  EXPECT_NEAR(s.deviator() / s.mean(), 0.5, 1e-8);
}

TEST(ElementTest, ExtensionToTensionEndsInAReportedFailureWithFiniteRecords) {
  const HypoplasticClay model(testing_models::LondonClay());
  const ModelState initial = InitialStateFromOcr(model, 10.0, 0.0, 1.0);
  // A tensile request: σ_r prescribed to fall by 5 kPa/s through zero.
  LoadingStage stage;
  stage.control[1] = stage.control[2] = ComponentControl::kStressRate;
  stage.rate = {0.0, -5.0, -5.0, 0, 0, 0};
  stage.duration = 10.0;
  ElementTestOptions options;
  options.integrator.max_steps = 20000;
  const ElementTestResult result = ElementTest(model, options).Run(initial, {stage});
  EXPECT_FALSE(result.summary.success());
  EXPECT_FALSE(result.summary.message.empty());
  // The last valid state is compressive.
  EXPECT_GT(MeanStress(result.final_state.stress), 0.0);
  RecordProperty("failure", result.summary.message);
  for (const ElementTestRecord& record : result.history) {
    for (double value : record.stress) EXPECT_TRUE(std::isfinite(value));
    EXPECT_TRUE(std::isfinite(record.void_ratio));
  }
}

TEST(ElementTest, ASummaryStartsAsNotRun) {
  const ElementTestSummary summary;
  EXPECT_EQ(summary.termination, TerminationType::kNotRun);
  EXPECT_FALSE(summary.success());
}

}  // namespace
}  // namespace granasym
