// A scene: the sample, the material, the numerics, the output and a chain of
// loading stages, read from a TOML file and validated with messages that name
// the file, the key, the value and the valid range (docs: docs/guide/scenes.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/output_path.h"
#include "dem/adaptive_time_step.h"
#include "dem/engine.h"
#include "dem/packing.h"
#include "dem/stage.h"

namespace granasym {
class ConfigTable;
}

namespace granasym::dem {

struct OutputOptions {
  double interval_strain = 1e-3;  // accumulated strain between rows
  int64_t interval_steps = 0;     // also a row every this many steps (0: off)
  bool overlap_histogram = false;
  int histogram_bins = 40;
  double histogram_min = 1e-6, histogram_max = 0.1;  // relative overlap range
  double checkpoint_interval_s = 600;                // wall-clock seconds between checkpoints
  double progress_interval_s = 10;                   // between plain progress lines
  // Keep the exact state at the end of every stage but the last (the final
  // state is always kept) in the result file, so that runs can fork from it.
  bool stage_states = true;
};

// A run's starting state taken from another run's result file: its final
// state, or the end of one of its stages.
struct ParentState {
  std::string path;   // result file (resolved relative to the scene)
  std::string stage;  // empty: the final state
};

struct Scene {
  std::string origin;  // file name
  std::string text;    // the scene as given
  // Sample: exactly one of a packing file, generation parameters or the
  // state of another run.
  std::string packing_path;  // resolved relative to the scene file
  std::optional<GenerationOptions> generate;
  std::string gsd_path;  // empty: the default table
  std::optional<ParentState> parent;
  // The files the scene reads (itself, its packing, GSD table or parent
  // state), for the check that no output overwrites them.
  std::vector<NamedPath> InputFiles() const;
  Material material;
  // The time step: a fixed Δt (numerics.time_step_s), or else the adaptive
  // rule (numerics.time_step_fraction, time_step_check_interval,
  // max_time_step_s; dem/adaptive_time_step.h).
  std::optional<double> time_step_s;
  AdaptiveTimeStep::Options adaptive_time_step;
  bool adaptive() const { return !time_step_s.has_value(); }
  double skin_fraction = 0.3;
  int threads = 1;
  OutputOptions output;
  std::vector<Stage> stages;

  static Scene Load(const std::string& path);
  static Scene Parse(const std::string& text, const std::string& origin,
                     const std::string& base_directory);
  // Builds the sample (reads or generates it); `report` receives the GSD
  // comparison when generated. Not for scenes that start from a parent state.
  Packing BuildSample(GenerationReport* report) const;
  // The parsed, defaulted scene as canonical text: what the run computes,
  // without file names, thread counts and reporting intervals.
  std::string Canonical() const;
  // The time step for a packing: the fixed Δt, or the adaptive rule's upper
  // bound (its value before the first contact, AdaptiveTimeStep::UpperBound).
  // Throws InputError naming the key and the computed limit: a fixed Δt above
  // the stability limit or below kSmallestTimeStepFraction of the smallest
  // contact duration; a fraction above the material's stability fraction
  // (ContactDurations::stability_fraction); a max_time_step_s below
  // kSmallestTimeStepFraction of the smallest contact duration.
  double TimeStep(const Packing& packing) const;
  // The same for spheres of these radii (m): a cost estimate before any sample exists
  // (study plan: the radii a sample of the GSD at its count will have).
  double TimeStep(const std::vector<double>& radii) const;
  // What the scene implies at this time step (the largest the run takes),
  // checked before the first step:
  // every stage moves the cell by at least kSmallestStrainPerStep per step,
  // and a stage whose stops all bound its steps from below (strains, time,
  // steps) needs at most kMaxStageSteps. Throws InputError naming the stage,
  // its keys, and the estimate.
  void CheckFeasible(double time_step) const;
};

// The smallest strain per step a stage may move the cell by (1e12 steps per
// unit strain; the slowest runs of the studies take about 1e8).
inline constexpr double kSmallestStrainPerStep = 1e-12;

}  // namespace granasym::dem
