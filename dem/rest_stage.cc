#include "dem/rest_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/contact_statistics.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

// Each axis: Δε_d = gain (p* − σ_dd)/C_d per step plus an integral term,
// C_d the affine stiffness of σ_dd under an isotropic strain increment.
class RestController final : public StageController {
 public:
  explicit RestController(const RestStage& spec) : spec_(spec) {}
  std::array<double, 3> Start() override {
    integral_ = {0.0, 0.0, 0.0};
    return {0.0, 0.0, 0.0};
  }
  bool NeedsStress(int64_t) const override { return true; }
  bool NeedsStiffness() const override { return true; }
  std::optional<std::array<double, 3>> Control(const Engine::Sums& sums, double dt) override {
    const ControlOptions& control = spec_.control;
    const double max_rate = control.max_rate_factor * spec_.max_strain_rate;
    const double target = spec_.mean_stress_kpa * kKiloPascal;
    const auto& c = sums.stiffness;
    const std::array<double, 3> row = {c[0] + c[3] + c[4], c[3] + c[1] + c[5], c[4] + c[5] + c[2]};
    std::array<double, 3> gradient;
    for (int d = 0; d < 3; ++d) {
      const double error = target - sums.stress[d];
      double rate;
      if (row[d] > 0) {
        const double strain_error = error / row[d];
        integral_[d] += control.integral_gain * strain_error;
        rate = std::clamp((control.gain * strain_error + integral_[d]) / dt, -max_rate, max_rate);
      } else {
        rate = error > 0 ? max_rate : -max_rate;
      }
      gradient[d] = -rate;
    }
    return gradient;
  }
  std::optional<std::string> CheckStop(const Engine& engine, int64_t stage_steps) const override {
    if (stage_steps % spec_.check_interval != 0) return std::nullopt;
    const Engine::Sums& sums = engine.sums();
    const double target = spec_.mean_stress_kpa * kKiloPascal;
    bool at_target = sums.contacts > 0;
    for (int d = 0; d < 3; ++d) {
      at_target = at_target && std::abs(sums.stress[d] - target) <= spec_.stress_tolerance * target;
    }
    if (!at_target) return std::nullopt;
    const double unbalanced = UnbalancedForceRatio(engine);
    if (unbalanced > spec_.unbalanced_force) return std::nullopt;
    return fmt::format("equilibrium at p = {:.6g} kPa, unbalanced force {:.3g}",
                       MeanStressKpa(sums), unbalanced);
  }
  std::vector<double> SaveState() const override { return {integral_.begin(), integral_.end()}; }
  void RestoreState(const std::vector<double>& state) override {
    for (int d = 0; d < 3; ++d) integral_[d] = state.at(d);
  }

 private:
  const RestStage& spec_;
  std::array<double, 3> integral_{};  // integral terms per axis (strain)
};

}  // namespace

std::shared_ptr<const StageSpec> RestStage::Parse(const ConfigTable& table) {
  auto stage = std::make_shared<RestStage>();
  stage->mean_stress_kpa = table.GetDouble("mean_stress_kpa", kStressKpa);
  stage->max_strain_rate = table.GetDouble("max_strain_rate", stage->max_strain_rate, kStrainRate);
  if (table.Has("control")) {
    const ConfigTable control = table.GetTable("control");
    stage->control = ControlOptions::Parse(control);
    stage->check_interval =
        control.GetInt("check_interval", stage->check_interval, Range::Closed(1, 1e7));
  }
  if (table.Has("stop")) {
    const ConfigTable stop = table.GetTable("stop");
    stage->stress_tolerance =
        stop.GetDouble("stress_tolerance", stage->stress_tolerance, Range::Open(0, 1));
    stage->unbalanced_force =
        stop.GetDouble("unbalanced_force", stage->unbalanced_force, {0.0, 1.0, false, true});
  }
  return stage;
}

std::unique_ptr<StageController> RestStage::MakeController(const StageContext&) const {
  return std::make_unique<RestController>(*this);
}

void RestStage::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "mean_stress_kpa", mean_stress_kpa);
  text.Add(prefix + "max_strain_rate", max_strain_rate);
  control.Canonical(text, prefix + "control.");
  text.Add(prefix + "control.check_interval", check_interval);
  text.Add(prefix + "stop.stress_tolerance", stress_tolerance);
  text.Add(prefix + "stop.unbalanced_force", unbalanced_force);
}

void RestStage::Describe(Hdf5File& file, const std::string& group) const {
  file.SetAttribute(group, record::kStageMeanStressKpa, mean_stress_kpa);
}

double RestStage::MaxStrainRate() const {
  return std::sqrt(3.0) * control.max_rate_factor * max_strain_rate;
}

}  // namespace granasym::dem
