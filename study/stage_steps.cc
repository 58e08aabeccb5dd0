#include "study/stage_steps.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "common/state_measures.h"
#include "dem/packing.h"
#include "dem/rest_stage.h"
#include "dem/stage_validity.h"
#include "dem/strain_path_stage.h"
#include "dem/triaxial_stage.h"

namespace granasym::study {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
// Midpoints of the integral of the steps over the strain of a path that does not load.
constexpr int kIntegrationPoints = 4000;
// Beyond any stress a DEM stage reaches (kPa): a loading walk ends there.
constexpr double kLargestStressKpa = 1e8;
// The strain assumed where no stop can be predicted (the former estimate).
constexpr double kFallbackStrain = 0.3;
constexpr double kUnknownStartKpa = 100.0;

// How p moves with the strain norm s along a path of fixed direction.
struct StressPath {
  double start_kpa = 0;                 // p at s = 0 (0: the generated sample)
  double jam_strain = 0;                // s at which the generated sample jams (p = 0 before)
  double volumetric = 0;                // ε̇_v/‖D‖ (compression positive)
  std::function<double(double)> speed;  // ‖D‖ (1/s) at p (kPa)
  double diameter = 0, density = 0;     // d_max (m), ρ_s (kg/m³)
  double generated_fraction = 0;        // φ_0
  double modulus_factor = 0;  // K = modulus_factor · κ p (Pa), K the affine bulk modulus
  dem::ContactLaw law = dem::ContactLaw::kLinear;
  double youngs_modulus = 0, poissons_ratio = 0;  // (Pa)

  // The solid fraction of the packing bearing p under the stage's rate:
  // φ_J − a I(p), I = ‖D‖ d sqrt(2ρ_s/p), not below the generated one.
  double Fraction(double p_kpa) const {
    const double p = std::max(p_kpa, kJammedMeanStressKpa) * kKiloPascal;
    const double inertial_number = speed(p_kpa) * diameter * std::sqrt(2 * density / p);
    return std::max(kJammedSolidFraction - kDilatancyCoefficient * inertial_number,
                    generated_fraction);
  }
  // The volumetric strain of loading to p, up to a constant: the denser
  // packing of a slower flow and the compliance of the contacts.
  double Compression(double p_kpa) const {
    return std::log(Fraction(p_kpa)) + kContactCompliance * p_kpa * kKiloPascal / youngs_modulus;
  }
  double loaded_start() const { return start_kpa > 0 ? start_kpa : kJammedMeanStressKpa; }
  // The strain norm of a loading path (ε̇_v > 0) when p reaches p_kpa.
  double LoadingStrainTo(double p_kpa) const {
    return (start_kpa > 0 ? 0 : jam_strain) +
           std::max(0.0, Compression(p_kpa) - Compression(loaded_start())) / volumetric;
  }

  // The affine bulk modulus of the network at p (Pa), K = Zφκp/(3π).
  double Modulus(double p_pa) const {
    if (law == dem::ContactLaw::kLinear) return modulus_factor * youngs_modulus / 2;
    const double stiffness = youngs_modulus / (1 - poissons_ratio * poissons_ratio);  // E/(1 − ν²)
    return modulus_factor * std::cbrt(stiffness * stiffness * std::max(p_pa, 0.0));
  }
  // p (kPa) at strain norm s of a path that does not load (ε̇_v ≤ 0).
  double NotLoadingAt(double s) const {
    if (start_kpa <= 0) return 0;
    if (volumetric == 0) return start_kpa;
    // Elastic unloading: dp/ds = −K(p)|ε̇_v/‖D‖|.
    const double rate = -volumetric;
    const double p0 = start_kpa * kKiloPascal;
    if (law == dem::ContactLaw::kLinear) {
      return std::max(0.0, p0 - Modulus(p0) * rate * s) / kKiloPascal;
    }
    // K = c p^{1/3}: p^{2/3} = p0^{2/3} − (2/3) c |v| s.
    const double c = Modulus(1.0);
    const double base = std::cbrt(p0 * p0) - 2.0 / 3.0 * c * rate * s;
    return base <= 0 ? 0 : std::pow(base, 1.5) / kKiloPascal;
  }
  // The strain norm at which p reaches `target` (kPa), or infinity.
  double StrainTo(double target) const {
    if (volumetric > 0) {
      if (start_kpa <= 0 && target <= kJammedMeanStressKpa) return jam_strain;
      return target > loaded_start() ? LoadingStrainTo(target) : kInfinity;
    }
    if (start_kpa <= 0 || volumetric == 0 || target >= start_kpa) return kInfinity;
    const double rate = -volumetric;
    const double p0 = start_kpa * kKiloPascal, p1 = std::max(target, 0.0) * kKiloPascal;
    if (law == dem::ContactLaw::kLinear) return (p0 - p1) / (Modulus(p0) * rate);
    const double c = Modulus(1.0);
    return 1.5 * (std::cbrt(p0 * p0) - std::cbrt(p1 * p1)) / (c * rate);
  }
};

// ∫ds/‖D‖(p(s)) over [from, to] of the strain norm and the p reached: along
// a loading path p is walked on a grid of ln p (the strain follows from it),
// along the others the strain is divided into equal parts.
struct Integral {
  double seconds = 0;        // of simulated time; the steps are seconds/Δt
  double loose_seconds = 0;  // of them, where an unloading has taken p to zero
  double end_p_kpa = 0;
};
Integral Integrate(const StressPath& path, double from, double to, bool at_floor,
                   double floor_rate) {
  Integral result;
  if (to <= from) {
    result.end_p_kpa = path.volumetric > 0 ? path.loaded_start() : path.NotLoadingAt(from);
    return result;
  }
  if (path.volumetric > 0) {
    constexpr double kLogStep = 0.005;  // of ln p
    double p = path.loaded_start(), s = std::max(path.LoadingStrainTo(p), from);
    while (s < to) {
      const double next_p = p * std::exp(kLogStep);
      double next_s = path.LoadingStrainTo(next_p);
      const bool last = next_s >= to || next_p > kLargestStressKpa;
      if (last) next_s = to;
      const double rate = at_floor ? floor_rate : path.speed(std::sqrt(p * next_p));
      result.seconds += (next_s - s) / rate;
      s = next_s;
      p = next_p;
      if (last) break;
    }
    result.end_p_kpa = p;
    return result;
  }
  const double ds = (to - from) / kIntegrationPoints;
  for (int k = 0; k < kIntegrationPoints; ++k) {
    const double s = from + (k + 0.5) * ds;
    const double p = path.NotLoadingAt(s);
    const double seconds = ds / (at_floor ? floor_rate : path.speed(p));
    result.seconds += seconds;
    // A packing unloaded to p = 0 is no longer jammed: loose steps.
    if (p <= 0) result.loose_seconds += seconds;
  }
  result.end_p_kpa = path.NotLoadingAt(to);
  return result;
}

// A stop's strain norm `s` replaces the end when it comes first.
void Consider(double s, const char* name, double* end, std::string* reason) {
  if (s >= 0 && s < *end) {
    *end = s;
    *reason = name;
  }
}

}  // namespace

StageSampleScales SampleScalesOf(const std::vector<double>& radii, double cell,
                                 const dem::Material& material, double time_step) {
  StageSampleScales scales;
  scales.time_step = time_step;
  scales.material = material;
  dem::Packing packing;
  packing.radii = radii;
  packing.cell = {cell, cell, cell};
  scales.context = dem::StageContext::Of(packing, material.density);
  scales.generated_solid_fraction = cell > 0 ? packing.SolidVolume() / (cell * cell * cell) : 0;
  return scales;
}

StageSteps EstimateStageSteps(const dem::Stage& stage, const StageSampleScales& scales,
                              double start_p_kpa) {
  const dem::StopConditions& stop = stage.stop;
  const double dt = scales.time_step;
  StageSteps result;
  result.stress_every_step = stop.mean_stress_kpa.has_value() || stage.As<dem::RestStage>() ||
                             stage.As<dem::TriaxialStage>();
  const double p0 = std::isnan(start_p_kpa) ? kUnknownStartKpa : std::max(start_p_kpa, 0.0);

  // Steps and time bound every stage.
  double step_cap = kInfinity;
  if (stop.steps) step_cap = static_cast<double>(*stop.steps);
  if (stop.time_s) step_cap = std::min(step_cap, *stop.time_s / dt);

  if (const auto* rest = stage.As<dem::RestStage>()) {
    result.steps = std::min(*rest->TypicalSteps(), step_cap);
    result.reason = result.steps == step_cap ? "steps" : "equilibrium";
    result.end_p_kpa = rest->mean_stress_kpa;
    return result;
  }

  // The stage's ‖D‖ and its strains per unit of strain norm.
  const auto* path = stage.As<dem::StrainPathStage>();
  const auto* triaxial = stage.As<dem::TriaxialStage>();
  double axial = 0, volumetric = 0, shear = 0, rate = 0;
  if (path) {
    const AxisymmetricRate unit = AxisymmetricRate::FromAngle(path->psi_epsilon(), 1.0);
    axial = unit.axial;
    volumetric = unit.volumetric();
    shear = unit.shear();
    if (std::abs(volumetric) < 1e-12) volumetric = 0;
    rate = path->stretching_rate;
  } else if (triaxial) {
    // At the critical state (ε̇_v = 0, ε̇_r = −ε̇_a/2): ‖D‖ = √1.5 |ε̇_a|.
    rate = std::sqrt(1.5) * std::abs(triaxial->axial_strain_rate);
    axial = (triaxial->axial_strain_rate > 0 ? 1 : -1) / std::sqrt(1.5);
    shear = axial;  // ε̇_s = 2(ε̇_a − ε̇_r)/3 = ε̇_a
  } else {
    rate = stage.spec->TypicalStrainRate(scales.material.density, p0);
  }
  const bool inertial = path && path->rule == dem::RateRule::kInertial;
  StressPath stress;
  stress.start_kpa = p0;
  stress.volumetric = triaxial ? 0 : volumetric;
  stress.speed = [&](double p_kpa) {
    return inertial ? path->inertial.Rate(p_kpa, scales.context, rate) : rate;
  };
  stress.diameter = scales.context.max_diameter;
  stress.density = scales.material.density;
  stress.generated_fraction = scales.generated_solid_fraction;
  stress.law = scales.material.contact_law;
  stress.youngs_modulus = scales.material.youngs_modulus;
  stress.poissons_ratio = scales.material.poissons_ratio;
  stress.modulus_factor = kIsostaticCoordination * kJammedSolidFraction / (3 * kPi);
  if (p0 <= 0 && stress.volumetric > 0 && scales.generated_solid_fraction > 0) {
    // The grains bear kJammedMeanStressKpa once the packing is as dense as
    // a flow at the inertial number of that stress allows.
    stress.jam_strain = std::max(0.0, std::log(stress.Fraction(kJammedMeanStressKpa) /
                                               scales.generated_solid_fraction)) /
                        stress.volumetric;
  }

  // The strain norm at which each predictable stop is reached.
  double end = kInfinity;
  std::string reason;
  if (stop.strain_norm) Consider(*stop.strain_norm, "strain_norm", &end, &reason);
  auto target = [&](const std::optional<double>& value, double per_strain, const char* name) {
    if (value && per_strain != 0 && *value / per_strain > 0) {
      Consider(*value / per_strain, name, &end, &reason);
    }
  };
  target(stop.axial_strain, axial, "axial_strain");
  target(stop.volumetric_strain, triaxial ? 0 : volumetric, "volumetric_strain");
  target(stop.shear_strain, shear, "shear_strain");
  const double cap = end;  // the caps alone
  const std::string cap_reason = reason;
  if (stop.mean_stress_kpa && !triaxial) {
    Consider(stress.StrainTo(*stop.mean_stress_kpa), "mean_stress_kpa", &end, &reason);
  }
  if (stop.asymptote) {
    const dem::AsymptoteCriterion& a = stage.asymptote;
    double s = kInfinity;
    if (a.kind == dem::PathKind::kIsochoric || a.kind == dem::PathKind::kStressControlled) {
      s = std::max(a.transient_strain, kShearTransientStrain) + a.window_strain;
    } else if (a.kind == dem::PathKind::kCompression && stress.volumetric > 0) {
      // One e-fold of p for the transient of ψ_σ, then the window in ln p.
      const double from = stress.loaded_start();
      const double transient = stress.LoadingStrainTo(from * std::exp(1.0));
      const double window = stress.LoadingStrainTo(from * std::exp(1.0 + a.window_lnp)) - transient;
      s = std::max(a.transient_strain, transient) + std::min(window, a.window_strain);
    }
    Consider(s, "asymptote", &end, &reason);
  }
  // The earliest end of a stage that may liquefy: its gas window after the
  // strain `gas` at which it may first be a gas.
  double earliest = end;
  double gas = kInfinity;
  if (stop.liquefied) {
    // Liquefaction may end the stage anywhere, and a sample that has been a
    // gas for a while reaches its asymptote later than the model says: only
    // the caps bound it, with p at the inertial rule's floor (the slowest
    // rate) throughout. The stops the model predicts are the low end's.
    result.at_most = true;
    const double predicted = end;
    if (cap < kInfinity) {
      end = cap;
      reason = cap_reason;
    }
    if (path && stress.volumetric < 0) {
      const bool extension = stage.asymptote.kind == dem::PathKind::kExtension;
      const double floor_kpa =
          extension ? stage.asymptote.floor_kpa : dem::kValidityLimits.gas_mean_stress_kpa;
      gas = p0 <= floor_kpa ? 0 : stress.StrainTo(floor_kpa);
    } else if (path && stress.volumetric == 0 && inertial) {
      gas = 0;
    }
    const double window = stop.liquefied_strain.value_or(stage.asymptote.window_strain);
    earliest = std::min(predicted, gas + window);
  }
  if (!(end < kInfinity)) {
    end = kFallbackStrain;
    earliest = end;
    reason = "no stop predicted: 0.3 of strain assumed";
  }
  result.strain = end;

  // The steps to strain `to`: before the generated sample jams at the rate
  // of p = 0 (the rule's floor), then over the modelled p (of a stage that
  // may liquefy under the inertial rule: at the floor, from strain
  // `modelled_until` on); their loose and still shares; and whether the
  // stage's step or time cap ends it first.
  const double floor_rate = stress.speed(0);
  const double still_share = 1 - std::min(1.0, floor_rate / kCollisionalStrainRate);
  struct Count {
    double steps = 0, loose = 0, still = 0, end_p_kpa = 0;
    bool capped = false;
  };
  auto count = [&](double to, double modelled_until) {
    const double jam = p0 <= 0 ? std::min(stress.jam_strain, to) : 0.0;
    const bool at_floor = inertial && stop.liquefied;
    const double split = at_floor ? std::clamp(modelled_until, jam, to) : to;
    const Integral modelled = Integrate(stress, jam, split, false, floor_rate);
    const Integral after = Integrate(stress, split, to, at_floor, floor_rate);
    Count c;
    c.loose = (jam / floor_rate + modelled.loose_seconds + after.loose_seconds) / dt;
    c.steps = (jam / floor_rate + modelled.seconds + after.seconds) / dt;
    c.end_p_kpa = split < to ? after.end_p_kpa : modelled.end_p_kpa;
    if (c.steps > step_cap) {
      c.steps = step_cap;
      c.loose = std::min(c.loose, step_cap);
      c.capped = true;
    }
    c.still = c.loose * still_share;
    return c;
  };
  const Count bound = count(end, 0);
  if (bound.capped) {
    reason = stop.steps && static_cast<double>(*stop.steps) == step_cap ? "steps" : "time_s";
  }
  result.steps = bound.steps;
  result.loose_steps = bound.loose;
  result.still_steps = bound.still;
  // The low end: the modelled p up to the first gas (at its own, faster
  // rate), then the floor.
  const Count first = earliest < end ? count(earliest, gas) : bound;
  result.earliest = {first.steps, first.loose, first.still, earliest};  // earliest <= end
  result.end_p_kpa = bound.end_p_kpa;
  if (triaxial) result.end_p_kpa = triaxial->radial_stress_kpa;
  if (stop.mean_stress_kpa && reason == "mean_stress_kpa") result.end_p_kpa = *stop.mean_stress_kpa;
  result.reason = reason + (result.at_most ? " (at most: it may liquefy earlier)" : "");
  return result;
}

}  // namespace granasym::study
