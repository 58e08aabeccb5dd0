// Shared parameter sets for the constitutive tests.
#pragma once

#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/hypoplastic_sand.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {
namespace testing_models {

inline HypoplasticClay::Parameters LondonClay() {
  return HypoplasticClay::Parameters::LondonClay();
}

inline ModifiedCamClay::Parameters CamClay() {
  return ModifiedCamClay::Parameters::LondonClayNcl();
}

inline HypoplasticSand::Parameters HochstettenSand() {
  return HypoplasticSand::Parameters::HochstettenSand();
}

}  // namespace testing_models
}  // namespace granasym
