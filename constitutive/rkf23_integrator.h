// The explicit Runge–Kutta–Fehlberg 2(3) pair with step control used by
// Mašín's reference implementations (SPEC §6.1), kept as the baseline:
//   k1 = f(y), k2 = f(y + h/2 k1), k3 = f(y − h k1 + 2h k2),
//   y2 = y + h k2 (2nd order), y3 = y + h (k1 + 4 k2 + k3)/6 (3rd order, kept),
//   accept when ‖y3 − y2‖ ≤ 1 in the weighted max norm (rtol |y| + atol),
//   h_new = 0.9 h ‖·‖^(−1/3), at most ×4 after success and at least ÷4 after a rejection.
// Steps whose stages leave the model's domain are rejected and quartered.
// Root crossings are located by re-taking the step with the Illinois method.
#pragma once

#include "constitutive/integrator.h"

namespace granasym {

class Rkf23Integrator : public Integrator {
 public:
  explicit Rkf23Integrator(const IntegratorOptions& options) : options_(options) {}
  IntegrationSummary Integrate(OdeSystem& system, double t0, double t_end, double* y,
                               const std::vector<double>& output_times,
                               const Observer& observer) override;

 private:
  IntegratorOptions options_;
};

}  // namespace granasym
