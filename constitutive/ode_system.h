// A first-order system y' = f(t, y) with optional exact Jacobian and root
// functions g(t, y) whose zero crossings stop the integration (targets).
#pragma once

#include <string>

namespace granasym {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int dimension() const = 0;
  // Typical magnitude of each component; absolute tolerances scale with it.
  virtual void ComponentScales(double* scale) const = 0;
  // The same at the state y; integrators weight errors with rtol |y_i| +
  // atol scale_i(y) on every step. Systems whose solution spans orders of
  // magnitude (stress unloaded from 1000 to 0.01 kPa) scale with the state,
  // so that the error control stays relative. Default: ComponentScales.
  virtual void StateScales(const double* y, double* scale) const { ComponentScales(scale); }
  // Returns false when y is outside the domain of f (a recoverable failure:
  // integrators cut the step); `last_failure()` then says why.
  virtual bool Rhs(double t, const double* y, double* y_dot) = 0;
  virtual bool has_jacobian() const { return false; }
  // Dense Jacobian ∂f/∂y, column-major, dimension x dimension.
  virtual bool Jacobian(double t, const double* y, double* jacobian) { return false; }
  // Sign constraints per component in SUNDIALS' coding: 0 none, 1 (≥ 0),
  // 2 (> 0), −1 (≤ 0), −2 (< 0). Integrators reject (and shrink) a step whose
  // result violates them, so that no accepted state leaves the domain of f.
  // Returns false when the system has none.
  virtual bool Constraints(double* codes) const { return false; }
  virtual int num_roots() const { return 0; }
  virtual bool Roots(double t, const double* y, double* g) { return true; }
  virtual const std::string& last_failure() const = 0;
};

}  // namespace granasym
