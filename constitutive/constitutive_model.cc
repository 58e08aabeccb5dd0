// Names of the model kinds and the overconsolidation ratio of a state.
#include "constitutive/constitutive_model.h"

namespace granasym {

const char* ToString(ModelKind kind) {
  switch (kind) {
    case ModelKind::kHypoplasticClay:
      return "hypoplastic_clay";
    case ModelKind::kModifiedCamClay:
      return "modified_cam_clay";
    case ModelKind::kHypoplasticSand:
      return "hypoplastic_sand";
  }
  return "unknown";
}

bool FromString(const std::string& name, ModelKind* kind) {
  for (ModelKind candidate :
       {ModelKind::kHypoplasticClay, ModelKind::kModifiedCamClay, ModelKind::kHypoplasticSand}) {
    if (name == ToString(candidate)) {
      *kind = candidate;
      return true;
    }
  }
  return false;
}

double OverconsolidationRatio(const ConstitutiveModel& model, const ModelState& state) {
  return model.EquivalentPressure(state.void_ratio) / MeanStress(state.stress);
}

}  // namespace granasym
