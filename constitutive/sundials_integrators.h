// SUNDIALS 6 integrators (CVODE, ARKODE) behind the Integrator interface.
// Every SUNDIALS object is owned by an RAII wrapper; every setup call is
// checked and a failure names the call (RuntimeError). Failures while
// integrating (step too small, Newton divergence, RHS outside the model's
// domain) end in a Summary with TerminationType::kFailure and the message.
#pragma once

#include "constitutive/integrator.h"

namespace granasym {

// CVODE: BDF with Newton and a dense direct solver (exact or difference-quotient
// Jacobian), or Adams–Moulton with fixed-point iteration.
class CvodeIntegrator : public Integrator {
 public:
  explicit CvodeIntegrator(const IntegratorOptions& options) : options_(options) {}
  IntegrationSummary Integrate(OdeSystem& system, double t0, double t_end, double* y,
                               const std::vector<double>& output_times,
                               const Observer& observer) override;

 private:
  IntegratorOptions options_;
};

// ARKODE: ERKStep adaptive explicit Runge–Kutta of the chosen order, or ARKStep
// DIRK (fully implicit) with Newton and a dense direct solver.
class ArkodeIntegrator : public Integrator {
 public:
  explicit ArkodeIntegrator(const IntegratorOptions& options) : options_(options) {}
  IntegrationSummary Integrate(OdeSystem& system, double t0, double t_end, double* y,
                               const std::vector<double>& output_times,
                               const Observer& observer) override;

 private:
  IntegratorOptions options_;
};

}  // namespace granasym
