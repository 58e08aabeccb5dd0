// A scene: the sample, the material, the numerics, the output and a chain of
// loading stages, read from a TOML file and validated with messages that name
// the file, the key, the value and the valid range (docs: README "Scene files").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dem/engine.h"
#include "dem/packing.h"

namespace granasym {
class ConfigTable;
}

namespace granasym::dem {

enum class StageType { kStrainPath, kTriaxial, kRest };
std::string ToString(StageType type);
StageType StageTypeFromString(const std::string& name);  // InputError if unknown

enum class Direction { kAuto, kRising, kFalling };

// Asymptotic-state criterion (SPEC §5): over the last `window_strain` of
// accumulated strain ∫‖D‖dt, sampled every `sample_strain`,
//  (1) the fitted change of ψ_σ across the window is below psi_tolerance_deg,
//  (2) the change of ln p across each half of the window differs between the
//      halves by less than lnp_tolerance (d ln p/dε is stationary, so the
//      state moves parallel to an asymptotic line, or stays at constant p).
struct AsymptoteCriterion {
  double sample_strain = 2e-3;
  double window_strain = 0.1;
  double psi_tolerance_deg = 0.5;
  double lnp_tolerance = 0.02;
  std::string Describe() const;
};

struct StopConditions {
  std::optional<double> mean_stress_kpa;
  Direction mean_stress_direction = Direction::kAuto;
  // Stage-relative strains, compression positive; reached when crossed.
  std::optional<double> axial_strain, volumetric_strain, shear_strain;
  std::optional<double> strain_norm;  // ∫‖D‖dt within the stage (> 0)
  std::optional<double> time_s;       // stage duration (s)
  std::optional<int64_t> steps;       // stage steps
  bool asymptote = false;             // stop when the asymptotic state is detected
  // Rest stages: equilibrium when |σ_ii − p*| <= stress_tolerance p* on each
  // axis and the unbalanced-force ratio <= unbalanced_force.
  double stress_tolerance = 0.01;
  double unbalanced_force = 1e-3;
};

struct ControlOptions {
  // Fraction of the stress error removed per step by the affine (Voigt)
  // stiffness; the true, relaxed stiffness is lower, so this is an upper
  // bound of the per-step correction.
  double gain = 0.2;
  // Integral gain per step on the same strain error (removes steady errors).
  double integral_gain = 0.01;
  // Largest controlled strain rate as a multiple of the stage's ‖D‖ scale.
  double max_rate_factor = 2.0;
  // Steps between stress/unbalanced-force checks of rest stages.
  int64_t check_interval = 50;
};

struct Stage {
  std::string name;
  StageType type = StageType::kStrainPath;
  double psi_epsilon = 0;        // strain path: ψ_ε (rad)
  double stretching_rate = 0;    // strain path: ‖D‖ (1/s); rest: largest rate
  double axial_strain_rate = 0;  // triaxial: ε̇_a, compression positive (1/s)
  double radial_stress_kpa = 0;  // triaxial: σ_r target
  double mean_stress_kpa = 0;    // rest: p target (isotropic)
  StopConditions stop;
  ControlOptions control;
  AsymptoteCriterion asymptote;
  bool detect_asymptote = false;  // run the detector (always on with stop.asymptote)
};

struct OutputOptions {
  double interval_strain = 1e-3;  // accumulated strain between rows
  int64_t interval_steps = 0;     // also a row every this many steps (0: off)
  bool overlap_histogram = false;
  int histogram_bins = 40;
  double histogram_min = 1e-6, histogram_max = 0.1;  // relative overlap range
  double checkpoint_interval_s = 600;  // wall-clock seconds between checkpoints
  double progress_interval_s = 10;     // between plain progress lines
};

struct Scene {
  std::string origin;  // file name
  std::string text;    // the scene as given
  // Sample: a packing file, or generation parameters.
  std::string packing_path;  // resolved relative to the scene file
  std::optional<GenerationOptions> generate;
  std::string gsd_path;  // empty: the default table
  Material material;
  std::optional<double> time_step_s;
  double time_step_fraction = 0.1;  // of the smallest contact duration (reduced mass)
  double skin_fraction = 0.3;
  int threads = 1;
  OutputOptions output;
  std::vector<Stage> stages;

  static Scene Load(const std::string& path);
  static Scene Parse(const std::string& text, const std::string& origin,
                     const std::string& base_directory);
  // Builds the sample (reads or generates it); `report` receives the GSD
  // comparison when generated.
  Packing BuildSample(GenerationReport* report) const;
  // The time step for a packing; throws InputError naming numerics.time_step_s
  // and the computed limit when it is above the stability limit.
  double TimeStep(const Packing& packing) const;
};

}  // namespace granasym::dem
