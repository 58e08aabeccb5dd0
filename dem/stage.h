// A loading stage of a DEM run: its parsed keys (a StageSpec of one stage
// type), the stop conditions every stage shares, and the controller that
// drives the cell while the stage runs.
//
// Adding a loading mode: write one file pair `<mode>_stage.h/.cc` with a
// StageSpec (its keys, parsed from the [[stage]] table, its canonical text
// and its description for the result file) and a StageController (start,
// whether it needs the stress this step, the velocity gradient it applies,
// its own stop check, its checkpointed state), and add its parser to the
// table in stage_types.cc. The run loop (simulation.cc) does not change.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/enum_names.h"
#include "dem/asymptote_detector.h"
#include "dem/engine.h"

namespace granasym {
class CanonicalText;
class ConfigTable;
class Hdf5File;
}  // namespace granasym

namespace granasym::dem {

// The name tables of common/enum_names.h serve dem/'s enumerations too.
using granasym::FromString;
using granasym::ToString;

// Which way the mean stress must cross its stop target; auto: away from the
// stage's first p.
enum class Direction { kAuto, kRising, kFalling };
}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::Direction> {
  static constexpr EnumEntry<dem::Direction> kEntries[] = {
      {dem::Direction::kAuto, "auto", "away from the stage's first mean stress"},
      {dem::Direction::kRising, "rising"},
      {dem::Direction::kFalling, "falling"},
  };
};

namespace granasym::dem {

// The stage types read stresses, rates and strains with the shared ranges
// of common/config.h (kStressKpa, kStrainRate, kStageStrain).
// The most steps one stage may take, and the smallest time step as a
// fraction of the smallest contact duration: below it a run resolves no
// more and only costs (the scene's feasibility check, dem/scene.h).
inline constexpr int64_t kMaxStageSteps = 1'000'000'000'000;
inline constexpr double kSmallestTimeStepFraction = 1e-4;

// Stop conditions shared by all stage types ([stage.stop]); any one ends the stage.
struct StopConditions {
  std::optional<double> mean_stress_kpa;
  Direction mean_stress_direction = Direction::kAuto;
  // Stage-relative logarithmic strains, compression positive; reached when crossed.
  std::optional<double> axial_strain, volumetric_strain, shear_strain;
  std::optional<double> strain_norm;  // ∫‖D‖dt within the stage (> 0)
  std::optional<double> time_s;       // stage duration (s)
  std::optional<int64_t> steps;       // stage steps
  bool asymptote = false;             // stop when the asymptotic state is detected
  // Stop when the sample has been a gas (SPEC §8.3: no load-bearing network
  // or no stress) on every output row over the detector's window_strain: it
  // has liquefied and no asymptote follows on a path that keeps dilating.
  bool liquefied = false;
  // The gas window of `liquefied` (strain norm; default the detector's
  // window_strain). Measured on the rate study's 5 000-sphere paths: no
  // dilating path (ψ_ε > 90°) at I* ≤ 3e-2 rebuilt its network after any gas
  // row (63 cases), while isochoric paths and ψ_ε = 100° at I* = 0.1 did after
  // up to 0.12 of strain of gas (studies/programmes/rate.toml).
  std::optional<double> liquefied_strain;
  bool any() const;
  static StopConditions Parse(const ConfigTable& stop);  // a [stage.stop] table
  void Canonical(CanonicalText& text, const std::string& prefix) const;
};

// Where the current stage started and how far it has gone: what the stop
// conditions and controllers measure against. Checkpointed.
struct StageClock {
  int64_t start_step = 0;
  double start_time = 0;
  std::array<double, 3> start_cell{};
  double start_p_kpa = std::numeric_limits<double>::quiet_NaN();  // first p measured
  double strain_norm = 0;                                         // ∫‖D‖dt since the start
  double next_sample_strain = 0;                                  // of the asymptote detector
  int64_t first_row = 0;
  // The closest approach to a mean-stress target (checked on output rows
  // that are not a gas): its distance |ln(p/target)| and the stage strain
  // where it was seen; the distance is infinite before the first such row.
  double target_distance = std::numeric_limits<double>::infinity();
  double target_distance_strain = 0;
  // The stage strain of the first of the latest output rows that were all a
  // gas (NaN when the last row was not a gas): stop.liquefied measures from it.
  double gas_since_strain = std::numeric_limits<double>::quiet_NaN();
  int64_t steps(const Engine& engine) const { return engine.step() - start_step; }
};

// Mean stress of the last stress sums (kPa, compression positive).
double MeanStressKpa(const Engine::Sums& sums);

// Stress controllers ([stage.control]). Rates are compression positive; the
// affine (Voigt) stiffness C of the contact network converts a stress error
// into a strain increment, so the law is dimensionally consistent and
// independent of the material's scale: Δε = gain · (σ* − σ)/C per step.
struct ControlOptions {
  // Fraction of the stress error removed per step by the affine stiffness;
  // the true, relaxed stiffness is lower, so this bounds the correction.
  double gain = 0.2;
  // Integral gain per step on the same strain error (removes steady errors).
  double integral_gain = 0.01;
  // Largest controlled strain rate as a multiple of the stage's rate scale.
  double max_rate_factor = 2.0;
  static ControlOptions Parse(const ConfigTable& table);  // missing keys keep defaults
  void Canonical(CanonicalText& text, const std::string& prefix) const;
};

// What a stage type does while its stage runs. Created at the stage start.
class StageController {
 public:
  virtual ~StageController() = default;
  // The velocity gradient D at the start of the stage (continuum sign, 1/s).
  virtual std::array<double, 3> Start() = 0;
  // Whether the force evaluation of this step must sum the stress (for the
  // controller or its stop check) and the affine stiffness.
  virtual bool NeedsStress(int64_t stage_steps) const = 0;
  virtual bool NeedsStiffness() const = 0;
  // The velocity gradient from the stress just measured; nullopt keeps it.
  virtual std::optional<std::array<double, 3>> Control(const Engine::Sums& sums,
                                                       double time_step) = 0;
  // A stop of the stage type's own (e.g. equilibrium), checked on steps
  // with stress after the shared conditions; the reason, or nullopt.
  virtual std::optional<std::string> CheckStop(const Engine& engine, int64_t stage_steps) const {
    return std::nullopt;
  }
  // Internal state (e.g. integral terms) for checkpoints.
  virtual std::vector<double> SaveState() const { return {}; }
  virtual void RestoreState(const std::vector<double>& state) {}
};

// What a stage's controller may need of the run besides its keys.
struct StageContext {
  double min_diameter = 0, median_diameter = 0,
         max_diameter = 0;  // of the sample (m); d_50 by mass
  double density = 0;       // solid density (kg/m³)
  // The diameters of `sample` and the solid `density`.
  static StageContext Of(const Packing& sample, double density);
};

// The parsed keys of one stage type.
class StageSpec {
 public:
  virtual ~StageSpec() = default;
  virtual std::string type() const = 0;  // the spelling of `type` in scene files
  // True when the type ends its stage without a [stage.stop] condition.
  virtual bool StopsByItself() const { return false; }
  // The kind of asymptote the stage can reach; nullopt: none (no detector).
  virtual std::optional<PathKind> path_kind() const { return std::nullopt; }
  // True when a stage of this spec continues the path of `previous` (the
  // same proportional straining), so that the asymptote detector keeps its
  // samples across the boundary (an NCL saved at several stresses).
  virtual bool ContinuesPath(const StageSpec& previous) const { return false; }
  virtual std::unique_ptr<StageController> MakeController(const StageContext& context) const = 0;
  // An upper bound of the stretching norm ‖D‖ the stage applies (1/s) and the
  // key that sets it: the scene's feasibility check bounds the steps a stage
  // needs from below with it.
  virtual double MaxStrainRate() const = 0;
  virtual const char* RateKey() const = 0;
  // The stretching norm ‖D‖ (1/s) the stage typically runs at, for cost
  // estimates (a study's shards and ETA): a rate rule at its target for a
  // grain of d = 1 mm (the default GSD's largest) at `mean_stress_kpa`.
  virtual double TypicalStrainRate(double density, double mean_stress_kpa) const {
    return 167.0;  // the paper's ‖D‖
  }
  // The steps it takes whatever its stop conditions say, or nullopt.
  virtual std::optional<double> TypicalSteps() const { return std::nullopt; }
  // The type's keys for the canonical scene (`prefix` ends with '.').
  virtual void Canonical(CanonicalText& text, const std::string& prefix) const = 0;
  // Attributes of the stage's record in the result file.
  virtual void Describe(Hdf5File& file, const std::string& group) const = 0;
};

struct Stage {
  std::string name;
  std::shared_ptr<const StageSpec> spec;
  StopConditions stop;
  AsymptoteCriterion asymptote;   // of the stage's path kind
  bool detect_asymptote = false;  // run the detector (always on with stop.asymptote)

  std::string type() const { return spec->type(); }
  template <typename Spec>
  const Spec* As() const {
    return dynamic_cast<const Spec*>(spec.get());
  }
  void Canonical(CanonicalText& text, const std::string& prefix) const;
  // Both stages detect asymptotes with the same criterion and this one
  // continues the path of `previous` (StageSpec::ContinuesPath).
  bool ContinuesDetection(const Stage& previous) const;
};

// The shared stop conditions, in the order of their reasons: the mean-stress
// target (needs stress), then strains, the strain norm, steps and time.
std::optional<std::string> MeanStressStop(const StopConditions& stop, const StageClock& clock,
                                          double p_kpa);
// The direction a mean-stress target is approached from (auto resolved).
Direction MeanStressDirection(const StopConditions& stop, const StageClock& clock);
bool StrainOrDurationStopReached(const StopConditions& stop, const StageClock& clock,
                                 const Engine& engine);
std::string StrainOrDurationReason(const StopConditions& stop, const StageClock& clock,
                                   const Engine& engine);

}  // namespace granasym::dem
