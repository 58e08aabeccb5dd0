// Helpers for forward automatic differentiation with Eigen's AutoDiffScalar:
// the models write their rate once, templated on the scalar, and obtain exact
// Jacobians (used for implicit integrators and checked against finite
// differences in the tests).
#pragma once

#include <cmath>
#include <string>

#include "constitutive/constitutive_model.h"
#include "constitutive/eigen.h"

namespace granasym {
namespace autodiff {

inline double Value(double x) { return x; }
template <typename Derivatives>
double Value(const Eigen::AutoDiffScalar<Derivatives>& x) {
  return x.value();
}

// A variable with value `value` that is the `index`-th independent direction.
template <int kSize>
Eigen::AutoDiffScalar<Eigen::Matrix<double, kSize, 1>> Variable(double value, int index) {
  return Eigen::AutoDiffScalar<Eigen::Matrix<double, kSize, 1>>(value, kSize, index);
}

// A constant of the same type (zero derivatives).
template <typename Scalar>
Scalar Constant(double value) {
  return Scalar(value);
}

// The scalar of rate laws without internal variables: derivatives with
// respect to the stress (6), ln(1+e) and the stretching (6).
using StateScalar = Eigen::AutoDiffScalar<Eigen::Matrix<double, 13, 1>>;

// RateJacobian of such a law from its templated code:
// rate_of(T, ln(1+e), D, &T̊, why) evaluated once in StateScalar.
template <typename RateOf>
bool StressRateJacobian(const ModelState& state, const Vector6& stretching, RateOf rate_of,
                        RateJacobian* jacobian, std::string* why) {
  constexpr int kSize = 13;
  Vec6<StateScalar> t, d;
  for (int i = 0; i < 6; ++i) {
    t[i] = Variable<kSize>(state.stress[i], i);
    d[i] = Variable<kSize>(stretching[i], 7 + i);
  }
  const StateScalar log_1pe = Variable<kSize>(std::log1p(state.void_ratio), 6);
  Vec6<StateScalar> rate;
  if (!rate_of(t, log_1pe, d, &rate, why)) return false;
  jacobian->d_state.resize(6, 7);
  jacobian->d_stretching.resize(6, 6);
  for (int i = 0; i < 6; ++i) {
    const auto& derivatives = rate[i].derivatives();
    jacobian->d_state.row(i) = derivatives.head<7>().transpose();
    jacobian->d_stretching.row(i) = derivatives.tail<6>().transpose();
  }
  if (!jacobian->d_state.allFinite() || !jacobian->d_stretching.allFinite()) {
    if (why != nullptr) *why = "Jacobian is not finite";
    return false;
  }
  return true;
}

}  // namespace autodiff
}  // namespace granasym
