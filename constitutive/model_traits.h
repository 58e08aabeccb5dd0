// What each constitutive model states about itself, in one place: one table
// per model in model_traits.cc. For each parameter: the key of model files,
// calibration files and outputs, the symbol for tables, the unit, the valid
// range, a description and its role in calibration (where its start comes
// from, which data determine it, its typical value and default bounds). For
// each model: its other keys (alternative forms, optional settings), the form
// of its NCL, its default integrator tolerance, how a [model] table and a
// parameter vector make it, and the orders in which other programs list its
// parameters.
//
// `Traits(kind)` is the one lookup from a ModelKind; the model files
// (model_config.h), calibration (calibration/model_parameters.h and the
// rest) and the element-test driver iterate over these tables, and what a
// model does differently at run time is a virtual method of
// ConstitutiveModel.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/config.h"
#include "common/enum_names.h"
#include "constitutive/constitutive_model.h"

namespace granasym {

// Positions in the parameter vector of the clay models (hypoplastic clay and
// Modified Cam clay share them): φ_c (deg), λ*, κ*, N, and r = K/G
// (hypoplastic clay) or ν (Modified Cam clay, Poisson-ratio elasticity,
// log-log form: SPEC §6.2).
enum ClayParameterIndex : int {
  kCriticalFrictionAngle = 0,  // φ_c (deg)
  kLambdaStar = 1,             // λ* (1)
  kKappaStar = 2,              // κ* (1)
  kNIntercept = 3,             // N (1)
  kShearParameter = 4,         // r (hypoplastic) or ν (Cam clay) (1)
  kNumClayParameters = 5,
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

// Where calibration takes a parameter's starting value from
// (calibration/starting_values.h and ChooseParameters).
enum class ParameterStart {
  kTypical,
  kCslStressRatio,
  kNclSlope,
  kUnloadingSlope,
  kNclIntercept,
  kBauerNcl,
  kCslVoidRatio,
  kDensestFraction,
};
template <>
struct EnumNames<ParameterStart> {
  static constexpr EnumEntry<ParameterStart> kEntries[] = {
      {ParameterStart::kTypical, "typical", "its typical value"},
      {ParameterStart::kCslStressRatio, "csl_stress_ratio",
       "the mean stress ratio of the CSL states (paper Eq. 1 inverted)"},
      {ParameterStart::kNclSlope, "ncl_slope",
       "the slope of ln(1+e) against ln p over the NCL states (else the CSL states)"},
      {ParameterStart::kUnloadingSlope, "unloading_slope",
       "the slope of the unloading branches; lambda*/5 without them"},
      {ParameterStart::kNclIntercept, "ncl_intercept",
       "ln(1+e) at p_r of the straight line through the NCL states"},
      {ParameterStart::kBauerNcl, "bauer_ncl",
       "Bauer's e_i through the NCL's e and slope at the NCL states' mean p"},
      {ParameterStart::kCslVoidRatio, "csl_void_ratio",
       "e_i0 times the CSL states' mean e/e_i (else 1/1.15)"},
      {ParameterStart::kDensestFraction, "densest_fraction", "0.6 e_c0"},
  };
};

// Which data determine a parameter (calibration/calibration_problem.h,
// Unidentifiable): data without them cannot identify it whatever the fit.
enum class Identification {
  kAnyState,
  kTwoMeanStresses,
  kOffIsotropicAxis,
  kTwoOffAxisDirections,
  kJacobian,
};
template <>
struct EnumNames<Identification> {
  static constexpr EnumEntry<Identification> kEntries[] = {
      {Identification::kAnyState, "any_state", "any asymptotic state"},
      {Identification::kTwoMeanStresses, "two_mean_stresses",
       "asymptotic states at two or more mean stresses"},
      {Identification::kOffIsotropicAxis, "off_isotropic_axis",
       "states away from the isotropic axis (CSL, compression, extension or ASBS)"},
      {Identification::kTwoOffAxisDirections, "two_off_axis_directions",
       "non-isotropic states in two or more directions besides the critical state"},
      {Identification::kJacobian, "jacobian",
       "judged from the fit's Jacobian (the model is not homogeneous in p)"},
  };
};

// A key of a [model] table.
struct ParameterTraits {
  const char* key;     // in model and calibration files and outputs, e.g. "lambda_star"
  const char* symbol;  // for tables and figures, e.g. "λ*"
  const char* unit;    // "1", "deg" or "kPa"
  Range range;         // valid values; calibration's values and bounds stay inside
  const char* description;
  // Model files may leave it out: the model's default (its Parameters struct).
  bool optional = false;
};

// A parameter of the model's parameter vector: what calibration fits.
struct FittedParameter {
  ParameterTraits traits;
  ParameterStart start;
  Identification identified_by;
  double typical;       // the start when the data give none
  double lower, upper;  // default bounds of a fit (calibration_config.h)
};

// Named values in the order of another program's input (names include units).
struct ExportedParameters {
  std::string program;  // e.g. "UMAT (Masin clay hypoplasticity, props 1-5)"
  std::vector<std::pair<std::string, double>> values;
};

struct ModelTraits {
  ModelKind kind;
  const char* title;  // in prose: "hypoplastic clay"
  // The parameter vector, in the order of ClayParameterIndex or
  // SandParameterIndex: what calibration fits and model.toml lists.
  std::vector<FittedParameter> parameters;
  // The other keys of its [model] table: alternative forms and settings.
  std::vector<ParameterTraits> other_keys;
  // The isotropic NCL is the line ln(1+e) = N − λ* ln(p/p_r) and the model is
  // homogeneous in p: each ψ_ε has one asymptotic ψ_σ and OCR (a line parallel
  // to the NCL) and each stress direction its OCR on the asymptotic state
  // boundary surface (ConstitutiveModel::AsymptoteOfStressDirection). Else
  // (the sand: Bauer's curve e_i(p)) asymptotic states are compared at their
  // own p.
  bool linear_ncl;
  // OCR at the critical state, in words ("2"); empty when it changes with p.
  const char* critical_state_ocr;
  // rtol = atol of its default integrator, ARKODE ERK 5
  // (DefaultIntegratorOptions, constitutive/element_driver.h).
  double integrator_tolerance;
  // The model of a [model] table, its kind already read: InputError naming
  // the file, the key, the value and what is valid.
  std::unique_ptr<ConstitutiveModel> (*read)(const ConfigTable& table);
  // The model of a full parameter vector (units of the keys: deg, kPa);
  // nullptr with the reason when the values make no valid model.
  std::unique_ptr<ConstitutiveModel> (*make)(const std::vector<double>& values, std::string* why);
  // The parameter vector in the orders of other programs' inputs.
  std::vector<ExportedParameters> (*export_orders)(const std::vector<double>& values);
};

// The traits of `kind`: the one lookup from a ModelKind.
const ModelTraits& Traits(ModelKind kind);

// The models whose traits satisfy `predicate`, as "a, b or c" (for messages).
template <typename Predicate>
std::string ModelNamesWhere(Predicate predicate) {
  std::vector<std::string> names;
  for (ModelKind kind : EnumValues<ModelKind>()) {
    if (predicate(Traits(kind))) names.push_back(ToString(kind));
  }
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return text;
}

}  // namespace granasym
