// Parameter tables of the calibrated models and their export orders.
#include "calibration/model_parameters.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym::calibration {

ModelParameters ModelParameters::Defaults(ModelKind kind) {
  GRANASYM_CHECK(IsCalibrated(kind))
      << "calibration fits the clay models only, not " << ToString(kind);
  ModelParameters parameters;
  parameters.kind_ = kind;
  // Bounds wide enough for clays and for DEM sphere packings (small λ*).
  parameters.specs_ = {
      {"phi_c_deg", "deg", "critical state friction angle", 25.0, 5.0, 50.0, true},
      {"lambda_star", "1", "slope of the isotropic NCL in ln(1+e)-ln p", 0.1, 1e-3, 0.5, true},
      {"kappa_star", "1", "slope of isotropic unloading in ln(1+e)-ln p", 0.02, 1e-4, 0.2, true},
      {"n_intercept", "1", "ln(1+e) on the NCL at p_r = 1 kPa", 1.0, 0.05, 4.0, true},
  };
  if (kind == ModelKind::kHypoplasticClay) {
    parameters.specs_.push_back(
        {"r", "1", "bulk/shear stiffness ratio K/G on the NCL", 0.4, 0.01, 3.0, true});
  } else {
    parameters.specs_.push_back(
        {"poisson_ratio", "1", "Poisson ratio of the elastic law", 0.25, 0.0, 0.49, true});
  }
  return parameters;
}

int ModelParameters::Index(const std::string& name) const {
  for (size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<int> ModelParameters::FreeIndices() const {
  std::vector<int> indices;
  for (size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].free) indices.push_back(static_cast<int>(i));
  }
  return indices;
}

std::vector<double> ModelParameters::Values() const {
  std::vector<double> values;
  for (const ParameterSpec& spec : specs_) values.push_back(spec.value);
  return values;
}

std::vector<double> ModelParameters::WithFree(const std::vector<double>& free_values) const {
  std::vector<double> values = Values();
  const std::vector<int> free = FreeIndices();
  GRANASYM_CHECK(free.size() == free_values.size())
      << free_values.size() << " values for " << free.size() << " free parameters";
  for (size_t k = 0; k < free.size(); ++k) values[free[k]] = free_values[k];
  return values;
}

void ModelParameters::Validate() const {
  for (const ParameterSpec& spec : specs_) {
    if (!std::isfinite(spec.value)) {
      throw InputError(fmt::format("parameter {}: value {} is not finite", spec.name, spec.value));
    }
    if (!spec.free) continue;
    if (!(spec.lower < spec.upper)) {
      throw InputError(fmt::format("parameter {}: lower bound {} must be below upper bound {}",
                                   spec.name, spec.lower, spec.upper));
    }
    if (!(spec.value >= spec.lower && spec.value <= spec.upper)) {
      throw InputError(fmt::format("parameter {}: starting value {} outside the bounds [{}, {}]",
                                   spec.name, spec.value, spec.lower, spec.upper));
    }
  }
}

std::unique_ptr<ConstitutiveModel> MakeModel(ModelKind kind, const std::vector<double>& values,
                                             std::string* why) {
  GRANASYM_CHECK(values.size() == kNumParameters) << values.size();
  GRANASYM_CHECK(IsCalibrated(kind))
      << "calibration fits the clay models only, not " << ToString(kind);
  if (kind == ModelKind::kHypoplasticClay) {
    HypoplasticClay::Parameters p;
    p.critical_friction_angle = values[kCriticalFrictionAngle] * kDegree;
    p.lambda_star = values[kLambdaStar];
    p.kappa_star = values[kKappaStar];
    p.n_intercept = values[kNIntercept];
    p.bulk_shear_ratio = values[kShearParameter];
    if (!p.IsValid(why)) return nullptr;
    return std::make_unique<HypoplasticClay>(p);
  }
  ModifiedCamClay::Parameters p;
  const double phi = values[kCriticalFrictionAngle] * kDegree;
  if (!(phi > 0 && phi < 0.5 * kPi)) {
    *why = fmt::format("phi_c_deg = {} must be in (0, 90)", values[kCriticalFrictionAngle]);
    return nullptr;
  }
  p.critical_state_ratio = CriticalStateRatio(phi);
  p.lambda = values[kLambdaStar];
  p.kappa = values[kKappaStar];
  p.n_intercept = values[kNIntercept];
  p.poisson_ratio = values[kShearParameter];
  if (!p.IsValid(why)) return nullptr;
  return std::make_unique<ModifiedCamClay>(p);
}

std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values) {
  GRANASYM_CHECK(values.size() == kNumParameters) << values.size();
  const double phi = values[kCriticalFrictionAngle];
  const double lambda = values[kLambdaStar], kappa = values[kKappaStar];
  const double n = values[kNIntercept], fifth = values[kShearParameter];
  std::vector<ExportedParameters> orders;
  if (kind == ModelKind::kHypoplasticClay) {
    // Mašín's clay hypoplasticity UMAT (Abaqus, 2005 form) reads props 1-5 as
    // φ_c, λ*, κ*, N, r (then the intergranular-strain parameters, not fitted here).
    orders.push_back({"UMAT clay hypoplasticity (Masin 2005), props 1-5",
                      {{"phi_c_deg", phi},
                       {"lambda_star", lambda},
                       {"kappa_star", kappa},
                       {"N", n},
                       {"r", fifth}}});
    // The soilmodels.com UMAT/PLAXIS UDSM form puts the tensile shift p_t second.
    orders.push_back({"PLAXIS UDSM / soilmodels.com UMAT (p_t second), parameters 1-6",
                      {{"phi_c_deg", phi},
                       {"p_t_kpa", 0.0},
                       {"lambda_star", lambda},
                       {"kappa_star", kappa},
                       {"N", n},
                       {"r", fifth}}});
  } else {
    const double m = CriticalStateRatio(phi * kDegree);
    orders.push_back(
        {"Modified Cam clay (ln(1+e)-ln p form)",
         {{"M", m}, {"lambda_star", lambda}, {"kappa_star", kappa}, {"N", n}, {"nu", fifth}}});
    // PLAXIS' Modified Cam-Clay takes λ, κ of the e-ln p form; at the NCL
    // state with 1 + e = exp(N) (p = 1 kPa) they are λ*(1+e), κ*(1+e).
    orders.push_back({"PLAXIS Modified Cam-Clay (nu_ur, kappa, lambda, M at 1+e = exp N)",
                      {{"nu_ur", fifth},
                       {"kappa", kappa * std::exp(n)},
                       {"lambda", lambda * std::exp(n)},
                       {"M", m}}});
  }
  return orders;
}

}  // namespace granasym::calibration
