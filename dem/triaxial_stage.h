// Drained triaxial stage: a constant axial strain rate ε̇_a with the radial
// stress σ_r held at a target by a PI controller on the radial strain rate.
#pragma once

#include <cmath>

#include "dem/stage.h"

namespace granasym::dem {

class TriaxialStage final : public StageSpec {
 public:
  double axial_strain_rate = 0;  // ε̇_a, compression positive, non-zero (1/s)
  double radial_stress_kpa = 0;  // σ_r target (kPa)
  ControlOptions control;        // rate scale of max_rate_factor: |ε̇_a|

  static std::shared_ptr<const StageSpec> Parse(const ConfigTable& table);
  std::string type() const override { return "triaxial"; }
  std::optional<PathKind> path_kind() const override { return PathKind::kStressControlled; }
  std::unique_ptr<StageController> MakeController(const StageContext&) const override;
  // The axial rate and the radial rates up to max_rate_factor times it.
  double MaxStrainRate() const override;
  const char* RateKey() const override { return "axial_strain_rate"; }
  // ‖D‖ of drained compression at ε̇_a, about 1.5 |ε̇_a|.
  double TypicalStrainRate(double, double) const override {
    return 1.5 * std::abs(axial_strain_rate);
  }
  void Canonical(CanonicalText& text, const std::string& prefix) const override;
  void Describe(Hdf5File& file, const std::string& group) const override;
};

}  // namespace granasym::dem
