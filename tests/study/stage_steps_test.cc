#include "study/stage_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "dem/rest_stage.h"
#include "dem/strain_path_stage.h"
#include "dem/triaxial_stage.h"

namespace granasym::study {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDt = 1e-7;

// 1000 spheres of 1 mm in a cell of solid fraction 0.4.
StageSampleScales Scales() {
  const std::vector<double> radii(1000, 0.5e-3);
  const double solid = 1000 * 4.0 / 3.0 * kPi * std::pow(0.5e-3, 3);
  return SampleScalesOf(radii, std::cbrt(solid / 0.4), dem::Material{}, kDt);
}

dem::Stage PathStage(double psi_deg, double rate, const dem::StopConditions& stop,
                     double inertial_number = 0) {
  auto spec = std::make_shared<dem::StrainPathStage>();
  spec->psi_epsilon_deg = psi_deg;
  spec->stretching_rate = rate;
  if (inertial_number > 0) {
    spec->rule = dem::RateRule::kInertial;
    spec->inertial.inertial_number = inertial_number;
    spec->inertial.min_mean_stress_kpa = 1.0;
  }
  dem::Stage stage;
  stage.name = "s";
  stage.spec = spec;
  stage.stop = stop;
  if (spec->path_kind()) stage.asymptote = dem::AsymptoteCriterion::For(*spec->path_kind());
  return stage;
}

TEST(StageSteps, TheSamplesScalesAreItsDiametersAndSolidFraction) {
  const StageSampleScales scales = Scales();
  EXPECT_NEAR(scales.generated_solid_fraction, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(scales.context.max_diameter, 1e-3);
  EXPECT_DOUBLE_EQ(scales.time_step, kDt);
}

TEST(StageSteps, AStrainCapAtAConstantRateIsExact) {
  dem::StopConditions stop;
  stop.strain_norm = 0.5;
  const StageSteps steps = EstimateStageSteps(PathStage(90, 200, stop), Scales(), 100);
  EXPECT_NEAR(steps.steps, 0.5 / (200 * kDt), 1e-6);
  EXPECT_FALSE(steps.at_most);
  EXPECT_EQ(steps.reason, "strain_norm");
  EXPECT_FALSE(steps.stress_every_step);
}

TEST(StageSteps, StrainTargetsOfAStrainPathFollowFromItsDirection) {
  // ψ_ε = 30°: ε̇_a = ‖D‖(cos ψ/√3 + sin ψ √(2/3)), ε̇_v = √3 ‖D‖ cos ψ.
  const double psi = 30 * kPi / 180;
  dem::StopConditions stop;
  stop.strain_norm = 2.0;
  stop.axial_strain = 0.1;
  const StageSteps axial = EstimateStageSteps(PathStage(30, 100, stop), Scales(), 100);
  const double per_norm = std::cos(psi) / std::sqrt(3.0) + std::sin(psi) * std::sqrt(2.0 / 3.0);
  EXPECT_NEAR(axial.strain, 0.1 / per_norm, 1e-12);
  EXPECT_EQ(axial.reason, "axial_strain");
  // A target the path moves away from is never reached: the cap ends it.
  stop.axial_strain.reset();
  stop.volumetric_strain = -0.05;
  const StageSteps away = EstimateStageSteps(PathStage(30, 100, stop), Scales(), 100);
  EXPECT_DOUBLE_EQ(away.strain, 2.0);
  stop.volumetric_strain = 0.05;
  const StageSteps toward = EstimateStageSteps(PathStage(30, 100, stop), Scales(), 100);
  EXPECT_NEAR(toward.strain, 0.05 / (std::sqrt(3.0) * std::cos(psi)), 1e-12);
}

TEST(StageSteps, ATriaxialAxialStrainIsExactAtItsAxialRate) {
  auto spec = std::make_shared<dem::TriaxialStage>();
  spec->axial_strain_rate = 40;
  spec->radial_stress_kpa = 100;
  dem::Stage stage;
  stage.spec = spec;
  stage.stop.axial_strain = 0.2;
  const StageSteps steps = EstimateStageSteps(stage, Scales(), 100);
  EXPECT_NEAR(steps.steps, 0.2 / (40 * kDt), 1e-6);
  EXPECT_TRUE(steps.stress_every_step);
  // With the asymptote: the shear transient and the detector's window first.
  stage.stop.axial_strain = 0.6;
  stage.stop.asymptote = true;
  stage.asymptote = dem::AsymptoteCriterion::For(dem::PathKind::kStressControlled);
  const StageSteps asymptote = EstimateStageSteps(stage, Scales(), 100);
  EXPECT_NEAR(asymptote.strain, kShearTransientStrain + stage.asymptote.window_strain, 1e-12);
  EXPECT_EQ(asymptote.reason, "asymptote");
}

// The loading law's volumetric strain at p (kPa) for a constant ‖D‖ and
// d_max = 1 mm, up to a constant: ln(φ_J − a I(p)) + C p/E.
double Compression(double p_kpa, double rate) {
  const double inertial_number = rate * 1e-3 * std::sqrt(2 * 2650.0 / (p_kpa * 1e3));
  return std::log(kJammedSolidFraction - kDilatancyCoefficient * inertial_number) +
         kContactCompliance * p_kpa * 1e3 / 500e6;
}

TEST(StageSteps, ALoadingPathCompressesToAMeanStress) {
  dem::StopConditions stop;
  stop.mean_stress_kpa = 2000;
  const StageSteps steps = EstimateStageSteps(PathStage(50, 167, stop), Scales(), 20);
  const double v = std::sqrt(3.0) * std::cos(50 * kPi / 180);
  EXPECT_NEAR(steps.strain, (Compression(2000, 167) - Compression(20, 167)) / v, 1e-12);
  EXPECT_NEAR(steps.steps, steps.strain / (167 * kDt), 1e-6);
  EXPECT_NEAR(steps.end_p_kpa, 2000, 1e-9);
  EXPECT_TRUE(steps.stress_every_step);
  EXPECT_EQ(steps.reason, "mean_stress_kpa");
}

TEST(StageSteps, AGeneratedSampleJamsFirstAtItsLooseRate) {
  dem::StopConditions stop;
  stop.mean_stress_kpa = 100;
  const StageSteps steps = EstimateStageSteps(PathStage(0, 167, stop), Scales(), 0);
  // At 167 1/s the grains bear 1 kPa in a flow of I = ‖D‖ d sqrt(2ρ/p),
  // at φ = φ_J − a I.
  const double inertial_number = 167 * 1e-3 * std::sqrt(2 * 2650.0 / 1e3);
  const double jam =
      std::log((kJammedSolidFraction - kDilatancyCoefficient * inertial_number) / 0.4) /
      std::sqrt(3.0);
  EXPECT_GT(jam, 0);
  EXPECT_NEAR(steps.loose_steps, jam / (167 * kDt), 1e-6);
  EXPECT_DOUBLE_EQ(steps.still_steps, 0);  // at 167 1/s the grains collide
  // Under the inertial rule the generated sample jams at the floor's rate,
  // too slow for its grains to collide: still steps, almost all of them.
  const StageSteps slow = EstimateStageSteps(PathStage(0, 5000, stop, 1e-3), Scales(), 0);
  const double floor_rate = 1e-3 * std::sqrt(1e3 / (2 * 2650.0)) / 1e-3;
  EXPECT_GT(slow.loose_steps, 0);
  EXPECT_NEAR(slow.still_steps, slow.loose_steps * (1 - floor_rate / kCollisionalStrainRate),
              1e-9 * slow.loose_steps);
  EXPECT_NEAR(
      steps.strain,
      jam + (Compression(100, 167) - Compression(kJammedMeanStressKpa, 167)) / std::sqrt(3.0),
      1e-12);
}

TEST(StageSteps, AnUnloadingIsElasticWithTheAffineModulus) {
  dem::StopConditions stop;
  stop.mean_stress_kpa = 200;
  const StageSteps steps = EstimateStageSteps(PathStage(180, 167, stop), Scales(), 1000);
  // Linear contacts: K = Z φ_J E/(6π).
  const double modulus = kIsostaticCoordination * kJammedSolidFraction * 500e6 / (6 * kPi);
  EXPECT_NEAR(steps.strain, 800e3 / (modulus * std::sqrt(3.0)), 1e-12);
}

TEST(StageSteps, InertialCompressionMatchesTheClosedFormIntegral) {
  // Under the inertial rule I is I*: the loading law is ε_v = C p/E + const,
  // so s = C (p − p0)/(E v), and with ‖D‖ = c √p, c = I*/(d √(2ρ)), the
  // steps are ∫ds/(c√p Δt) = 2C/(E v c Δt) (√p1 − √p0) (p in Pa).
  const double inertial = 1e-3, p0 = 20e3, p1 = 2000e3;
  dem::StopConditions stop;
  stop.mean_stress_kpa = p1 / 1e3;
  const StageSteps steps =
      EstimateStageSteps(PathStage(0, 1e5, stop, inertial), Scales(), p0 / 1e3);
  const double c = inertial / (1e-3 * std::sqrt(2 * 2650.0));
  const double v = std::sqrt(3.0);
  const double closed =
      2 * kContactCompliance / (500e6 * v * c * kDt) * (std::sqrt(p1) - std::sqrt(p0));
  EXPECT_NEAR(steps.steps, closed, 0.01 * closed);
  EXPECT_FALSE(steps.at_most);
  // Ten times the inertial number: a tenth of the steps.
  const StageSteps faster =
      EstimateStageSteps(PathStage(0, 1e5, stop, 10 * inertial), Scales(), p0 / 1e3);
  EXPECT_NEAR(faster.steps, steps.steps / 10, 1e-6 * steps.steps);
}

TEST(StageSteps, AStageThatMayLiquefyIsBoundedByItsCapAtTheFloorRate) {
  dem::StopConditions stop;
  stop.strain_norm = 1.0;
  stop.liquefied = true;
  const StageSteps steps = EstimateStageSteps(PathStage(95, 5000, stop, 1e-3), Scales(), 2000);
  const double floor_rate = 1e-3 * std::sqrt(1e3 / (2 * 2650.0)) / 1e-3;
  EXPECT_NEAR(steps.steps, 1.0 / (floor_rate * kDt), 1e-3 * steps.steps);
  EXPECT_TRUE(steps.at_most);
  EXPECT_NE(steps.reason.find("at most"), std::string::npos) << steps.reason;
  // At a constant rate: the cap at that rate.
  const StageSteps constant = EstimateStageSteps(PathStage(95, 167, stop), Scales(), 2000);
  EXPECT_NEAR(constant.steps, 1.0 / (167 * kDt), 1e-6);
  EXPECT_TRUE(constant.at_most);
}

TEST(StageSteps, AStageThatMayLiquefyEndsAtTheEarliestItsGasWindowAfterTheFirstGas) {
  const double floor_rate = 1e-3 * std::sqrt(1e3 / (2 * 2650.0)) / 1e-3;
  dem::StopConditions stop;
  stop.strain_norm = 1.0;
  stop.asymptote = true;
  stop.liquefied = true;
  stop.liquefied_strain = 0.02;
  // A dilating path unloads elastically (linear contacts: K = Z φ_J E/(6π))
  // to the extension detector's floor of p, a gas from there.
  const dem::Stage dilating = PathStage(95, 5000, stop, 1e-3);
  const StageSteps extension = EstimateStageSteps(dilating, Scales(), 2000);
  const double modulus = kIsostaticCoordination * kJammedSolidFraction * 500e6 / (6 * kPi);
  const double unloading = -std::sqrt(3.0) * std::cos(95 * kPi / 180);  // |ε̇_v|/‖D‖
  const double gas = (2000e3 - dilating.asymptote.floor_kpa * 1e3) / (modulus * unloading);
  EXPECT_TRUE(extension.at_most);
  EXPECT_NEAR(extension.earliest.strain, gas + 0.02, 1e-9);
  // Up to the gas at the rate of the modelled p, p = p0 − K|v|s, ‖D‖ = c √p
  // (c = floor_rate/√(1 kPa)): ∫ds/(c√p) = 2(√p0 − √p1)/(c K|v|); then the
  // window at the floor's rate.
  const double c = floor_rate / std::sqrt(1e3);
  const double unloading_seconds =
      2 * (std::sqrt(2000e3) - std::sqrt(0.5e3)) / (c * modulus * unloading);
  const double expected = unloading_seconds / kDt + 0.02 / (floor_rate * kDt);
  EXPECT_NEAR(extension.earliest.steps, expected, 1e-3 * expected);
  EXPECT_LT(extension.earliest.steps, extension.steps);
  // From below the floor: a gas at once.
  const StageSteps loose = EstimateStageSteps(dilating, Scales(), 0.2);
  EXPECT_NEAR(loose.earliest.strain, 0.02, 1e-12);

  // An isochoric path under the inertial rule may liquefy at once: its
  // window (the detector's, without liquefied_strain) at the floor's rate.
  stop.liquefied_strain.reset();
  const dem::Stage isochoric = PathStage(90, 5000, stop, 1e-3);
  const StageSteps shear = EstimateStageSteps(isochoric, Scales(), 100);
  EXPECT_NEAR(shear.strain, 1.0, 1e-12);  // the cap: the asymptote may come later
  EXPECT_EQ(shear.reason, "strain_norm (at most: it may liquefy earlier)");
  EXPECT_NEAR(shear.earliest.strain, isochoric.asymptote.window_strain, 1e-12);
  EXPECT_NEAR(shear.earliest.steps, isochoric.asymptote.window_strain / (floor_rate * kDt),
              1e-3 * shear.earliest.steps);
  // At a constant rate nothing says that p collapses: the earliest end is
  // the predicted asymptote, at the same rate.
  const StageSteps constant = EstimateStageSteps(PathStage(90, 167, stop), Scales(), 100);
  EXPECT_TRUE(constant.at_most);
  EXPECT_NEAR(constant.strain, 1.0, 1e-12);
  EXPECT_NEAR(constant.earliest.strain, kShearTransientStrain + isochoric.asymptote.window_strain,
              1e-12);
  EXPECT_NEAR(constant.earliest.steps, constant.earliest.strain / (167 * kDt), 1e-6);
  // A loading path never becomes a gas and has no predicted stop before its
  // cap here: the earliest end is the bound's.
  stop.asymptote = false;
  const StageSteps loading = EstimateStageSteps(PathStage(0, 5000, stop, 1e-3), Scales(), 100);
  EXPECT_TRUE(loading.at_most);
  EXPECT_DOUBLE_EQ(loading.earliest.strain, loading.strain);
  EXPECT_DOUBLE_EQ(loading.earliest.steps, loading.steps);
  EXPECT_DOUBLE_EQ(loading.earliest.loose_steps, loading.loose_steps);
  // A stage that cannot liquefy: the same figures.
  const StageSteps plain = EstimateStageSteps(PathStage(90, 167, dem::StopConditions{[] {
                                                          dem::StopConditions s;
                                                          s.strain_norm = 0.5;
                                                          return s;
                                                        }()}),
                                              Scales(), 100);
  EXPECT_FALSE(plain.at_most);
  EXPECT_DOUBLE_EQ(plain.earliest.steps, plain.steps);
}

TEST(StageSteps, AnIsochoricAsymptoteComesAfterTheTransientAndTheWindow) {
  dem::StopConditions stop;
  stop.strain_norm = 0.8;
  stop.asymptote = true;
  const dem::Stage stage = PathStage(90, 167, stop);
  const StageSteps steps = EstimateStageSteps(stage, Scales(), 100);
  EXPECT_NEAR(steps.strain, kShearTransientStrain + stage.asymptote.window_strain, 1e-12);
  EXPECT_DOUBLE_EQ(steps.end_p_kpa, 100);
}

TEST(StageSteps, StepsAndTimeBoundEveryStage) {
  dem::StopConditions stop;
  stop.strain_norm = 1.0;
  stop.steps = 1000;
  EXPECT_DOUBLE_EQ(EstimateStageSteps(PathStage(90, 167, stop), Scales(), 100).steps, 1000);
  auto rest = std::make_shared<dem::RestStage>();
  rest->mean_stress_kpa = 50;
  dem::Stage stage;
  stage.spec = rest;
  const StageSteps at_rest = EstimateStageSteps(stage, Scales(), 100);
  EXPECT_DOUBLE_EQ(at_rest.steps, 5000);
  EXPECT_DOUBLE_EQ(at_rest.end_p_kpa, 50);
  EXPECT_TRUE(at_rest.stress_every_step);
}

}  // namespace
}  // namespace granasym::study
