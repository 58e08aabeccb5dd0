// The parameters a calibration can fit, per model, with their units, default
// bounds and the orders in which Mašín's UMAT and PLAXIS UDSM inputs list them.
//
// Both models share the first four: φ_c (deg), λ*, κ*, N (ln(1+e) on the NCL
// at p_r = 1 kPa); the fifth is r = K/G (hypoplastic clay) or ν (Modified Cam
// clay, Poisson-ratio elasticity, log-log form: SPEC §6.2).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "constitutive/constitutive_model.h"

namespace granasym::calibration {

// Positions in every parameter vector of this library.
enum ParameterIndex : int {
  kCriticalFrictionAngle = 0,  // φ_c (deg)
  kLambdaStar = 1,             // λ* (1)
  kKappaStar = 2,              // κ* (1)
  kNIntercept = 3,             // N (1)
  kShearParameter = 4,         // r (hypoplastic) or ν (Cam clay) (1)
  kNumParameters = 5,
};

struct ParameterSpec {
  std::string name;   // config and HDF5 key, e.g. "lambda_star"
  std::string units;  // "deg" or "1"
  std::string description;
  double value = 0.0;  // starting value (free) or the fixed value
  double lower = 0.0;  // bounds of the fit (free parameters)
  double upper = 0.0;
  bool free = true;
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
// (their five parameters share one layout, see ModelParameters).
inline bool IsCalibrated(ModelKind kind) {
  return kind == ModelKind::kHypoplasticClay || kind == ModelKind::kModifiedCamClay;
}

// The constitutive model for a full parameter vector; nullptr with the reason
// when the combination is invalid (e.g. κ* ≥ λ*, α undefined).
std::unique_ptr<ConstitutiveModel> MakeModel(ModelKind kind, const std::vector<double>& values,
                                             std::string* why);

// Named values in the order of the external programs' inputs (names include units).
struct ExportedParameters {
  std::string program;  // e.g. "UMAT (Masin clay hypoplasticity, props 1-5)"
  std::vector<std::pair<std::string, double>> values;
};
std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values);

}  // namespace granasym::calibration
