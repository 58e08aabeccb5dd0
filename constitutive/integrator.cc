// Integrator names, options, summaries and the factory.
#include "constitutive/integrator.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "constitutive/rkf23_integrator.h"
#include "constitutive/sundials_integrators.h"

namespace granasym {

std::vector<IntegratorKind> AllIntegratorKinds() { return EnumValues<IntegratorKind>(); }

bool IntegratorOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(relative_tolerance > 0 && relative_tolerance < 1)) {
    return fail(fmt::format("relative_tolerance = {} must be in (0, 1)", relative_tolerance));
  }
  if (!(absolute_tolerance > 0)) {
    return fail(fmt::format("absolute_tolerance = {} must be > 0", absolute_tolerance));
  }
  if (!(max_steps > 0)) return fail(fmt::format("max_steps = {} must be > 0", max_steps));
  if (!(initial_step >= 0))
    return fail(fmt::format("initial_step = {} must be >= 0", initial_step));
  if (!(max_step >= 0)) return fail(fmt::format("max_step = {} must be >= 0", max_step));
  if (!(fixed_step >= 0)) return fail(fmt::format("fixed_step = {} must be >= 0", fixed_step));
  if (kind == IntegratorKind::kArkodeErk && !(arkode_order >= 2 && arkode_order <= 8)) {
    return fail(fmt::format("arkode_order = {} must be in [2, 8] for arkode_erk", arkode_order));
  }
  if (kind == IntegratorKind::kArkodeDirk && !(arkode_order >= 2 && arkode_order <= 5)) {
    return fail(fmt::format("arkode_order = {} must be in [2, 5] for arkode_dirk", arkode_order));
  }
  const int max_cvode_order = kind == IntegratorKind::kCvodeAdams ? 12 : 5;
  if (!(cvode_max_order >= 1 && cvode_max_order <= max_cvode_order)) {
    return fail(
        fmt::format("cvode_max_order = {} must be in [1, {}]", cvode_max_order, max_cvode_order));
  }
  if (!(rkf23_min_step_fraction > 0 && rkf23_min_step_fraction < 1)) {
    return fail(
        fmt::format("rkf23_min_step_fraction = {} must be in (0, 1)", rkf23_min_step_fraction));
  }
  return true;
}

std::string IntegrationSummary::Report() const {
  std::string line = fmt::format(
      "{}: t = {:.6g}, {} steps ({} rejected), {} RHS, {} Jacobians, {} nonlinear iterations, "
      "{:.3g} s",
      ToString(termination), final_time, steps, rejected_steps, rhs_evaluations,
      jacobian_evaluations, nonlinear_iterations, wall_time_s);
  if (root_index >= 0) line += fmt::format(", root {}", root_index);
  if (!message.empty()) line += " — " + message;
  return line;
}

void IntegrationSummary::Accumulate(const IntegrationSummary& other) {
  steps += other.steps;
  rejected_steps += other.rejected_steps;
  rhs_evaluations += other.rhs_evaluations;
  jacobian_evaluations += other.jacobian_evaluations;
  nonlinear_iterations += other.nonlinear_iterations;
  nonlinear_failures += other.nonlinear_failures;
  wall_time_s += other.wall_time_s;
}

std::unique_ptr<Integrator> Integrator::Create(const IntegratorOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  switch (options.kind) {
    case IntegratorKind::kCvodeBdf:
    case IntegratorKind::kCvodeAdams:
      return std::make_unique<CvodeIntegrator>(options);
    case IntegratorKind::kArkodeErk:
    case IntegratorKind::kArkodeDirk:
      return std::make_unique<ArkodeIntegrator>(options);
    case IntegratorKind::kRkf23:
      return std::make_unique<Rkf23Integrator>(options);
  }
  GRANASYM_CHECK(false) << "unknown integrator kind";
  return nullptr;
}

}  // namespace granasym
