#include "dem/strain_path_stage.h"

#include <algorithm>
#include <cmath>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

class StrainPathController final : public StageController {
 public:
  StrainPathController(const StrainPathStage& spec, const StageContext& context)
      : spec_(spec), context_(context) {}
  std::array<double, 3> Start() override {
    // Under the inertial rule the first step runs at the floor's rate; the
    // stress of that step sets the rate from then on.
    return Gradient(spec_.rule == RateRule::kInertial
                        ? spec_.inertial.Rate(spec_.inertial.min_mean_stress_kpa, context_,
                                              spec_.stretching_rate)
                        : spec_.stretching_rate);
  }
  bool NeedsStress(int64_t stage_steps) const override {
    return spec_.rule == RateRule::kInertial && stage_steps % spec_.inertial.check_interval == 0;
  }
  bool NeedsStiffness() const override { return false; }
  std::optional<std::array<double, 3>> Control(const Engine::Sums& sums, double) override {
    if (spec_.rule != RateRule::kInertial) return std::nullopt;
    return Gradient(spec_.inertial.Rate(MeanStressKpa(sums), context_, spec_.stretching_rate));
  }

 private:
  std::array<double, 3> Gradient(double norm) const {
    const AxisymmetricRate rate = AxisymmetricRate::FromAngle(spec_.psi_epsilon(), norm);
    return {-rate.axial, -rate.radial, -rate.radial};
  }
  const StrainPathStage& spec_;
  StageContext context_;
};

}  // namespace

std::shared_ptr<const StageSpec> StrainPathStage::Parse(const ConfigTable& table) {
  auto stage = std::make_shared<StrainPathStage>();
  stage->psi_epsilon_deg = table.GetDouble("psi_epsilon_deg", Range::Closed(-180, 180));
  stage->stretching_rate = table.GetDouble("stretching_rate", kStrainRate);
  if (table.Has("rate")) {
    const ConfigTable rate = table.GetTable("rate");
    stage->rule = rate.GetEnum<RateRule>("rule");
    if (stage->rule == RateRule::kInertial) {
      InertialRate& i = stage->inertial;
      i.inertial_number = rate.GetDouble("inertial_number", {0.0, 1.0, false, true});
      i.diameter = rate.GetEnum("diameter", i.diameter);
      i.min_mean_stress_kpa =
          rate.GetDouble("min_mean_stress_kpa", i.min_mean_stress_kpa, kStressKpa);
      i.check_interval = rate.GetInt("check_interval", i.check_interval, Range::Closed(1, 1e6));
    }
  }
  return stage;
}

double InertialRate::Rate(double p_kpa, const StageContext& context, double cap) const {
  const double d = diameter == InertialDiameter::kMax      ? context.max_diameter
                   : diameter == InertialDiameter::kMedian ? context.median_diameter
                                                           : context.min_diameter;
  const double floored =
      std::isnan(p_kpa) ? min_mean_stress_kpa : std::max(p_kpa, min_mean_stress_kpa);
  const double p = floored * kKiloPascal;
  const double rate = inertial_number * std::sqrt(p / (2 * context.density)) / d;
  return std::isfinite(rate) ? std::min(rate, cap) : cap;
}

double StrainPathStage::psi_epsilon() const { return psi_epsilon_deg * kDegree; }

std::unique_ptr<StageController> StrainPathStage::MakeController(
    const StageContext& context) const {
  return std::make_unique<StrainPathController>(*this, context);
}

void StrainPathStage::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "psi_epsilon_deg", psi_epsilon_deg);
  text.Add(prefix + "stretching_rate", stretching_rate);
  if (rule == RateRule::kInertial) {
    text.Add(prefix + "rate.rule", ToString(rule));
    text.Add(prefix + "rate.inertial_number", inertial.inertial_number);
    text.Add(prefix + "rate.diameter", ToString(inertial.diameter));
    text.Add(prefix + "rate.min_mean_stress_kpa", inertial.min_mean_stress_kpa);
    text.Add(prefix + "rate.check_interval", inertial.check_interval);
  }
}

void StrainPathStage::Describe(Hdf5File& file, const std::string& group) const {
  file.SetAttribute(group, record::kStagePsiEpsilonDeg, psi_epsilon_deg);
  file.SetAttribute(group, record::kStageStretchingRate, stretching_rate);
  file.SetAttribute(group, record::kStageRateRule, ToString(rule));
  if (rule == RateRule::kInertial) {
    file.SetAttribute(group, record::kStageRateInertialNumber, inertial.inertial_number);
    file.SetAttribute(group, record::kStageRateDiameter, ToString(inertial.diameter));
    file.SetAttribute(group, record::kStageRateMinMeanStressKpa, inertial.min_mean_stress_kpa);
  }
}

bool StrainPathStage::ContinuesPath(const StageSpec& previous) const {
  const auto* path = dynamic_cast<const StrainPathStage*>(&previous);
  return path && path->psi_epsilon_deg == psi_epsilon_deg &&
         path->stretching_rate == stretching_rate && path->rule == rule &&
         (rule == RateRule::kConstant ||
          (path->inertial.inertial_number == inertial.inertial_number &&
           path->inertial.diameter == inertial.diameter &&
           path->inertial.min_mean_stress_kpa == inertial.min_mean_stress_kpa &&
           path->inertial.check_interval == inertial.check_interval));
}

double StrainPathStage::TypicalStrainRate(double density, double mean_stress_kpa) const {
  if (rule != RateRule::kInertial) return stretching_rate;
  const double p_kpa = std::max(mean_stress_kpa, inertial.min_mean_stress_kpa);
  return std::min(stretching_rate,
                  inertial.inertial_number * std::sqrt(p_kpa * 1e3 / (2 * density)) / 1e-3);
}

}  // namespace granasym::dem
