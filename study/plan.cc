#include "study/plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/provenance.h"
#include "common/results_version.h"
#include "common/text_file.h"
#include "dem/grain_size_distribution.h"
#include "dem/scene.h"

namespace granasym::study {
namespace {

// A framed field of a cache key: a name, the length and the bytes, so that
// no two different inputs give the same hashed text.
void AddField(Sha256& hash, const std::string& name, const std::string& value) {
  hash.Update(name + "=" + std::to_string(value.size()) + ":");
  hash.Update(value);
  hash.Update("\n");
}

// A case's key and its inputs (done.toml) from its canonical scene and its
// parent's (or sample's) key.
void KeyCase(const std::string& canonical, const std::string& parent_key,
             const std::string& results_key, int threads, PlannedCase* c) {
  Sha256 hash;
  AddField(hash, "kind", "granasym-study-case-v2");
  AddField(hash, "scene", canonical);
  AddField(hash, "parent", parent_key);
  AddField(hash, "parent_stage", c->spec.parent_stage);
  AddField(hash, "results", results_key);
  AddField(hash, "threads", std::to_string(threads));
  c->key = hash.HexDigest();
  c->inputs = {Sha256Hex(canonical), parent_key, results_key, threads};
}

}  // namespace

std::string PackingSampleKey(const std::string& sample_key, const std::string& packing_sha256) {
  Sha256 hash;
  AddField(hash, "kind", "granasym-study-edited-sample-v1");
  AddField(hash, "sample", sample_key);
  AddField(hash, "packing_sha256", packing_sha256);
  return hash.HexDigest();
}

void Plan::KeyOnSamples(const std::map<int, std::string>& sample_keys) {
  for (PlannedCase& c : cases) {
    const auto it = sample_keys.find(c.replicate);
    if (it == sample_keys.end()) continue;
    const std::string parent_key =
        c.parent < 0 ? it->second : cases[static_cast<size_t>(c.parent)].key;
    const dem::Scene scene =
        dem::Scene::Parse(c.scene_text, c.directory + "/scene.toml", c.directory);
    KeyCase(scene.Canonical(), parent_key, results_key, threads, &c);
  }
}

Plan Plan::Make(const Programme& programme, int threads, const std::string& directory,
                const std::string& results_key) {
  const Scale scale = programme.scale;
  Plan plan;
  plan.programme = programme;
  plan.scale = scale;
  plan.threads = threads;
  plan.directory = directory;
  plan.program_version = ProgramVersion();
  plan.results_key = results_key;
  const ScaleSpec& spec = programme.At(scale);
  // The radii every replicate's sample will have (the generator places the
  // GSD's number quantiles): the cases' time steps for their cost estimates.
  const std::vector<double> radii =
      (programme.sample.gsd_path.empty()
           ? dem::GrainSizeDistribution::Default()
           : dem::GrainSizeDistribution::ReadCsv(programme.sample.gsd_path))
          .QuantileRadii(static_cast<size_t>(spec.count));
  const double cell_m = programme.sample.CellSizeMm(spec.count) * 1e-3;
  const std::string gsd_text =
      programme.sample.gsd_path.empty() ? "default" : ReadTextFile(programme.sample.gsd_path);
  for (int r = 1; r <= spec.replicates; ++r) {
    PlannedSample sample;
    sample.replicate = r;
    sample.options.count = static_cast<size_t>(spec.count);
    sample.options.cell_size = programme.sample.CellSizeMm(spec.count) * 1e-3;
    sample.options.seed = static_cast<uint64_t>(programme.sample.seed + r - 1);
    sample.options.max_attempts = static_cast<int>(programme.sample.max_attempts);
    sample.gsd_path = programme.sample.gsd_path;
    std::string why;
    if (!sample.options.IsValid(&why)) {
      throw InputError(programme.origin + ": the sample at scale " + ToString(scale) + ": " + why);
    }
    Sha256 hash;
    AddField(hash, "kind", "granasym-study-sample-v2");
    AddField(hash, "count", std::to_string(sample.options.count));
    std::ostringstream cell;
    cell.precision(17);
    cell << sample.options.cell_size;
    AddField(hash, "cell_size_m", cell.str());
    AddField(hash, "seed", std::to_string(sample.options.seed));
    AddField(hash, "max_attempts", std::to_string(sample.options.max_attempts));
    AddField(hash, "gsd", gsd_text);
    AddField(hash, "results", plan.results_key);
    sample.key = hash.HexDigest();
    sample.directory = directory + "/samples/r" + std::to_string(r);
    plan.samples.push_back(sample);
  }
  std::map<std::string, int> index;              // case id → index in plan.cases
  std::vector<std::vector<double>> stage_end_p;  // per case: the mean stress at its stages' ends
  for (int r = 1; r <= spec.replicates; ++r) {
    const std::string replicate = "r" + std::to_string(r);
    for (const CaseSpec& case_spec : programme.cases) {
      PlannedCase c;
      c.id = replicate + "/" + case_spec.name;
      c.replicate = r;
      c.spec = case_spec;
      c.directory = directory + "/cases/" + c.id;
      c.particles = spec.count;
      std::string sample_table = "[sample]\n";
      std::string parent_key;
      if (case_spec.parent.empty()) {
        sample_table +=
            "packing = " + TomlQuoted("../../../samples/" + replicate + "/packing.txt") + "\n";
        parent_key = plan.samples[static_cast<size_t>(r - 1)].key;
      } else {
        const auto parent = index.find(replicate + "/" + case_spec.parent);
        GRANASYM_CHECK(parent != index.end()) << "the programme orders parents first";
        c.parent = parent->second;
        GRANASYM_CHECK(c.parent >= 0) << "the programme orders parents first";
        sample_table += "state = " + TomlQuoted("../" + case_spec.parent + "/result.h5") + "\n";
        if (!case_spec.parent_stage.empty()) {
          sample_table += "stage = " + TomlQuoted(case_spec.parent_stage) + "\n";
        }
        parent_key = plan.cases[static_cast<size_t>(c.parent)].key;
      }
      c.scene_text = sample_table + "\n" + case_spec.scene_body;
      dem::Scene scene;
      try {
        scene = dem::Scene::Parse(c.scene_text, c.directory + "/scene.toml", c.directory);
      } catch (const InputError& error) {
        throw InputError(programme.origin + ": case '" + case_spec.name + "' (from [[run]] '" +
                         case_spec.run + "'): " + error.what());
      }
      KeyCase(scene.Canonical(), parent_key, plan.results_key, threads, &c);
      double time_step = 0;
      try {
        time_step = scene.TimeStep(radii);
      } catch (const InputError& error) {
        throw InputError(programme.origin + ": case '" + case_spec.name + "' (from [[run]] '" +
                         case_spec.run + "'): " + error.what());
      }
      c.time_step = time_step;
      // The mean stress each stage starts at: 0 for the generated sample, the
      // parent's at its fork (the end of its stage parent_stage, else its last).
      double p_kpa = 0;
      if (c.parent >= 0) {
        const std::vector<double>& parent_p = stage_end_p[static_cast<size_t>(c.parent)];
        const std::vector<std::string>& names =
            plan.cases[static_cast<size_t>(c.parent)].spec.stage_names;
        p_kpa = parent_p.empty() ? std::numeric_limits<double>::quiet_NaN() : parent_p.back();
        for (size_t s = 0; s < names.size() && s < parent_p.size(); ++s) {
          if (names[s] == case_spec.parent_stage) p_kpa = parent_p[s];
        }
      }
      std::vector<double> ends;
      const StageSampleScales scales = SampleScalesOf(radii, cell_m, scene.material, time_step);
      for (const dem::Stage& stage : scene.stages) {
        const StageSteps steps = EstimateStageSteps(stage, scales, p_kpa);
        c.estimated_steps += steps.steps;
        c.estimated_loose_steps += steps.loose_steps;
        c.estimated_still_steps += steps.still_steps;
        if (steps.stress_every_step) c.estimated_stress_steps += steps.steps - steps.loose_steps;
        c.steps_at_most = c.steps_at_most || steps.at_most;
        PlannedCase::Earliest& first = c.estimated_earliest;
        first.steps += steps.earliest.steps;
        first.loose_steps += steps.earliest.loose_steps;
        first.still_steps += steps.earliest.still_steps;
        if (steps.stress_every_step) {
          first.stress_steps += steps.earliest.steps - steps.earliest.loose_steps;
        }
        c.stage_steps.push_back(steps);
        p_kpa = steps.end_p_kpa;
        ends.push_back(p_kpa);
      }
      stage_end_p.push_back(ends);
      if (c.parent >= 0)
        plan.cases[static_cast<size_t>(c.parent)].children.push_back(
            static_cast<int>(plan.cases.size()));
      index.emplace(c.id, static_cast<int>(plan.cases.size()));
      plan.cases.push_back(std::move(c));
    }
  }
  Sha256 identity;
  AddField(identity, "kind", "granasym-programme-v1");
  AddField(identity, "name", programme.name);
  AddField(identity, "scale", ToString(scale));
  AddField(identity, "replicates", std::to_string(spec.replicates));
  for (const PlannedSample& sample : plan.samples) {
    AddField(identity, "sample",
             std::to_string(sample.options.count) + "/" + std::to_string(sample.options.seed) +
                 "/" + std::to_string(sample.options.max_attempts));
    std::ostringstream cell;
    cell.precision(17);
    cell << sample.options.cell_size;
    AddField(identity, "cell_size_m", cell.str());
  }
  AddField(identity, "gsd", gsd_text);
  AddField(identity, "ncl", programme.ncl_case);
  for (const CaseSpec& c : programme.cases) {
    AddField(identity, "case", c.name);
    AddField(identity, "parent", c.parent);
    AddField(identity, "parent_stage", c.parent_stage);
    AddField(identity, "run", c.run);
    AddField(identity, "figures", c.figures.Text());
    AddField(identity, "scene", c.scene_body);
  }
  for (const ModelCaseSpec& model : programme.model_cases) {
    AddField(identity, "model_run", model.name);
    AddField(identity, "test", model.text);
  }
  plan.programme_sha256 = identity.HexDigest();
  for (const ModelCaseSpec& model : programme.model_cases) {
    PlannedModelCase m;
    m.id = "models/" + model.name;
    m.spec = model;
    m.directory = directory + "/" + m.id;
    Sha256 hash;
    AddField(hash, "kind", "granasym-study-model-v2");
    AddField(hash, "test", model.text);
    AddField(hash, "results", plan.results_key);
    m.key = hash.HexDigest();
    plan.model_cases.push_back(std::move(m));
  }
  return plan;
}

int Plan::Find(const std::string& id) const {
  for (size_t k = 0; k < cases.size(); ++k) {
    if (cases[k].id == id) return static_cast<int>(k);
  }
  return -1;
}

std::vector<int> Plan::Shard(int index, int count) const {
  GRANASYM_CHECK(count >= 1 && index >= 1 && index <= count) << "shard " << index << "/" << count;
  std::vector<int> leaves;
  for (size_t k = 0; k < cases.size(); ++k) {
    if (cases[k].children.empty()) leaves.push_back(static_cast<int>(k));
  }
  auto cost = [this](int k) {
    return static_cast<double>(cases[static_cast<size_t>(k)].particles) *
           cases[static_cast<size_t>(k)].estimated_steps;
  };
  std::stable_sort(leaves.begin(), leaves.end(), [&](int a, int b) { return cost(a) > cost(b); });
  std::vector<double> load(static_cast<size_t>(count), 0.0);
  std::vector<bool> wanted(cases.size(), false);
  for (int leaf : leaves) {
    const size_t target =
        static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[target] += cost(leaf);
    if (static_cast<int>(target) + 1 != index) continue;
    for (int k = leaf; k >= 0; k = cases[static_cast<size_t>(k)].parent) {
      wanted[static_cast<size_t>(k)] = true;
    }
  }
  std::vector<int> selected;
  for (size_t k = 0; k < cases.size(); ++k) {
    if (wanted[k]) selected.push_back(static_cast<int>(k));
  }
  return selected;
}

std::string StudyRecordText(const Plan& plan) {
  std::ostringstream out;
  out << "# written by granasym study run; describes the cases below cases/\n"
      << "programme = " << TomlQuoted(plan.programme.name) << "\n"
      << "programme_file = "
      << TomlQuoted(std::filesystem::path(plan.programme.origin).filename().string()) << "\n"
      << "scale = " << TomlQuoted(ToString(plan.scale)) << "\n"
      << "threads = " << plan.threads << "\n"
      << "replicates = " << plan.samples.size() << "\n"
      << "count = " << plan.programme.At(plan.scale).count << "\n"
      << "ncl = " << TomlQuoted(plan.programme.ncl_case) << "\n"
      << "programme_sha256 = " << TomlQuoted(plan.programme_sha256) << "\n"
      << "program_version = " << TomlQuoted(plan.program_version) << "\n";
  // The programme's [figures] table, read by `study figures`.
  const std::string figures = plan.programme.figures.ToToml();
  if (!figures.empty()) out << "\n" << figures;
  return out.str();
}

}  // namespace granasym::study
