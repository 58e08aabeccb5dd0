#include "dem/triaxial_stage.h"

#include <algorithm>
#include <cmath>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

// σ_r is held by Δε_r = gain (σ_r* − σ_r)/C_rr per step plus an integral
// term, with the feed-forward −(C_ra/C_rr) ε̇_a that keeps σ_r constant under
// the axial rate in the affine estimate; the integral removes the steady
// error left by that estimate (the relaxed network is softer).
class TriaxialController final : public StageController {
 public:
  explicit TriaxialController(const TriaxialStage& spec) : spec_(spec) {}
  std::array<double, 3> Start() override {
    // Hold the radial strain; the controller takes over at the first step.
    integral_ = 0;
    return {-spec_.axial_strain_rate, 0.0, 0.0};
  }
  bool NeedsStress(int64_t) const override { return true; }
  bool NeedsStiffness() const override { return true; }
  std::optional<std::array<double, 3>> Control(const Engine::Sums& sums, double dt) override {
    const ControlOptions& control = spec_.control;
    const double max_rate = control.max_rate_factor * std::abs(spec_.axial_strain_rate);
    const auto& c = sums.stiffness;  // 11-11, 22-22, 33-33, 11-22, 11-33, 22-33
    const double target = spec_.radial_stress_kpa * kKiloPascal;
    const double radial = 0.5 * (sums.stress[1] + sums.stress[2]);
    const double c_rr = 0.5 * (c[1] + c[2] + 2.0 * c[5]);
    const double c_ra = 0.5 * (c[3] + c[4]);
    double rate;
    if (c_rr > 0) {
      const double strain_error = (target - radial) / c_rr;
      integral_ += control.integral_gain * strain_error;
      rate =
          -c_ra / c_rr * spec_.axial_strain_rate + (control.gain * strain_error + integral_) / dt;
    } else {
      rate = target > radial ? max_rate : -max_rate;
    }
    rate = std::clamp(rate, -max_rate, max_rate);
    return std::array<double, 3>{-spec_.axial_strain_rate, -rate, -rate};
  }
  std::vector<double> SaveState() const override { return {integral_}; }
  void RestoreState(const std::vector<double>& state) override { integral_ = state.at(0); }

 private:
  const TriaxialStage& spec_;
  double integral_ = 0;  // integral term (strain)
};

}  // namespace

std::shared_ptr<const StageSpec> TriaxialStage::Parse(const ConfigTable& table) {
  auto stage = std::make_shared<TriaxialStage>();
  stage->axial_strain_rate =
      table.GetDouble("axial_strain_rate", Range::Closed(-kStrainRate.max, kStrainRate.max));
  if (stage->axial_strain_rate == 0) {
    table.Fail("axial_strain_rate", "= 0: must be non-zero (1/s, compression positive)");
  }
  stage->radial_stress_kpa = table.GetDouble("radial_stress_kpa", kStressKpa);
  if (table.Has("control")) stage->control = ControlOptions::Parse(table.GetTable("control"));
  return stage;
}

std::unique_ptr<StageController> TriaxialStage::MakeController(const StageContext&) const {
  return std::make_unique<TriaxialController>(*this);
}

void TriaxialStage::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "axial_strain_rate", axial_strain_rate);
  text.Add(prefix + "radial_stress_kpa", radial_stress_kpa);
  control.Canonical(text, prefix + "control.");
}

void TriaxialStage::Describe(Hdf5File& file, const std::string& group) const {
  file.SetAttribute(group, record::kStageAxialStrainRate, axial_strain_rate);
  file.SetAttribute(group, record::kStageRadialStressKpa, radial_stress_kpa);
}

double TriaxialStage::MaxStrainRate() const {
  const double radial = control.max_rate_factor * std::abs(axial_strain_rate);
  return std::sqrt(axial_strain_rate * axial_strain_rate + 2 * radial * radial);
}

}  // namespace granasym::dem
