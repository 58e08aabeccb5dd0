#include "common/state_measures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace granasym {
namespace {

TEST(AxisymmetricRate, SpecWorkedExampleAtNinetyDegrees) {
  // SPEC §2: ψ_ε = 90°, ‖D‖ = 167 1/s gives ε̇_a = 136.355, ε̇_r = −68.177 1/s.
  const AxisymmetricRate rate = AxisymmetricRate::FromAngle(90.0 * kDegree, 167.0);
  EXPECT_NEAR(rate.axial, 136.355, 1e-3);
  EXPECT_NEAR(rate.radial, -68.177, 1e-3);
  EXPECT_NEAR(rate.volumetric(), 0.0, 1e-12);
}

TEST(AxisymmetricRate, AngleAndNormRoundTripOverTheWholeCircle) {
  for (double degrees = -180.0; degrees < 180.0; degrees += 7.5) {
    const AxisymmetricRate rate = AxisymmetricRate::FromAngle(degrees * kDegree, 3.0);
    EXPECT_NEAR(rate.norm(), 3.0, 1e-12);
    EXPECT_NEAR(std::remainder(rate.psi() - degrees * kDegree, 2 * kPi), 0.0, 1e-12) << degrees;
  }
}

TEST(AxisymmetricRate, IsotropicCompressionIsZeroAndExtensionIsOneEighty) {
  EXPECT_NEAR(AxisymmetricRate({1.0, 1.0}).psi(), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(AxisymmetricRate({-1.0, -1.0}).psi()), kPi, 1e-15);
}

TEST(AxisymmetricStress, ExtensionLimitWithZeroRadialStress) {
  // σ_r → 0 gives ψ_σ(d) = atan √2 = 54.74°.
  EXPECT_NEAR(AxisymmetricStress({100.0, 0.0}).psi() / kDegree, 54.7356, 1e-4);
}

TEST(AxisymmetricStress, TanPsiIsRootTwoThirdsOfStressRatio) {
  const AxisymmetricStress stress{300.0, 120.0};
  EXPECT_NEAR(std::tan(stress.psi()), std::sqrt(2.0) / 3.0 * stress.deviator() / stress.mean(),
              1e-14);
}

TEST(AxisymmetricStress, FromTensorAveragesTheTwoHorizontalComponents) {
  const AxisymmetricStress stress = AxisymmetricFromTensor({10, 4, 6, 1, 2, 3});
  EXPECT_DOUBLE_EQ(stress.axial, 10);
  EXPECT_DOUBLE_EQ(stress.radial, 5);
  EXPECT_DOUBLE_EQ(stress.mean(), 20.0 / 3.0);
}

TEST(SignConvention, FlipIsAnInvolutionAndTurnsCompressionPositive) {
  const SymTensor continuum{-100, -50, -50, 1, 0, -2};
  const SymTensor soil = FlipSign(continuum);
  EXPECT_DOUBLE_EQ(soil[0], 100);
  EXPECT_GT(AxisymmetricFromTensor(soil).mean(), 0);
  EXPECT_EQ(FlipSign(soil), continuum);
}

TEST(CriticalState, PsiSigmaFromFrictionAngle) {
  const double phi = 30.0 * kDegree;
  EXPECT_NEAR(CriticalStateRatio(phi), 1.2, 1e-12);
  EXPECT_NEAR(std::tan(CriticalStatePsiSigma(phi)), std::sqrt(2.0) / 3.0 * 1.2, 1e-12);
}

TEST(EquivalentPressure, LiesOnTheNcl) {
  const double n = 1.0, lambda = 0.05;
  const double e = std::exp(n - lambda * std::log(200.0)) - 1.0;
  EXPECT_NEAR(EquivalentPressure(e, n, lambda), 200.0, 1e-9);
}

}  // namespace
}  // namespace granasym
