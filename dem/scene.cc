#include "dem/scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/config.h"
#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::dem {

std::string ToString(StageType type) {
  switch (type) {
    case StageType::kStrainPath: return "strain_path";
    case StageType::kTriaxial: return "triaxial";
    case StageType::kRest: return "rest";
  }
  return "unknown";
}

StageType StageTypeFromString(const std::string& name) {
  for (StageType type : {StageType::kStrainPath, StageType::kTriaxial, StageType::kRest}) {
    if (ToString(type) == name) return type;
  }
  throw InputError("unknown stage type '" + name + "': expected strain_path, triaxial or rest");
}

std::string AsymptoteCriterion::Describe() const {
  std::ostringstream out;
  out << "over the last " << window_strain << " of accumulated strain (samples every "
      << sample_strain << "): fitted change of psi_sigma < " << psi_tolerance_deg
      << " deg, and the changes of ln p over the two half-windows differ by < " << lnp_tolerance;
  return out.str();
}

namespace {

std::optional<double> OptionalDouble(const ConfigTable& table, const std::string& key, Range range) {
  if (!table.Has(key)) return std::nullopt;
  return table.GetDouble(key, range);
}

Stage ParseStage(const ConfigTable& table, size_t index) {
  Stage stage;
  stage.name = table.GetString("name", "stage" + std::to_string(index + 1));
  const std::string type =
      table.GetChoice("type", {"strain_path", "triaxial", "rest"}, "strain_path");
  stage.type = StageTypeFromString(type);
  switch (stage.type) {
    case StageType::kStrainPath:
      stage.psi_epsilon = table.GetDouble("psi_epsilon_deg", Range::Closed(-180, 180)) * kDegree;
      stage.stretching_rate = table.GetDouble("stretching_rate", Range::Positive());
      break;
    case StageType::kTriaxial:
      stage.axial_strain_rate = table.GetDouble("axial_strain_rate", Range::Any());
      if (stage.axial_strain_rate == 0) {
        table.Fail("axial_strain_rate", "= 0: must be non-zero (1/s, compression positive)");
      }
      stage.radial_stress_kpa = table.GetDouble("radial_stress_kpa", Range::Positive());
      stage.stretching_rate = std::abs(stage.axial_strain_rate);
      break;
    case StageType::kRest:
      stage.mean_stress_kpa = table.GetDouble("mean_stress_kpa", Range::Positive());
      stage.stretching_rate = table.GetDouble("max_strain_rate", 10.0, Range::Positive());
      break;
  }
  if (table.Has("control")) {
    const ConfigTable control = table.GetTable("control");
    stage.control.gain = control.GetDouble("gain", stage.control.gain, Range::Open(0, 1));
    stage.control.integral_gain =
        control.GetDouble("integral_gain", stage.control.integral_gain, Range::Closed(0, 1));
    stage.control.max_rate_factor =
        control.GetDouble("max_rate_factor", stage.control.max_rate_factor, Range::Positive());
    stage.control.check_interval =
        control.GetInt("check_interval", stage.control.check_interval, Range::AtLeast(1));
  }
  if (table.Has("asymptote")) {
    const ConfigTable a = table.GetTable("asymptote");
    AsymptoteCriterion& c = stage.asymptote;
    c.sample_strain = a.GetDouble("sample_strain", c.sample_strain, Range::Positive());
    c.window_strain = a.GetDouble("window_strain", c.window_strain, Range::Positive());
    c.psi_tolerance_deg = a.GetDouble("psi_tolerance_deg", c.psi_tolerance_deg, Range::Positive());
    c.lnp_tolerance = a.GetDouble("lnp_tolerance", c.lnp_tolerance, Range::Positive());
    if (c.window_strain < 8 * c.sample_strain) {
      a.Fail("window_strain", "= " + std::to_string(c.window_strain) +
                                  " must be at least 8 times sample_strain (" +
                                  std::to_string(c.sample_strain) + ")");
    }
    stage.detect_asymptote = true;
  }
  if (!table.Has("stop")) {
    table.Fail("stop", "is missing: every stage needs a [stage.stop] table with at least one of "
                       "mean_stress_kpa, axial_strain, volumetric_strain, shear_strain, "
                       "strain_norm, time_s, steps, asymptote (rest stages stop at equilibrium)");
  }
  const ConfigTable stop = table.GetTable("stop");
  StopConditions& s = stage.stop;
  s.mean_stress_kpa = OptionalDouble(stop, "mean_stress_kpa", Range::Positive());
  const std::string direction = stop.GetChoice("direction", {"auto", "rising", "falling"}, "auto");
  s.mean_stress_direction = direction == "rising"    ? Direction::kRising
                            : direction == "falling" ? Direction::kFalling
                                                     : Direction::kAuto;
  s.axial_strain = OptionalDouble(stop, "axial_strain", Range::Any());
  s.volumetric_strain = OptionalDouble(stop, "volumetric_strain", Range::Any());
  s.shear_strain = OptionalDouble(stop, "shear_strain", Range::Any());
  s.strain_norm = OptionalDouble(stop, "strain_norm", Range::Positive());
  s.time_s = OptionalDouble(stop, "time_s", Range::Positive());
  if (stop.Has("steps")) s.steps = stop.GetInt("steps", Range::AtLeast(1));
  s.asymptote = stop.GetBool("asymptote", false);
  s.stress_tolerance = stop.GetDouble("stress_tolerance", s.stress_tolerance, Range::Open(0, 1));
  s.unbalanced_force = stop.GetDouble("unbalanced_force", s.unbalanced_force, Range::Positive());
  if (s.asymptote) stage.detect_asymptote = true;
  const bool any = s.mean_stress_kpa || s.axial_strain || s.volumetric_strain || s.shear_strain ||
                   s.strain_norm || s.time_s || s.steps || s.asymptote ||
                   stage.type == StageType::kRest;
  if (!any) {
    stop.Fail("", "has no stop condition: give at least one of mean_stress_kpa, axial_strain, "
                  "volumetric_strain, shear_strain, strain_norm, time_s, steps, asymptote");
  }
  return stage;
}

}  // namespace

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
  Scene scene;
  scene.origin = origin;
  scene.text = text;
  auto resolve = [&](const std::string& path) {
    const std::filesystem::path p(path);
    if (p.is_absolute() || base_directory.empty()) return p.string();
    return (std::filesystem::path(base_directory) / p).string();
  };

  const ConfigTable sample = root.GetTable("sample");
  if (sample.Has("packing") == sample.Has("generate")) {
    sample.Fail("packing", "and [sample.generate]: give exactly one of them");
  }
  if (sample.Has("packing")) {
    scene.packing_path = resolve(sample.GetString("packing"));
  } else {
    const ConfigTable generate = sample.GetTable("generate");
    GenerationOptions options;
    options.count =
        static_cast<size_t>(generate.GetInt("count", 150000, Range::Closed(2, 2e9)));
    options.cell_size = generate.GetDouble("cell_size_mm", 31.0, Range::Positive()) * 1e-3;
    options.seed = static_cast<uint64_t>(generate.GetInt("seed", 1, Range::NonNegative()));
    options.max_attempts = static_cast<int>(
        generate.GetInt("max_attempts", options.max_attempts, Range::Closed(1, 1e9)));
    if (generate.Has("gsd")) scene.gsd_path = resolve(generate.GetString("gsd"));
    scene.generate = options;
  }

  if (root.Has("material")) {
    const ConfigTable m = root.GetTable("material");
    Material& material = scene.material;
    material.youngs_modulus =
        m.GetDouble("youngs_modulus_mpa", material.youngs_modulus * 1e-6, Range::Positive()) * 1e6;
    material.stiffness_ratio =
        m.GetDouble("stiffness_ratio", material.stiffness_ratio, Range::NonNegative());
    material.friction_angle = m.GetDouble("friction_angle_rad", material.friction_angle,
                                          {0.0, kPi / 2, true, false});
    material.density = m.GetDouble("density_kg_m3", material.density, Range::Positive());
    material.local_damping =
        m.GetDouble("local_damping", material.local_damping, {0.0, 1.0, true, false});
  }

  if (root.Has("numerics")) {
    const ConfigTable n = root.GetTable("numerics");
    if (n.Has("time_step_s") && n.Has("time_step_fraction")) {
      n.Fail("time_step_s", "and time_step_fraction are both given: give one of them");
    }
    if (n.Has("time_step_s")) scene.time_step_s = n.GetDouble("time_step_s", Range::Positive());
    scene.time_step_fraction = n.GetDouble("time_step_fraction", scene.time_step_fraction,
                                           {0.0, 2.0 / kPi, false, true});
    scene.skin_fraction = n.GetDouble("skin_fraction", scene.skin_fraction, {0.0, 2.0, false, true});
    scene.threads = static_cast<int>(n.GetInt("threads", 1, Range::Closed(1, 1024)));
  }

  if (root.Has("output")) {
    const ConfigTable o = root.GetTable("output");
    OutputOptions& output = scene.output;
    output.interval_strain = o.GetDouble("interval_strain", output.interval_strain, Range::Positive());
    output.interval_steps = o.GetInt("interval_steps", output.interval_steps, Range::NonNegative());
    output.overlap_histogram = o.GetBool("overlap_histogram", output.overlap_histogram);
    output.histogram_bins =
        static_cast<int>(o.GetInt("histogram_bins", output.histogram_bins, Range::Closed(1, 10000)));
    output.histogram_min = o.GetDouble("histogram_min", output.histogram_min, Range::Positive());
    output.histogram_max =
        o.GetDouble("histogram_max", output.histogram_max, Range::Open(output.histogram_min, 1.0));
    output.checkpoint_interval_s =
        o.GetDouble("checkpoint_interval_s", output.checkpoint_interval_s, Range::Positive());
    output.progress_interval_s =
        o.GetDouble("progress_interval_s", output.progress_interval_s, Range::Positive());
  }

  const std::vector<ConfigTable> stages = root.GetTableArray("stage");
  if (stages.empty()) {
    throw InputError(origin + ": no [[stage]] given: a scene needs at least one loading stage");
  }
  for (size_t k = 0; k < stages.size(); ++k) scene.stages.push_back(ParseStage(stages[k], k));
  root.CheckNoUnknownKeys();
  return scene;
}

Packing Scene::BuildSample(GenerationReport* report) const {
  if (!packing_path.empty()) return Packing::ReadText(packing_path);
  const GrainSizeDistribution gsd =
      gsd_path.empty() ? GrainSizeDistribution::Default() : GrainSizeDistribution::ReadCsv(gsd_path);
  return GeneratePacking(gsd, *generate, report);
}

double Scene::TimeStep(const Packing& packing) const {
  const ContactDurations durations = ComputeContactDurations(packing.radii, material);
  if (!time_step_s) return time_step_fraction * durations.smallest_reduced_mass;
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

}  // namespace granasym::dem
