// Time integrators for the element-test ODE behind one interface: SUNDIALS
// CVODE (BDF + Newton + dense; Adams + fixed point), ARKODE (adaptive explicit
// RK; DIRK + Newton + dense) and the explicit Runge–Kutta–Fehlberg 2(3) with
// step control of Mašín's reference codes (SPEC §6.1). Targets are found by
// root finding: integration stops at the crossing of a root function.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "constitutive/ode_system.h"

namespace granasym {

enum class IntegratorKind { kCvodeBdf, kCvodeAdams, kArkodeErk, kArkodeDirk, kRkf23 };
template <>
struct EnumNames<IntegratorKind> {
  static constexpr EnumEntry<IntegratorKind> kEntries[] = {
      {IntegratorKind::kCvodeBdf, "cvode_bdf", "CVODE BDF with Newton and a dense solver"},
      {IntegratorKind::kCvodeAdams, "cvode_adams", "CVODE Adams-Moulton with fixed point"},
      {IntegratorKind::kArkodeErk, "arkode_erk", "ARKODE adaptive explicit Runge-Kutta"},
      {IntegratorKind::kArkodeDirk, "arkode_dirk", "ARKODE DIRK with Newton and a dense solver"},
      {IntegratorKind::kRkf23, "rkf23", "Runge-Kutta-Fehlberg 2(3) of Masin's reference codes"},
  };
};
// Every kind, in table order (EnumValues<IntegratorKind>()).
std::vector<IntegratorKind> AllIntegratorKinds();

enum class JacobianKind { kExact, kFiniteDifference };
template <>
struct EnumNames<JacobianKind> {
  static constexpr EnumEntry<JacobianKind> kEntries[] = {
      {JacobianKind::kExact, "exact", "automatic differentiation"},
      {JacobianKind::kFiniteDifference, "finite_difference", "difference quotients"},
  };
};

enum class TerminationType { kReachedEnd, kRootFound, kFailure, kNotRun };
template <>
struct EnumNames<TerminationType> {
  static constexpr EnumEntry<TerminationType> kEntries[] = {
      {TerminationType::kReachedEnd, "reached_end", "integrated to the end time"},
      {TerminationType::kRootFound, "root_found", "stopped at the crossing of a root function"},
      {TerminationType::kFailure, "failure", "the integrator failed (see the message)"},
      {TerminationType::kNotRun, "not_run", "not started"},
  };
};

// Defaults chosen from the work-precision study (bench/README.md,
// bench/constitutive_work_precision, 7 paths × 2 models): the element-test
// ODE has 14–15 components and a cheap right-hand side, so per-step overhead
// decides; ARKODE's explicit order-5 pair (Cash–Karp) wins. The tolerance
// here (1e-8) is the hypoplastic clay's; element tests take each model's own
// default (DefaultIntegratorOptions in constitutive/element_driver.h: 1e-9 for
// Modified Cam clay, whose kinks at the yield surface make ERK 5 lose to
// RKF23 at 1e-8 on some paths). BDF/DIRK pay for Newton and Jacobians on a
// problem that is not stiff.
struct IntegratorOptions {
  IntegratorKind kind = IntegratorKind::kArkodeErk;
  // Relative tolerance on each component (dimensionless); see the note above.
  double relative_tolerance = 1e-8;
  // Absolute tolerance as a fraction of each component's scale at the current
  // state (OdeSystem::StateScales; stresses: ‖T‖); guards components that pass
  // through zero.
  double absolute_tolerance = 1e-8;
  // Implicit methods: exact (automatic differentiation) or difference-quotient Jacobian.
  JacobianKind jacobian = JacobianKind::kExact;
  // Steps allowed per call before failing (protects against stalls).
  long max_steps = 1000000;
  // First step size in time units; 0 lets the method choose.
  double initial_step = 0.0;
  // Largest step in time units; 0 means unlimited.
  double max_step = 0.0;
  // Explicit ARKODE: method order (2..8, SUNDIALS default tables; 5 is
  // Cash–Karp, the fastest in the study above). DIRK: 2..5.
  int arkode_order = 5;
  // RKF23: smallest step as a fraction of the interval before failing.
  double rkf23_min_step_fraction = 1e-17;
  // Fixed step size in time units for convergence studies; 0 = adaptive (default).
  // CVODE emulates it with equal minimum/maximum steps, loose tolerances and
  // `cvode_max_order`.
  double fixed_step = 0.0;
  // CVODE: highest BDF (1..5) or Adams (1..12) order.
  int cvode_max_order = 5;

  bool IsValid(std::string* why) const;
};

struct IntegrationSummary {
  TerminationType termination = TerminationType::kFailure;
  std::string message;
  long steps = 0;
  long rejected_steps = 0;  // error-test failures
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long nonlinear_iterations = 0;
  long nonlinear_failures = 0;
  double wall_time_s = 0.0;
  double final_time = 0.0;
  int root_index = -1;  // which root function stopped the integration
  bool success() const { return termination != TerminationType::kFailure; }
  std::string Report() const;  // one line
  // Adds the counters of another run (stages of one test).
  void Accumulate(const IntegrationSummary& other);
};

class Integrator {
 public:
  // Called at each output time with the (interpolated) state.
  using Observer = std::function<void(double t, const double* y)>;

  virtual ~Integrator() = default;
  // Integrates from t0 to t_end in place on y (dimension of the system), calling
  // `observer` at every time of `output_times` that lies in (t0, t_end] and is
  // reached before a root. On a root, y and final_time are the crossing.
  virtual IntegrationSummary Integrate(OdeSystem& system, double t0, double t_end, double* y,
                                       const std::vector<double>& output_times,
                                       const Observer& observer) = 0;

  // The options must be valid (GRANASYM_CHECK).
  static std::unique_ptr<Integrator> Create(const IntegratorOptions& options);
};

}  // namespace granasym
