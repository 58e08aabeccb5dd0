// The overconsolidation ratio of a state; the defaults of the interface.
#include "constitutive/constitutive_model.h"

namespace granasym {

bool ConstitutiveModel::AsymptoteOfStressDirection(double, double*, double*,
                                                   std::string* why) const {
  if (why != nullptr) *why = "the model has no closed-form asymptotic states";
  return false;
}

double OverconsolidationRatio(const ConstitutiveModel& model, const ModelState& state) {
  return model.EquivalentPressure(state.void_ratio) / MeanStress(state.stress);
}

}  // namespace granasym
