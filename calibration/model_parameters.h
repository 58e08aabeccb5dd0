// The parameters a calibration can fit, per model, with their units, default
// bounds and the orders in which Mašín's UMAT and PLAXIS UDSM inputs list them.
//
// The clay models share the first four: φ_c (deg), λ*, κ*, N (ln(1+e) on the NCL
// at p_r = 1 kPa); the fifth is r = K/G (hypoplastic clay) or ν (Modified Cam
// clay, Poisson-ratio elasticity, log-log form: SPEC §6.2). The sand model
// has its own eight: φ_c, h_s, n, e_d0, e_c0, e_i0, α, β (SPEC §6.3).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/config.h"
#include "constitutive/constitutive_model.h"

namespace granasym::calibration {

// Positions in the parameter vectors of the clay models.
enum ParameterIndex : int {
  kCriticalFrictionAngle = 0,  // φ_c (deg)
  kLambdaStar = 1,             // λ* (1)
  kKappaStar = 2,              // κ* (1)
  kNIntercept = 3,             // N (1)
  kShearParameter = 4,         // r (hypoplastic) or ν (Cam clay) (1)
  kNumParameters = 5,
};

// Positions in the parameter vector of the von Wolffersdorff sand model
// (SPEC §6.3; the order of the soilmodels.com UMAT without p_t).
enum SandParameterIndex : int {
  kSandCriticalFrictionAngle = 0,  // φ_c (deg)
  kSandGranularHardness = 1,       // h_s (kPa)
  kSandExponent = 2,               // n of Bauer's law
  kSandDensestVoidRatio = 3,       // e_d0
  kSandCriticalVoidRatio = 4,      // e_c0
  kSandLoosestVoidRatio = 5,       // e_i0
  kSandPyknotropyExponent = 6,     // α
  kSandStiffnessExponent = 7,      // β
  kNumSandParameters = 8,
};

// The length of the parameter vector of `kind`.
int NumParameters(ModelKind kind);

struct ParameterSpec {
  std::string name;   // config and HDF5 key, e.g. "lambda_star"
  std::string units;  // "deg" or "1"
  std::string description;
  double value = 0.0;  // starting value (free) or the fixed value
  double lower = 0.0;  // bounds of the fit (free parameters)
  double upper = 0.0;
  bool free = true;
  // Where the model is defined: every value, bound and fit stays inside
  // (an open end excludes its limit, e.g. phi_c in (0, 90) deg).
  Range domain;
};

class ModelParameters {
 public:
  // Names, units, typical values and bounds for `kind`; all free.
  static ModelParameters Defaults(ModelKind kind);

  ModelKind kind() const { return kind_; }
  const std::vector<ParameterSpec>& specs() const { return specs_; }
  std::vector<ParameterSpec>& mutable_specs() { return specs_; }
  // −1 when unknown.
  int Index(const std::string& name) const;
  std::vector<int> FreeIndices() const;
  std::vector<double> Values() const;
  // The full vector with the free entries replaced by `free_values`.
  std::vector<double> WithFree(const std::vector<double>& free_values) const;
  // Throws InputError (naming the parameter) unless lower < upper and the
  // value lies within the bounds for every free parameter.
  void Validate() const;

 private:
  ModelKind kind_ = ModelKind::kHypoplasticClay;
  std::vector<ParameterSpec> specs_;
};

// The models calibration fits: the hypoplastic clay and Modified Cam clay
// (their five parameters share one layout, ParameterIndex) and the
// von Wolffersdorff sand (SandParameterIndex).
inline bool IsCalibrated(ModelKind kind) {
  return kind == ModelKind::kHypoplasticClay || kind == ModelKind::kModifiedCamClay ||
         kind == ModelKind::kHypoplasticSand;
}
// Whether the model's NCL is the straight line ln(1+e) = N − λ* ln(p/p_r)
// with asymptotes parallel to it (the clay models), so that λ*, κ*, N exist.
inline bool HasLinearNcl(ModelKind kind) { return kind != ModelKind::kHypoplasticSand; }

// The constitutive model for a full parameter vector; nullptr with the reason
// when the combination is invalid (e.g. κ* ≥ λ*, α undefined).
std::unique_ptr<ConstitutiveModel> MakeModel(ModelKind kind, const std::vector<double>& values,
                                             std::string* why);

// The [model] table of `granasym model run` for a full parameter vector
// (constitutive/model_config.h), one `key = value` per line after "[model]".
std::string ModelTomlBlock(ModelKind kind, const std::vector<double>& values);

// Named values in the order of the external programs' inputs (names include units).
struct ExportedParameters {
  std::string program;  // e.g. "UMAT (Masin clay hypoplasticity, props 1-5)"
  std::vector<std::pair<std::string, double>> values;
};
std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values);

}  // namespace granasym::calibration
