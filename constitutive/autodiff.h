// Helpers for forward automatic differentiation with Eigen's AutoDiffScalar:
// the models write their rate once, templated on the scalar, and obtain exact
// Jacobians (used for implicit integrators and checked against finite
// differences in the tests).
#pragma once

#include <unsupported/Eigen/AutoDiff>

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

}  // namespace autodiff
}  // namespace granasym
