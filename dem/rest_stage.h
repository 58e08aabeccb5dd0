// Rest stage: the cell is servo-controlled toward an isotropic stress p* on
// each axis until the sample is in equilibrium there.
#pragma once

#include "dem/stage.h"

namespace granasym::dem {

class RestStage final : public StageSpec {
 public:
  double mean_stress_kpa = 0;   // p* (kPa)
  double max_strain_rate = 10;  // rate scale of max_rate_factor (1/s)
  ControlOptions control;
  int64_t check_interval = 50;  // steps between equilibrium checks ([stage.control])
  // Equilibrium ([stage.stop]): |σ_ii − p*| <= stress_tolerance p* on each
  // axis and the unbalanced-force ratio <= unbalanced_force.
  double stress_tolerance = 0.01;
  double unbalanced_force = 1e-3;

  static std::shared_ptr<const StageSpec> Parse(const ConfigTable& table);
  std::string type() const override { return "rest"; }
  bool StopsByItself() const override { return true; }
  std::unique_ptr<StageController> MakeController(const StageContext&) const override;
  // Three controlled rates of at most max_rate_factor times max_strain_rate.
  double MaxStrainRate() const override;
  const char* RateKey() const override { return "max_strain_rate"; }
  // A rest settles within a few thousand steps.
  std::optional<double> TypicalSteps() const override { return 5000; }
  void Canonical(CanonicalText& text, const std::string& prefix) const override;
  void Describe(Hdf5File& file, const std::string& group) const override;
};

}  // namespace granasym::dem
