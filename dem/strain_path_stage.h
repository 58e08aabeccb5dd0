// Strain-path stage: proportional straining at a fixed direction ψ_ε of the
// stretching D in the Rendulic plane and a fixed norm ‖D‖ (SPEC §2).
#pragma once

#include "dem/stage.h"

namespace granasym::dem {

class StrainPathStage final : public StageSpec {
 public:
  double psi_epsilon_deg = 0;  // ψ_ε in [-180, 180] (deg)
  double stretching_rate = 0;  // ‖D‖ (1/s)

  static std::shared_ptr<const StageSpec> Parse(const ConfigTable& table);
  double psi_epsilon() const;  // (rad)
  std::string type() const override { return "strain_path"; }
  std::optional<PathKind> path_kind() const override { return StrainPathKind(psi_epsilon_deg); }
  // The same ψ_ε and ‖D‖.
  bool ContinuesPath(const StageSpec& previous) const override;
  std::unique_ptr<StageController> MakeController() const override;
  double MaxStrainRate() const override { return stretching_rate; }
  const char* RateKey() const override { return "stretching_rate"; }
  void Canonical(CanonicalText& text, const std::string& prefix) const override;
  void Describe(Hdf5File& file, const std::string& group) const override;
};

}  // namespace granasym::dem
