// Shared parameter sets for the constitutive tests.
#pragma once

#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {
namespace testing_models {

inline HypoplasticClay::Parameters LondonClay() {
  return HypoplasticClay::Parameters::LondonClay();
}

inline ModifiedCamClay::Parameters CamClay() {
  return ModifiedCamClay::Parameters::LondonClayNcl();
}

}  // namespace testing_models
}  // namespace granasym
