// Strain-path stage: proportional straining at a fixed direction ψ_ε of the
// stretching D in the Rendulic plane (SPEC §2), at a fixed norm ‖D‖ or at a
// fixed inertial number:
//
//   [stage.rate]                 # optional; without it ‖D‖ = stretching_rate
//   rule = "inertial"            # ‖D‖ = I* sqrt(p / (2 ρ_s)) / d, at most stretching_rate
//   inertial_number = 1e-3       # I*, in (0, 1]
//   diameter = "d_max"           # d: d_max (default), d_50 (by mass) or d_min
//   min_mean_stress_kpa = 1.0    # floor on p (the start from a stress-free state)
//   check_interval = 10          # steps between updates of ‖D‖ from the measured p
#pragma once

#include "dem/stage.h"

namespace granasym::dem {

// The diameter an inertial number refers to.
enum class InertialDiameter { kMax, kMedian, kMin };
// How a strain-path stage sets ‖D‖.
enum class RateRule { kConstant, kInertial };

}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::InertialDiameter> {
  static constexpr EnumEntry<dem::InertialDiameter> kEntries[] = {
      {dem::InertialDiameter::kMax, "d_max", "the largest diameter of the sample"},
      {dem::InertialDiameter::kMedian, "d_50", "the diameter that half the mass passes"},
      {dem::InertialDiameter::kMin, "d_min", "the smallest diameter"},
  };
};
template <>
struct granasym::EnumNames<granasym::dem::RateRule> {
  static constexpr EnumEntry<dem::RateRule> kEntries[] = {
      {dem::RateRule::kConstant, "constant", "||D|| = stretching_rate"},
      {dem::RateRule::kInertial, "inertial", "||D|| from a target inertial number"},
  };
};

namespace granasym::dem {

struct InertialRate {
  double inertial_number = 1e-3;
  InertialDiameter diameter = InertialDiameter::kMax;
  double min_mean_stress_kpa = 1.0;
  int64_t check_interval = 10;
  // ‖D‖ for mean stress p (kPa), capped at `cap` (1/s).
  double Rate(double p_kpa, const StageContext& context, double cap) const;
};

class StrainPathStage final : public StageSpec {
 public:
  double psi_epsilon_deg = 0;  // ψ_ε in [-180, 180] (deg)
  double stretching_rate = 0;  // ‖D‖, or its cap under the inertial rule (1/s)
  RateRule rule = RateRule::kConstant;
  InertialRate inertial;  // with RateRule::kInertial

  static std::shared_ptr<const StageSpec> Parse(const ConfigTable& table);
  double psi_epsilon() const;  // (rad)
  std::string type() const override { return "strain_path"; }
  std::optional<PathKind> path_kind() const override { return StrainPathKind(psi_epsilon_deg); }
  // The same ψ_ε and rate (rule and its keys).
  bool ContinuesPath(const StageSpec& previous) const override;
  std::unique_ptr<StageController> MakeController(const StageContext& context) const override;
  double MaxStrainRate() const override { return stretching_rate; }
  const char* RateKey() const override { return "stretching_rate"; }
  double TypicalStrainRate(double density, double mean_stress_kpa) const override;
  void Canonical(CanonicalText& text, const std::string& prefix) const override;
  void Describe(Hdf5File& file, const std::string& group) const override;
};

}  // namespace granasym::dem
