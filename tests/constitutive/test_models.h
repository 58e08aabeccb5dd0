// Shared parameter sets for the constitutive tests.
#pragma once

#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {
namespace testing_models {

// London clay (Mašín 2005, Table 2).
inline HypoplasticClay::Parameters LondonClay() {
  HypoplasticClay::Parameters p;
  p.critical_friction_angle = 22.6 * kDegree;
  p.lambda_star = 0.11;
  p.kappa_star = 0.016;
  p.n_intercept = 1.375;
  p.bulk_shear_ratio = 0.4;
  return p;
}

inline ModifiedCamClay::Parameters CamClay() {
  ModifiedCamClay::Parameters p;
  p.critical_state_ratio = 0.9;
  p.lambda = 0.11;
  p.kappa = 0.016;
  p.n_intercept = 1.375;
  p.poisson_ratio = 0.25;
  return p;
}

}  // namespace testing_models
}  // namespace granasym
