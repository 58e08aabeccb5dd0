// The calibrated parameters of a model, from its traits.
#include "calibration/model_parameters.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"

namespace granasym::calibration {

namespace {

void CheckSize(ModelKind kind, const std::vector<double>& values) {
  GRANASYM_CHECK(values.size() == Traits(kind).parameters.size())
      << values.size() << " values for the parameters of " << ToString(kind);
}

}  // namespace

ModelParameters ModelParameters::Defaults(ModelKind kind) {
  ModelParameters parameters;
  parameters.kind_ = kind;
  for (const FittedParameter& p : Traits(kind).parameters) {
    parameters.specs_.push_back({p.traits.key, p.traits.symbol, p.traits.unit, p.traits.description,
                                 p.typical, p.lower, p.upper, true, p.traits.range});
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
  CheckSize(kind, values);
  return Traits(kind).make(values, why);
}

std::string ModelTomlBlock(ModelKind kind, const std::vector<double>& values) {
  CheckSize(kind, values);
  std::string s = fmt::format("[model]\nkind = \"{}\"\n", ToString(kind));
  const std::vector<FittedParameter>& parameters = Traits(kind).parameters;
  for (size_t i = 0; i < parameters.size(); ++i) {
    s += fmt::format("{} = {:.10g}\n", parameters[i].traits.key, values[i]);
  }
  return s;
}

std::vector<ExportedParameters> ExportOrders(ModelKind kind, const std::vector<double>& values) {
  CheckSize(kind, values);
  return Traits(kind).export_orders(values);
}

}  // namespace granasym::calibration
