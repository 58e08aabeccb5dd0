// Symmetric second-order tensors as 6-vectors of tensor components in Voigt
// order 11, 22, 33, 12, 13, 23 (not engineering shear), and fourth-order
// tensors as the 6x6 matrices that map such a vector to another.
//
// Double contraction A:B = Σ_{i<3} A_i B_i + 2 Σ_{i≥3} A_i B_i. A fourth-order
// tensor 𝕃 with minor symmetries becomes the matrix M with (𝕃:D)_I = Σ_J M_IJ D_J,
// i.e. M_IJ = 𝕃_IJ w_J with w = (1,1,1,2,2,2); then M is also the Jacobian of
// the map D ↦ 𝕃:D with respect to the six stored components. Templated on
// the scalar so that the models can be differentiated automatically.
#pragma once

#include <cmath>

#include "common/state_measures.h"
#include "constitutive/eigen.h"

namespace granasym {

template <typename Scalar>
using Vec6 = Eigen::Matrix<Scalar, 6, 1>;
template <typename Scalar>
using Mat6 = Eigen::Matrix<Scalar, 6, 6>;
using Vector6 = Vec6<double>;
using Matrix6 = Mat6<double>;

// Second-order identity 1.
inline Vector6 IdentityVoigt() {
  Vector6 one;
  one << 1, 1, 1, 0, 0, 0;
  return one;
}

// Contraction weights (1,1,1,2,2,2).
inline Vector6 VoigtWeights() {
  Vector6 w;
  w << 1, 1, 1, 2, 2, 2;
  return w;
}

template <typename Scalar>
Scalar Trace(const Vec6<Scalar>& a) {
  return a[0] + a[1] + a[2];
}

// A:B.
template <typename Scalar>
Scalar Contract(const Vec6<Scalar>& a, const Vec6<Scalar>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

// ‖A‖ = sqrt(A:A); callers guard the derivative at A = 0.
template <typename Scalar>
Scalar FrobeniusNorm(const Vec6<Scalar>& a) {
  using std::sqrt;
  return sqrt(Contract(a, a));
}

// A·A.
template <typename Scalar>
Vec6<Scalar> Square(const Vec6<Scalar>& a) {
  Vec6<Scalar> s;
  s[0] = a[0] * a[0] + a[3] * a[3] + a[4] * a[4];
  s[1] = a[3] * a[3] + a[1] * a[1] + a[5] * a[5];
  s[2] = a[4] * a[4] + a[5] * a[5] + a[2] * a[2];
  s[3] = a[0] * a[3] + a[3] * a[1] + a[4] * a[5];
  s[4] = a[0] * a[4] + a[3] * a[5] + a[4] * a[2];
  s[5] = a[3] * a[4] + a[1] * a[5] + a[5] * a[2];
  return s;
}

template <typename Scalar>
Scalar Determinant(const Vec6<Scalar>& a) {
  return a[0] * (a[1] * a[2] - a[5] * a[5]) - a[3] * (a[3] * a[2] - a[5] * a[4]) +
         a[4] * (a[3] * a[5] - a[1] * a[4]);
}

// Deviator A − (tr A/3) 1.
template <typename Scalar>
Vec6<Scalar> Deviator(const Vec6<Scalar>& a) {
  Vec6<Scalar> d = a;
  const Scalar mean = Trace(a) / 3.0;
  for (int i = 0; i < 3; ++i) d[i] -= mean;
  return d;
}

// Matrix of the dyad A⊗B acting as (A⊗B):D = A (B:D).
template <typename Scalar>
Mat6<Scalar> DyadMatrix(const Vec6<Scalar>& a, const Vec6<Scalar>& b) {
  Vec6<Scalar> weighted = b;
  for (int i = 3; i < 6; ++i) weighted[i] *= 2.0;
  return a * weighted.transpose();
}

inline Vector6 ToVector(const SymTensor& tensor) {
  return Eigen::Map<const Vector6>(tensor.data());
}
inline SymTensor ToSymTensor(const Vector6& vector) {
  SymTensor tensor;
  for (int i = 0; i < 6; ++i) tensor[i] = vector[i];
  return tensor;
}

// Mean stress p = −tr T/3 of a tension-positive stress.
inline double MeanStress(const Vector6& stress) { return -Trace(stress) / 3.0; }
// Deviator stress q = sqrt(3/2 s:s).
inline double DeviatorStress(const Vector6& stress) {
  const Vector6 s = Deviator(stress);
  return std::sqrt(1.5 * Contract(s, s));
}

}  // namespace granasym
