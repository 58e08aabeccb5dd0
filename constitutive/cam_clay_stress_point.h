// Stress-point algorithms for Modified Cam clay: the state after a strain
// increment Δε (tension positive) and, where asked, the tangent dσ/dΔε.
//
// kModifiedEuler (Sloan, Abbo & Sheng 2001, Eng. Computations 18:121–154):
//   the elastic part is integrated exactly (K = p/κ*, G ∝ p or constant), the
//   yield-surface intersection is found by the Pegasus method, the elastoplastic
//   part by modified Euler substeps with local error control (relative stress
//   error ≤ tolerance) and a consistent drift correction back onto f = 0.
// kReturnMapping (implicit, Borja & Lee 1990 style): p = p_n exp(Δε_v^e/κ*),
//   s = s_n + 2G(p) Δe^e, p_c = p_{c,n} exp(Δε_v^p/(λ*−κ*)), Δε^p = Δλ ∂f/∂σ at
//   the end state and f = 0, solved by Newton with the exact Jacobian (automatic
//   differentiation); the consistent tangent comes from the same Jacobian.
// Both are exact on isotropic NC loading (the NCL) for any increment size.
#pragma once

#include <string>

#include "common/enum_names.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {

class CamClayStressPoint {
 public:
  enum class Method { kModifiedEuler, kReturnMapping };

  struct Options {
    Method method = Method::kReturnMapping;
    // Modified Euler: relative local error per substep (stress and p_c).
    double tolerance = 1e-6;
    // Modified Euler: largest number of substeps per increment.
    int max_substeps = 100000;
    // Return mapping: Newton stops at this scaled residual.
    double newton_tolerance = 1e-12;
    int max_iterations = 50;
    bool IsValid(std::string* why) const;
  };

  struct Summary {
    bool success = false;
    std::string message;
    bool plastic = false;
    int substeps = 0;
    int rejected_substeps = 0;
    int iterations = 0;
  };

  // `model` must outlive this object; the options must be valid.
  CamClayStressPoint(const ModifiedCamClay& model, const Options& options);

  // Updates `state` by the strain increment; `tangent` (optional) receives
  // dσ/dΔε: the consistent tangent (return mapping) or the continuum tangent at
  // the end state (modified Euler). On failure `state` is unchanged.
  Summary Update(const Vector6& strain_increment, ModelState* state, Matrix6* tangent) const;

  const Options& options() const { return options_; }

 private:
  Summary UpdateModifiedEuler(const Vector6& strain_increment, ModelState* state,
                              Matrix6* tangent) const;
  Summary UpdateReturnMapping(const Vector6& strain_increment, ModelState* state,
                              Matrix6* tangent) const;
  // Exact elastic state after the fraction `fraction` of the increment.
  ModelState ElasticPath(const ModelState& state, const Vector6& strain_increment,
                         double fraction) const;
  // Modified Euler's pieces. f/(M p_c)² at a state.
  double ScaledYield(const ModelState& state) const;
  // Consistent drift correction onto f = 0 (Sloan et al. 2001, Sec. 4), else
  // a normal correction of the stress; false when f stays off the surface.
  bool CorrectDrift(ModelState* state) const;
  // The elastic fraction α of an increment whose elastic trial leaves the
  // yield surface: 0 when loading from the surface, else the crossing
  // (after elastic unloading, the second one) by the Pegasus method.
  double ElasticFraction(const ModelState& current, const Vector6& strain_increment) const;
  // Modified Euler substeps with local error control over the elastoplastic
  // part of the increment, each followed by the drift correction; false
  // with the message in `summary` on failure.
  bool IntegratePlastic(const Vector6& plastic_increment, ModelState* current,
                        Summary* summary) const;

  const ModifiedCamClay& model_;
  Options options_;
};

template <>
struct EnumNames<CamClayStressPoint::Method> {
  static constexpr EnumEntry<CamClayStressPoint::Method> kEntries[] = {
      {CamClayStressPoint::Method::kModifiedEuler, "modified_euler",
       "Sloan's modified Euler with drift correction"},
      {CamClayStressPoint::Method::kReturnMapping, "return_mapping",
       "implicit return mapping with the consistent tangent"},
  };
};

}  // namespace granasym
