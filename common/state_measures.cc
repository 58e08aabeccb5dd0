#include "common/state_measures.h"

#include <cmath>

namespace granasym {

SymTensor FlipSign(const SymTensor& tensor) {
  SymTensor flipped;
  for (int i = 0; i < 6; ++i) flipped[i] = -tensor[i];
  return flipped;
}

double AxisymmetricStress::psi() const {
  return std::atan2(std::sqrt(2.0) * (axial - radial), axial + 2.0 * radial);
}

AxisymmetricStress AxisymmetricFromTensor(const SymTensor& stress) {
  return {stress[0], 0.5 * (stress[1] + stress[2])};
}

double AxisymmetricRate::norm() const { return std::sqrt(axial * axial + 2.0 * radial * radial); }

double AxisymmetricRate::psi() const {
  return std::atan2(std::sqrt(2.0) * (axial - radial), axial + 2.0 * radial);
}

AxisymmetricRate AxisymmetricRate::FromAngle(double psi_epsilon, double stretching_rate) {
  const double c = std::cos(psi_epsilon);
  const double s = std::sin(psi_epsilon);
  return {stretching_rate * (c / std::sqrt(3.0) + s * std::sqrt(2.0 / 3.0)),
          stretching_rate * (c / std::sqrt(3.0) - s / std::sqrt(6.0))};
}

double CriticalStateRatio(double phi_c) {
  const double s = std::sin(phi_c);
  return 6.0 * s / (3.0 - s);
}

double CriticalStatePsiSigma(double phi_c) {
  return std::atan(std::sqrt(2.0) / 3.0 * CriticalStateRatio(phi_c));
}

double StressRatio(double psi_sigma) { return 3.0 / std::sqrt(2.0) * std::tan(psi_sigma); }

double EquivalentPressure(double void_ratio, double n_intercept, double lambda_star,
                          double reference_pressure) {
  return reference_pressure * std::exp((n_intercept - std::log1p(void_ratio)) / lambda_star);
}

double InertialNumber(double stretching_rate, double diameter, double solid_density,
                      double mean_stress) {
  return stretching_rate * diameter * std::sqrt(2.0 * solid_density / mean_stress);
}

}  // namespace granasym
