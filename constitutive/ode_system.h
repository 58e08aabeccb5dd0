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
  // Returns false when y is outside the domain of f (a recoverable failure:
  // integrators cut the step); `last_failure()` then says why.
  virtual bool Rhs(double t, const double* y, double* y_dot) = 0;
  virtual bool has_jacobian() const { return false; }
  // Dense Jacobian ∂f/∂y, column-major, dimension x dimension.
  virtual bool Jacobian(double t, const double* y, double* jacobian) { return false; }
  virtual int num_roots() const { return 0; }
  virtual bool Roots(double t, const double* y, double* g) { return true; }
  virtual const std::string& last_failure() const = 0;
};

}  // namespace granasym
