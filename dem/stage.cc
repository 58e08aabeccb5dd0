#include "dem/stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::dem {
namespace {

std::optional<double> OptionalDouble(const ConfigTable& table, const std::string& key,
                                     Range range) {
  if (!table.Has(key)) return std::nullopt;
  return table.GetDouble(key, range);
}

bool StepsOrTimeDone(const StopConditions& stop, const StageClock& clock, const Engine& engine) {
  if (stop.steps && clock.steps(engine) >= *stop.steps) return true;
  const double elapsed = engine.time() - clock.start_time;
  return stop.time_s && elapsed >= *stop.time_s * (1 - 1e-12);
}

}  // namespace

StageContext StageContext::Of(const Packing& sample, double density) {
  StageContext context;
  context.density = density;
  if (sample.radii.empty()) return context;
  std::vector<std::pair<double, double>> by_size;  // (radius, mass ∝ r³)
  double total = 0;
  for (double r : sample.radii) {
    by_size.push_back({r, r * r * r});
    total += r * r * r;
  }
  std::sort(by_size.begin(), by_size.end());
  context.min_diameter = 2 * by_size.front().first;
  context.max_diameter = 2 * by_size.back().first;
  double passing = 0;
  for (const auto& [r, mass] : by_size) {
    passing += mass;
    if (passing >= 0.5 * total) {
      context.median_diameter = 2 * r;
      break;
    }
  }
  return context;
}

StopConditions StopConditions::Parse(const ConfigTable& stop) {
  StopConditions s;
  s.mean_stress_kpa = OptionalDouble(stop, "mean_stress_kpa", kStressKpa);
  s.mean_stress_direction = stop.GetEnum("direction", Direction::kAuto);
  s.axial_strain = OptionalDouble(stop, "axial_strain", kStageStrain);
  s.volumetric_strain = OptionalDouble(stop, "volumetric_strain", kStageStrain);
  s.shear_strain = OptionalDouble(stop, "shear_strain", kStageStrain);
  s.strain_norm = OptionalDouble(stop, "strain_norm", {0.0, 1e3, false, true});
  s.time_s = OptionalDouble(stop, "time_s", {0.0, 1e6, false, true});
  if (stop.Has("steps")) s.steps = stop.GetInt("steps", Range::Closed(1, kMaxStageSteps));
  s.asymptote = stop.GetBool("asymptote", false);
  s.liquefied = stop.GetBool("liquefied", false);
  s.liquefied_strain = OptionalDouble(stop, "liquefied_strain", {0.0, 1e3, false, true});
  if (s.liquefied_strain && !s.liquefied) {
    stop.Fail("liquefied_strain", "is the gas window of liquefied = true, which is not set");
  }
  return s;
}

double MeanStressKpa(const Engine::Sums& sums) {
  return AxisymmetricFromTensor(sums.stress).mean() / kKiloPascal;
}

bool StopConditions::any() const {
  return mean_stress_kpa || axial_strain || volumetric_strain || shear_strain || strain_norm ||
         time_s || steps || asymptote;
}

void StopConditions::Canonical(CanonicalText& text, const std::string& prefix) const {
  auto optional = [&](const char* key, const std::optional<double>& value) {
    if (value) text.Add(prefix + key, *value);
  };
  optional("mean_stress_kpa", mean_stress_kpa);
  if (mean_stress_kpa) text.Add(prefix + "direction", ToString(mean_stress_direction));
  optional("axial_strain", axial_strain);
  optional("volumetric_strain", volumetric_strain);
  optional("shear_strain", shear_strain);
  optional("strain_norm", strain_norm);
  optional("time_s", time_s);
  if (steps) text.Add(prefix + "steps", *steps);
  text.Add(prefix + "asymptote", asymptote);
  if (liquefied) text.Add(prefix + "liquefied", true);  // absent: the keys of older scenes hold
  optional("liquefied_strain", liquefied_strain);
}

ControlOptions ControlOptions::Parse(const ConfigTable& control) {
  ControlOptions c;
  c.gain = control.GetDouble("gain", c.gain, Range::Open(0, 1));
  c.integral_gain = control.GetDouble("integral_gain", c.integral_gain, Range::Closed(0, 1));
  c.max_rate_factor =
      control.GetDouble("max_rate_factor", c.max_rate_factor, {0.0, 1e3, false, true});
  return c;
}

void ControlOptions::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "gain", gain);
  text.Add(prefix + "integral_gain", integral_gain);
  text.Add(prefix + "max_rate_factor", max_rate_factor);
}

void Stage::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "name", name);
  text.Add(prefix + "type", type());
  spec->Canonical(text, prefix);
  stop.Canonical(text, prefix + "stop.");
  text.Add(prefix + "detect_asymptote", detect_asymptote);
  if (detect_asymptote) asymptote.Canonical(text, prefix + "asymptote.");
}

Direction MeanStressDirection(const StopConditions& stop, const StageClock& clock) {
  if (stop.mean_stress_direction != Direction::kAuto || !stop.mean_stress_kpa) {
    return stop.mean_stress_direction;
  }
  return clock.start_p_kpa < *stop.mean_stress_kpa ? Direction::kRising : Direction::kFalling;
}

std::optional<std::string> MeanStressStop(const StopConditions& stop, const StageClock& clock,
                                          double p) {
  if (!stop.mean_stress_kpa) return std::nullopt;
  const Direction direction = MeanStressDirection(stop, clock);
  if ((direction == Direction::kRising && p >= *stop.mean_stress_kpa) ||
      (direction == Direction::kFalling && p <= *stop.mean_stress_kpa)) {
    return fmt::format("mean stress reached {:.6g} kPa (target {:.6g} kPa, {})", p,
                       *stop.mean_stress_kpa, ToString(direction));
  }
  return std::nullopt;
}

bool StrainOrDurationStopReached(const StopConditions& stop, const StageClock& clock,
                                 const Engine& engine) {
  std::array<double, 3> strain;
  for (int d = 0; d < 3; ++d) strain[d] = -std::log(engine.cell()[d] / clock.start_cell[d]);
  const double axial = strain[0], radial = 0.5 * (strain[1] + strain[2]);
  auto reached = [](std::optional<double> target, double value) {
    if (!target) return false;
    return *target >= 0 ? value >= *target : value <= *target;
  };
  if (reached(stop.axial_strain, axial)) return true;
  if (reached(stop.volumetric_strain, axial + 2 * radial)) return true;
  if (reached(stop.shear_strain, 2.0 * (axial - radial) / 3.0)) return true;
  if (stop.strain_norm && clock.strain_norm >= *stop.strain_norm) return true;
  return StepsOrTimeDone(stop, clock, engine);
}

std::string StrainOrDurationReason(const StopConditions& stop, const StageClock& clock,
                                   const Engine& engine) {
  if (StepsOrTimeDone(stop, clock, engine)) {
    return stop.steps ? fmt::format("{} steps done", *stop.steps)
                      : fmt::format("stage time {:.6g} s reached", *stop.time_s);
  }
  return "strain target reached";
}

bool Stage::ContinuesDetection(const Stage& previous) const {
  return detect_asymptote && previous.detect_asymptote &&
         asymptote.Describe() == previous.asymptote.Describe() &&
         spec->ContinuesPath(*previous.spec);
}

}  // namespace granasym::dem
