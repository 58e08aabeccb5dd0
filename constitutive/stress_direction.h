// The stress direction terms both hypoplastic models share (Mašín 2005 and
// von Wolffersdorff 1996, SPEC §6.1 and §6.3), written once for double and the
// automatic-differentiation scalar: T̂ = T/tr T, T̂* = T̂ − 1/3 and the
// Matsuoka–Nakai factor
//   F = sqrt(tan²ψ/8 + (2 − tan²ψ)/(2 + √2 tanψ cos3θ)) − tanψ/(2√2),
//   tanψ = √3 ‖T̂*‖, cos3θ = −√6 tr(T̂*³)/(T̂*:T̂*)^{3/2}.
#pragma once

#include <cmath>
#include <string>

#include "constitutive/autodiff.h"
#include "constitutive/voigt.h"

namespace granasym {

template <typename S>
struct StressDirection {
  Vec6<S> t_hat;   // T̂
  Vec6<S> t_star;  // T̂*
  S lode_factor;   // F
};

// False, with the reason, where F is not defined (stress obliquity outside the
// Matsuoka–Nakai cone's domain).
template <typename S>
bool ComputeStressDirection(const Vec6<S>& t, StressDirection<S>* out, std::string* why) {
  using std::sqrt;
  const double sqrt2 = std::sqrt(2.0);
  const double sqrt6 = std::sqrt(6.0);
  auto fail = [why](const char* message) {
    if (why != nullptr) *why = message;
    return false;
  };
  out->t_hat = t / Trace(t);
  out->t_star = out->t_hat;
  for (int i = 0; i < 3; ++i) out->t_star[i] -= 1.0 / 3.0;
  const S t_star2 = Contract(out->t_star, out->t_star);
  // At T̂* = 0 (isotropic stress) cos 3θ is undefined (SPEC takes −1) and
  // irrelevant: tanψ = 0 and F = 1, kept constant so that no derivative of
  // sqrt passes through 0.
  S tan_psi(0.0);
  S cos3theta(-1.0);
  if (autodiff::Value(t_star2) > 1e-28) {
    tan_psi = std::sqrt(3.0) * sqrt(t_star2);
    cos3theta = -sqrt6 * Contract(Square(out->t_star), out->t_star) / (t_star2 * sqrt(t_star2));
    if (autodiff::Value(cos3theta) > 1.0) cos3theta = S(1.0);
    if (autodiff::Value(cos3theta) < -1.0) cos3theta = S(-1.0);
  }
  const S lode_denominator = 2.0 + sqrt2 * tan_psi * cos3theta;
  if (!(autodiff::Value(lode_denominator) > 0)) {
    return fail("stress obliquity outside the model's domain (2 + √2 tanψ cos3θ ≤ 0)");
  }
  const S radicand = tan_psi * tan_psi / 8.0 + (2.0 - tan_psi * tan_psi) / lode_denominator;
  if (!(autodiff::Value(radicand) > 0)) {
    return fail("stress obliquity outside the model's domain (F is not real)");
  }
  out->lode_factor = sqrt(radicand) - tan_psi / (2.0 * sqrt2);
  if (!(autodiff::Value(out->lode_factor) > 0)) {
    return fail("stress obliquity outside the model's domain (F ≤ 0)");
  }
  return true;
}

}  // namespace granasym
