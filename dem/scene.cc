#include "dem/scene.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/error.h"
#include "common/state_measures.h"
#include "dem/scene_keys.h"
#include "dem/stage_types.h"

namespace granasym::dem {

Scene Scene::Load(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot open scene file '" + path + "'");
  std::stringstream buffer;
  buffer << file.rdbuf();
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  return Parse(buffer.str(), path, base.string());
}

Scene Scene::Parse(const std::string& text, const std::string& origin,
                   const std::string& base_directory) {
  const ConfigTable root = ConfigTable::ParseString(text, origin);
  root.UseKeys({&SceneKeys(), &StageKeys()});
  Scene scene;
  scene.origin = origin;
  scene.text = text;
  auto resolve = [&](const std::string& path) {
    const std::filesystem::path p(path);
    if (p.is_absolute() || base_directory.empty()) return p.string();
    return (std::filesystem::path(base_directory) / p).string();
  };

  const ConfigTable sample = root.GetTable("sample");
  const int sources =
      int{sample.Has("packing")} + int{sample.Has("generate")} + int{sample.Has("state")};
  if (sources != 1) {
    sample.Fail("packing",
                "[sample.generate] and state: give exactly one of them (a packing "
                "file, generation parameters, or the result file of a run to "
                "continue from)");
  }
  if (sample.Has("state")) {
    ParentState parent;
    parent.path = resolve(sample.GetString("state"));
    parent.stage = sample.GetString("stage", "");
    scene.parent = parent;
  } else if (sample.Has("stage")) {
    sample.Fail("stage", "applies only to a sample that starts from a state (sample.state)");
  }
  if (sample.Has("packing")) {
    scene.packing_path = resolve(sample.GetString("packing"));
  } else if (sample.Has("generate")) {
    const ConfigTable generate = sample.GetTable("generate");
    GenerationOptions options;
    options.count = static_cast<size_t>(generate.GetInt("count", 150000, Range::Closed(2, 2e9)));
    options.cell_size = generate.GetDouble("cell_size_mm", 31.0, Range::Closed(1e-3, 1e6)) * 1e-3;
    options.seed = static_cast<uint64_t>(generate.GetInt("seed", 1, Range::NonNegative()));
    options.max_attempts = static_cast<int>(
        generate.GetInt("max_attempts", options.max_attempts, Range::Closed(1, 1e9)));
    if (generate.Has("gsd")) scene.gsd_path = resolve(generate.GetString("gsd"));
    scene.generate = options;
  }

  if (root.Has("material")) scene.material = ParseMaterial(root.GetTable("material"));

  if (root.Has("numerics")) {
    const ConfigTable n = root.GetTable("numerics");
    if (n.Has("time_step_s") && n.Has("time_step_fraction")) {
      n.Fail("time_step_s",
             "and time_step_fraction are both given: give one of them (a fixed step, or the "
             "adaptive step as a fraction of the shortest contact duration)");
    }
    if (n.Has("time_step_s")) {
      scene.time_step_s = n.GetDouble("time_step_s", Range::Open(0.0, 1.0));
      for (const char* key : {"time_step_check_interval", "max_time_step_s"}) {
        if (n.Has(key)) {
          n.Fail(key,
                 "applies only to the adaptive time step (time_step_fraction), not to the fixed "
                 "time_step_s: remove one of them");
        }
      }
    }
    AdaptiveTimeStep::Options& adaptive = scene.adaptive_time_step;
    adaptive.fraction = n.GetDouble("time_step_fraction", adaptive.fraction,
                                    Range::Closed(kSmallestTimeStepFraction, 2.0 / kPi));
    adaptive.check_interval =
        n.GetInt("time_step_check_interval", adaptive.check_interval, Range::Closed(1, 1e6));
    adaptive.max_time_step =
        n.GetDouble("max_time_step_s", adaptive.max_time_step, Range::Open(0.0, 1.0));
    scene.skin_fraction =
        n.GetDouble("skin_fraction", scene.skin_fraction, {0.0, 2.0, false, true});
    scene.threads = static_cast<int>(n.GetInt("threads", 1, Range::Closed(1, 1024)));
  }

  if (root.Has("output")) {
    const ConfigTable o = root.GetTable("output");
    OutputOptions& output = scene.output;
    output.interval_strain =
        o.GetDouble("interval_strain", output.interval_strain, Range::Closed(1e-9, 1e9));
    output.interval_steps =
        o.GetInt("interval_steps", output.interval_steps, Range::Closed(0, kMaxStageSteps));
    output.overlap_histogram = o.GetBool("overlap_histogram", output.overlap_histogram);
    if (!output.overlap_histogram) {
      for (const char* key : {"histogram_bins", "histogram_min", "histogram_max"}) {
        if (o.Has(key)) o.Fail(key, "applies only with overlap_histogram = true");
      }
    }
    output.histogram_bins = static_cast<int>(
        o.GetInt("histogram_bins", output.histogram_bins, Range::Closed(1, 10000)));
    // Overlaps relative to the smaller radius: 0 < min < max <= 1.
    output.histogram_min =
        o.GetDouble("histogram_min", output.histogram_min, Range::Open(0.0, 1.0));
    output.histogram_max =
        o.GetDouble("histogram_max", output.histogram_max, {0.0, 1.0, false, true});
    if (!(output.histogram_min < output.histogram_max)) {
      o.Fail(o.Has("histogram_max") ? "histogram_max" : "histogram_min",
             fmt::format("must be above histogram_min: histogram_min = {:g}, histogram_max = {:g}",
                         output.histogram_min, output.histogram_max));
    }
    output.checkpoint_interval_s =
        o.GetDouble("checkpoint_interval_s", output.checkpoint_interval_s, {0.0, 1e9, false, true});
    output.progress_interval_s =
        o.GetDouble("progress_interval_s", output.progress_interval_s, {0.0, 1e9, false, true});
    output.stage_states = o.GetBool("stage_states", output.stage_states);
  }

  const std::vector<ConfigTable> stages = root.GetTableArray("stage");
  if (stages.empty()) {
    throw InputError(origin + ": no [[stage]] given: a scene needs at least one loading stage");
  }
  for (size_t k = 0; k < stages.size(); ++k) scene.stages.push_back(ParseStage(stages[k], k));
  root.CheckNoUnknownKeys();
  return scene;
}

std::vector<NamedPath> Scene::InputFiles() const {
  std::vector<NamedPath> files = {{"the scene file", origin}};
  if (!packing_path.empty()) files.push_back({"the packing file (sample.packing)", packing_path});
  if (!gsd_path.empty()) files.push_back({"the grain-size table (sample.generate.gsd)", gsd_path});
  if (parent) files.push_back({"the parent state (sample.state)", parent->path});
  return files;
}

std::string Scene::Canonical() const {
  CanonicalText text;
  if (parent) {
    text.Add("sample.source", "state");
    text.Add("sample.stage", parent->stage);
  } else if (generate) {
    text.Add("sample.source", "generate");
    text.Add("sample.generate.count", static_cast<int64_t>(generate->count));
    text.Add("sample.generate.cell_size_mm", generate->cell_size * 1e3);
    text.Add("sample.generate.seed", static_cast<int64_t>(generate->seed));
    text.Add("sample.generate.max_attempts", static_cast<int64_t>(generate->max_attempts));
    text.Add("sample.generate.gsd", gsd_path.empty() ? "default" : "file");
  } else {
    text.Add("sample.source", "packing");
  }
  material.Canonical(text, "material.");
  if (time_step_s) {
    text.Add("numerics.time_step_s", *time_step_s);
  } else {
    text.Add("numerics.time_step_fraction", adaptive_time_step.fraction);
    text.Add("numerics.time_step_check_interval", adaptive_time_step.check_interval);
    if (std::isfinite(adaptive_time_step.max_time_step)) {
      text.Add("numerics.max_time_step_s", adaptive_time_step.max_time_step);
    }
  }
  text.Add("numerics.skin_fraction", skin_fraction);
  text.Add("output.interval_strain", output.interval_strain);
  text.Add("output.interval_steps", output.interval_steps);
  text.Add("output.overlap_histogram", output.overlap_histogram);
  if (output.overlap_histogram) {
    text.Add("output.histogram_bins", output.histogram_bins);
    text.Add("output.histogram_min", output.histogram_min);
    text.Add("output.histogram_max", output.histogram_max);
  }
  text.Add("output.stage_states", output.stage_states);
  for (size_t k = 0; k < stages.size(); ++k) {
    stages[k].Canonical(text, "stage[" + std::to_string(k) + "].");
  }
  return text.Text();
}

Packing Scene::BuildSample(GenerationReport* report) const {
  GRANASYM_CHECK(!parent) << "the sample of a forked scene comes from its parent state";
  if (!packing_path.empty()) return Packing::ReadText(packing_path);
  const GrainSizeDistribution gsd = gsd_path.empty() ? GrainSizeDistribution::Default()
                                                     : GrainSizeDistribution::ReadCsv(gsd_path);
  try {
    return GeneratePacking(gsd, *generate, report);
  } catch (const InputError& error) {
    // What the generator refuses comes from [sample.generate]: say where.
    throw InputError(fmt::format("{}: [sample.generate] (count = {}, cell_size_mm = {:g}): {}",
                                 origin, generate->count, generate->cell_size * 1e3, error.what()));
  }
}

double Scene::TimeStep(const Packing& packing) const { return TimeStep(packing.radii); }

double Scene::TimeStep(const std::vector<double>& radii) const {
  const ContactDurations durations = ComputeContactDurations(radii, material);
  if (!time_step_s) {
    const AdaptiveTimeStep::Options& adaptive = adaptive_time_step;
    if (adaptive.fraction > durations.stability_fraction) {
      throw InputError(fmt::format(
          "{}: key 'numerics.time_step_fraction' = {:g} is above the stability limit {:.4g} of "
          "this material's contacts (the leapfrog limit as a fraction of a contact's duration{}): "
          "use at most {:.4g}, e.g. 0.1",
          origin, adaptive.fraction, durations.stability_fraction,
          material.has_friction() ? ", lowered by the tangential and rolling springs" : "",
          durations.stability_fraction));
    }
    const double smallest = kSmallestTimeStepFraction * durations.smallest_reduced_mass;
    if (adaptive.max_time_step < smallest) {
      throw InputError(fmt::format(
          "{}: key 'numerics.max_time_step_s' = {:g} s is below {:g} of the smallest contact "
          "duration {:.4g} s: such a step resolves nothing more and multiplies the cost; use at "
          "least {:.4g} s (or leave it out)",
          origin, adaptive.max_time_step, kSmallestTimeStepFraction,
          durations.smallest_reduced_mass, smallest));
    }
    return AdaptiveTimeStep(adaptive, material, radii).UpperBound();
  }
  if (*time_step_s < kSmallestTimeStepFraction * durations.smallest_reduced_mass) {
    throw InputError(fmt::format(
        "{}: key 'numerics.time_step_s' = {:g} s is below {:g} of the smallest contact duration "
        "{:.4g} s: such a step resolves nothing more and multiplies the cost; use at least "
        "{:.4g} s (or time_step_fraction in [{:g}, {:.4g}])",
        origin, *time_step_s, kSmallestTimeStepFraction, durations.smallest_reduced_mass,
        kSmallestTimeStepFraction * durations.smallest_reduced_mass, kSmallestTimeStepFraction,
        2.0 / kPi));
  }
  if (*time_step_s > durations.critical_time_step) {
    std::ostringstream message;
    message << origin << ": key 'numerics.time_step_s' = " << *time_step_s
            << " s is above the stability limit " << durations.critical_time_step
            << " s of the stiffest contact (smallest contact duration "
            << durations.smallest_reduced_mass
            << " s): use a smaller step, e.g. time_step_fraction = 0.1 of the contact duration";
    throw InputError(message.str());
  }
  return *time_step_s;
}

void Scene::CheckFeasible(double time_step) const {
  GRANASYM_CHECK(time_step > 0) << "time step " << time_step;
  for (size_t k = 0; k < stages.size(); ++k) {
    const Stage& stage = stages[k];
    const std::string key = fmt::format("stage[{}].", k);
    const double rate = stage.spec->MaxStrainRate();
    const double per_step = rate * time_step;
    if (!(per_step >= kSmallestStrainPerStep)) {
      throw InputError(fmt::format(
          "{}: stage '{}': key '{}{}' = {:g} 1/s with the time step {:.4g} s moves the cell by at "
          "most {:.3g} per step, below {:g}: the stage would need more than {:.3g} steps per unit "
          "strain; raise the rate (or the time step)",
          origin, stage.name, key, stage.spec->RateKey(), rate, time_step, per_step,
          kSmallestStrainPerStep, 1 / kSmallestStrainPerStep));
    }
    // Each stop the stage can reach, with the fewest steps it needs: a strain
    // component changes by at most sqrt(3) ‖D‖ per unit time.
    const StopConditions& stop = stage.stop;
    if (stop.mean_stress_kpa || stop.asymptote || stage.spec->StopsByItself()) continue;
    double fewest = std::numeric_limits<double>::infinity();
    std::string by;
    auto consider = [&](double steps, const std::string& name) {
      if (steps < fewest) fewest = steps, by = name;
    };
    const double component = std::sqrt(3.0) * per_step;
    if (stop.axial_strain) consider(std::abs(*stop.axial_strain) / component, "axial_strain");
    if (stop.volumetric_strain) {
      consider(std::abs(*stop.volumetric_strain) / component, "volumetric_strain");
    }
    if (stop.shear_strain) consider(std::abs(*stop.shear_strain) / component, "shear_strain");
    if (stop.strain_norm) consider(*stop.strain_norm / per_step, "strain_norm");
    if (stop.time_s) consider(*stop.time_s / time_step, "time_s");
    if (stop.steps) consider(static_cast<double>(*stop.steps), "steps");
    if (fewest > static_cast<double>(kMaxStageSteps)) {
      throw InputError(fmt::format(
          "{}: stage '{}': key '{}stop.{}' needs at least {:.3g} steps at {}{} = {:g} 1/s and the "
          "time step {:.4g} s, more than the {:g} a stage may take; raise the rate or lower the "
          "stop value",
          origin, stage.name, key, by, fewest, key, stage.spec->RateKey(), rate, time_step,
          static_cast<double>(kMaxStageSteps)));
    }
  }
}

}  // namespace granasym::dem
