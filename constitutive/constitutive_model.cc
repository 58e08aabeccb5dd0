// The overconsolidation ratio of a state.
#include "constitutive/constitutive_model.h"

namespace granasym {

double OverconsolidationRatio(const ConstitutiveModel& model, const ModelState& state) {
  return model.EquivalentPressure(state.void_ratio) / MeanStress(state.stress);
}

}  // namespace granasym
