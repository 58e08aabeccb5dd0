// Starting values computed from the data (issue 4 §2), each with a standard
// error from its own regression:
//   λ*, N: least squares of ln(1+e) = N − λ* ln(p/p_r) over the NCL points;
//   φ_c:   from the mean critical stress ratio of the CSL points,
//          tan ψ_σ = (√2/3) M, sin φ_c = 3M/(6 + M) (paper Eq. 1 inverted);
//   κ*:    slope of ln(1+e) against ln p over each unloading branch (pooled);
// missing data leave a typical value and a note saying so.
#pragma once

#include <string>
#include <vector>

#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct Estimate {
  bool from_data = false;
  double value = 0.0;
  double standard_error = 0.0;  // NaN when not from data or not estimable (one point)
  int points = 0;
  std::string note;  // how it was obtained
};

struct StartingValues {
  Estimate critical_friction_angle_deg;
  Estimate lambda_star;
  Estimate kappa_star;
  Estimate n_intercept;
  std::string Report() const;  // several lines
};

StartingValues EstimateStartingValues(const std::vector<StateDataset>& datasets);

}  // namespace granasym::calibration
