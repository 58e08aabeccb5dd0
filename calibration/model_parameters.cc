// Parameter tables of the calibrated models and their export orders.
#include "calibration/model_parameters.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/hypoplastic_sand.h"
#include "constitutive/model_config.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym::calibration {

int NumParameters(ModelKind kind) {
  return kind == ModelKind::kHypoplasticSand ? static_cast<int>(kNumSandParameters)
                                             : static_cast<int>(kNumParameters);
}

ModelParameters ModelParameters::Defaults(ModelKind kind) {
  GRANASYM_CHECK(IsCalibrated(kind)) << "calibration does not fit " << ToString(kind);
  ModelParameters parameters;
  parameters.kind_ = kind;
  if (kind == ModelKind::kHypoplasticSand) {
    // Typical values (Herle & Gudehus 1999) and bounds wide enough for DEM
    // sphere packings (small compressibility: large h_s).
    parameters.specs_ = {
        {"phi_c_deg", "deg", "critical state friction angle", 30.0, 5.0, 50.0, true},
        {"h_s_kpa", "kPa", "granular hardness of Bauer's law", 1e5, 1e2, 1e9, true},
        {"n", "1", "exponent of Bauer's law", 0.4, 0.05, 0.95, true},
        {"e_d0", "1", "densest void ratio at p = 0", 0.5, 0.05, 3.0, true},
        {"e_c0", "1", "critical void ratio at p = 0", 0.8, 0.1, 4.0, true},
        {"e_i0", "1", "loosest void ratio at p = 0 (isotropic NCL)", 0.95, 0.1, 5.0, true},
        {"alpha", "1", "pyknotropy exponent of f_d", 0.15, 0.01, 1.0, true},
        {"beta", "1", "stiffness exponent of f_e", 1.0, 0.05, 5.0, true},
    };
    for (ParameterSpec& spec : parameters.specs_) spec.domain = ParameterRange(spec.name);
    return parameters;
  }
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
  for (ParameterSpec& spec : parameters.specs_) spec.domain = ParameterRange(spec.name);
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
  GRANASYM_CHECK(IsCalibrated(kind)) << "calibration does not fit " << ToString(kind);
  GRANASYM_CHECK(static_cast<int>(values.size()) == NumParameters(kind)) << values.size();
  if (kind == ModelKind::kHypoplasticSand) {
    HypoplasticSand::Parameters p;
    p.critical_friction_angle = values[kSandCriticalFrictionAngle] * kDegree;
    p.granular_hardness = values[kSandGranularHardness];
    p.compression_exponent = values[kSandExponent];
    p.densest_void_ratio0 = values[kSandDensestVoidRatio];
    p.critical_void_ratio0 = values[kSandCriticalVoidRatio];
    p.loosest_void_ratio0 = values[kSandLoosestVoidRatio];
    p.pyknotropy_exponent = values[kSandPyknotropyExponent];
    p.stiffness_exponent = values[kSandStiffnessExponent];
    for (double v : values) {
      if (!std::isfinite(v)) {
        *why = "a parameter is not finite";
        return nullptr;
      }
    }
    if (!p.IsValid(why)) return nullptr;
    return std::make_unique<HypoplasticSand>(p);
  }
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

std::string ModelTomlBlock(ModelKind kind, const std::vector<double>& values) {
  GRANASYM_CHECK(static_cast<int>(values.size()) == NumParameters(kind)) << values.size();
  std::string s = fmt::format("[model]\nkind = \"{}\"\n", ToString(kind));
  auto line = [&s](const char* key, double value) {
    s += fmt::format("{} = {:.10g}\n", key, value);
  };
  if (kind == ModelKind::kHypoplasticSand) {
    line("phi_c_deg", values[kSandCriticalFrictionAngle]);
    line("h_s_kpa", values[kSandGranularHardness]);
    line("n", values[kSandExponent]);
    line("e_d0", values[kSandDensestVoidRatio]);
    line("e_c0", values[kSandCriticalVoidRatio]);
    line("e_i0", values[kSandLoosestVoidRatio]);
    line("alpha", values[kSandPyknotropyExponent]);
    line("beta", values[kSandStiffnessExponent]);
    return s;
  }
  line("phi_c_deg", values[kCriticalFrictionAngle]);
  line("lambda_star", values[kLambdaStar]);
  line("kappa_star", values[kKappaStar]);
  line("n_intercept", values[kNIntercept]);
  line(kind == ModelKind::kHypoplasticClay ? "r" : "poisson_ratio", values[kShearParameter]);
  return s;
}

std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values) {
  GRANASYM_CHECK(static_cast<int>(values.size()) == NumParameters(kind)) << values.size();
  if (kind == ModelKind::kHypoplasticSand) {
    // The soilmodels.com UMAT / PLAXIS UDSM of sand hypoplasticity reads
    // φ_c, p_t, h_s, n, e_d0, e_c0, e_i0, α, β (then the intergranular strain).
    return {{"UMAT / PLAXIS UDSM sand hypoplasticity (von Wolffersdorff), parameters 1-9",
             {{"phi_c_deg", values[kSandCriticalFrictionAngle]},
              {"p_t_kpa", 0.0},
              {"h_s_kpa", values[kSandGranularHardness]},
              {"n", values[kSandExponent]},
              {"e_d0", values[kSandDensestVoidRatio]},
              {"e_c0", values[kSandCriticalVoidRatio]},
              {"e_i0", values[kSandLoosestVoidRatio]},
              {"alpha", values[kSandPyknotropyExponent]},
              {"beta", values[kSandStiffnessExponent]}}}};
  }
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
