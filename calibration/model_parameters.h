// The parameters a calibration fits, per model: the parameter vector of the
// model's traits (constitutive/model_traits.h: keys, units, valid ranges,
// typical values, default bounds and how the data determine each), with the
// user's choices of start values, bounds and fixed parameters.
//
// The clay models share the first four: φ_c (deg), λ*, κ*, N (ln(1+e) on the
// NCL at p_r = 1 kPa); the fifth is r = K/G (hypoplastic clay) or ν (Modified
// Cam clay, Poisson-ratio elasticity, log-log form: SPEC §6.2). The sand
// model has its own eight: φ_c, h_s, n, e_d0, e_c0, e_i0, α, β (SPEC §6.3).
// Their positions are ClayParameterIndex and SandParameterIndex.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/config.h"
#include "constitutive/constitutive_model.h"
#include "constitutive/model_traits.h"

namespace granasym::calibration {

struct ParameterSpec {
  std::string name;    // config and HDF5 key, e.g. "lambda_star"
  std::string symbol;  // for tables, e.g. "λ*"
  std::string units;   // "deg", "kPa" or "1"
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
  // The parameter vector of `kind`'s traits at its typical values and
  // default bounds; all free.
  static ModelParameters Defaults(ModelKind kind);

  ModelKind kind() const { return kind_; }
  const ModelTraits& traits() const { return Traits(kind_); }
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

// The constitutive model for a full parameter vector; nullptr with the reason
// when the combination is invalid (e.g. κ* ≥ λ*, α undefined).
std::unique_ptr<ConstitutiveModel> MakeModel(ModelKind kind, const std::vector<double>& values,
                                             std::string* why);

// The [model] table of `granasym model run` for a full parameter vector
// (constitutive/model_config.h), one `key = value` per line after "[model]".
std::string ModelTomlBlock(ModelKind kind, const std::vector<double>& values);

// The full parameter vector in the orders of other programs' inputs (Mašín's
// UMAT, PLAXIS): ModelTraits::export_orders.
std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values);

}  // namespace granasym::calibration
