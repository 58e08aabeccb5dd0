// Soil-mechanics measures shared by the DEM and the constitutive models
// (SPEC §1–§3): axisymmetric stress and strain-rate measures, the angles ψ_σ
// and ψ_ε of the Rendulic plane, and the sign convention between the
// continuum (tension positive) and the soil-mechanics (compression positive)
// forms. This is the one place where the sign convention is converted.
#pragma once

#include <array>

namespace granasym {

// Symmetric second-order tensor in Voigt order 11, 22, 33, 12, 13, 23.
using SymTensor = std::array<double, 6>;

// Tension-positive (continuum) <-> compression-positive (soil mechanics).
// The conversion is a sign flip of every component, in both directions.
SymTensor FlipSign(const SymTensor& tensor);

// Axisymmetric stress measures, compression positive, axis 1 vertical.
struct AxisymmetricStress {
  double axial = 0;                                             // σ_a = σ_11
  double radial = 0;                                            // σ_r = (σ_22 + σ_33)/2
  double mean() const { return (axial + 2.0 * radial) / 3.0; }  // p
  double deviator() const { return axial - radial; }            // q
  // ψ_σ = atan2(√2 (σ_a − σ_r), σ_a + 2σ_r) in radians.
  double psi() const;
};
AxisymmetricStress AxisymmetricFromTensor(const SymTensor& compression_positive_stress);

// Axisymmetric strain-rate measures, compression positive.
struct AxisymmetricRate {
  double axial = 0;                                              // ε̇_a
  double radial = 0;                                             // ε̇_r
  double volumetric() const { return axial + 2.0 * radial; }     // ε̇_v
  double shear() const { return 2.0 * (axial - radial) / 3.0; }  // ε̇_s
  double norm() const;                                           // ‖D‖ for diagonal D
  // ψ_ε = atan2(√2 (ε̇_a − ε̇_r), ε̇_a + 2ε̇_r) in radians.
  double psi() const;
  // The rates of direction ψ_ε (radians) and magnitude ‖D‖ (1/s) (SPEC §2).
  static AxisymmetricRate FromAngle(double psi_epsilon, double stretching_rate);
};

// Critical-state ψ_σ(c) for a critical friction angle φ_c (radians):
// tan ψ_σ = (√2/3) M, M = 6 sin φ_c/(3 − sin φ_c).
double CriticalStateRatio(double critical_friction_angle);  // M
double CriticalStatePsiSigma(double critical_friction_angle);

// The stress ratio q/p of a triaxial stress direction ψ_σ (radians):
// tan ψ_σ = (√2/3) q/p (SPEC §2).
double StressRatio(double psi_sigma);

// Hvorslev equivalent pressure on the NCL ln(1+e) = N − λ* ln(p/p_r) (SPEC §3).
double EquivalentPressure(double void_ratio, double n_intercept, double lambda_star,
                          double reference_pressure = 1.0);

// Inertial number I = ‖D‖ d sqrt(2 ρ_s / p) (paper Eq. 5; SI units).
double InertialNumber(double stretching_rate, double diameter, double solid_density,
                      double mean_stress);

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
constexpr double kKiloPascal = 1e3;  // Pa per kPa

}  // namespace granasym
