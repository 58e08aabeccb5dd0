#include "dem/run_start.h"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/hdf5_file.h"
#include "common/provenance.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

template <typename Value>
void HashVector(Sha256& hash, const std::vector<Value>& values) {
  hash.Update(values.data(), values.size() * sizeof(Value));
}

std::string HashPacking(const Packing& packing) {
  Sha256 hash;
  hash.Update(packing.cell.data(), sizeof(packing.cell));
  HashVector(hash, packing.positions);
  HashVector(hash, packing.radii);
  return hash.HexDigest();
}

std::string HashEngineState(const Engine::State& state) {
  Sha256 hash;
  HashVector(hash, state.position);
  HashVector(hash, state.velocity);
  HashVector(hash, state.spin);
  HashVector(hash, state.id);
  hash.Update(state.cell.data(), sizeof(state.cell));
  hash.Update(state.gradient.data(), sizeof(state.gradient));
  hash.Update(&state.time, sizeof(state.time));
  hash.Update(&state.step, sizeof(state.step));
  hash.Update(&state.time_step, sizeof(state.time_step));
  HashVector(hash, state.neighbors.offsets);
  HashVector(hash, state.neighbors.neighbors);
  HashVector(hash, state.neighbors.shear);
  HashVector(hash, state.neighbors.rolling);
  return hash.HexDigest();
}

}  // namespace

Provenance RunProvenance(const Scene& scene, int threads) {
  Provenance provenance;
  provenance.program_version = ProgramVersion();
  provenance.scene_canonical = scene.Canonical();
  provenance.scene_sha256 = Sha256Hex(provenance.scene_canonical);
  provenance.threads = threads;
  provenance.cpu_model = HostCpuModel();
  return provenance;
}

void StartFromSample(const Scene& scene, RunContents* contents) {
  contents->sample = scene.BuildSample(&contents->generation);
  contents->generated = scene.generate.has_value();
  contents->provenance.start_kind = contents->generated ? "generated" : "packing";
  contents->provenance.start_sha256 = HashPacking(contents->sample);
}

Engine::State StartFromParent(const Scene& scene, RunContents* contents) {
  const ParentState& parent = *scene.parent;
  const std::string where = scene.origin + ": sample.state '" + parent.path + "'";
  if (!std::filesystem::exists(parent.path)) {
    throw InputError(where + " does not exist (give the result file of a granasym DEM run)");
  }
  const Hdf5File file = Hdf5File::OpenRead(parent.path);
  if (!file.Exists(record::kSample) || !file.Exists(record::kSummary)) {
    throw InputError(where + " is not a granasym DEM result file (no /sample or /summary)");
  }
  contents->generated = ReadSample(file, &contents->sample, &contents->generation);
  const RunSummary summary = ReadSummary(file);
  const std::vector<StageRecord> records = ReadStageRecords(file);
  std::optional<Engine::State> state;
  const bool completed = summary.termination == Termination::kCompleted;
  const bool last = !records.empty() && records.back().name == parent.stage;
  if (parent.stage.empty() || (last && completed && !records.back().end_state)) {
    if (!completed) {
      throw InputError(fmt::format(
          "{}: the run ended '{}' ({}): only a completed run's final state, or the end of one of "
          "its completed stages (sample.stage), can be continued",
          where, ToString(summary.termination), summary.message));
    }
    state = ReadEngineState(file, std::string(record::kFinalState) + "/" + record::kEngineGroup);
  } else {
    std::string names;
    for (const StageRecord& r : records) {
      if (r.failed) continue;
      if (r.name == parent.stage) {
        if (!r.end_state) {
          throw InputError(
              fmt::format("{}: stage '{}' kept no end state (the run had "
                          "output.stage_states = false)",
                          where, parent.stage));
        }
        state = r.end_state;
        break;
      }
      names += (names.empty() ? "" : ", ") + ("'" + r.name + "'");
    }
    if (!state) {
      throw InputError(fmt::format("{}: no completed stage named '{}' (completed stages: {})",
                                   where, parent.stage, names.empty() ? "none" : names));
    }
  }
  Provenance& provenance = contents->provenance;
  provenance.start_kind = "state";
  provenance.start_sha256 = HashEngineState(*state);
  provenance.parent_file = parent.path;
  provenance.parent_stage = parent.stage;
  if (file.Exists(record::kProvenance)) {
    provenance.parent_scene_sha256 = ReadProvenance(file).scene_sha256;
  }
  return std::move(*state);
}

std::vector<std::string> StartLines(const Scene& scene, const Packing& sample, int threads,
                                    double time_step, const std::string& time_step_rule) {
  std::vector<std::string> lines;
  const ContactDurations d = ComputeContactDurations(sample.radii, scene.material);
  lines.push_back(
      fmt::format("{} spheres, {} threads; time step {:.4g} s = {:.3f} of the smallest contact "
                  "duration {:.4g} s (reduced mass; {:.4g} s with one sphere's mass; largest "
                  "{:.4g} / {:.4g} s); stability limit {:.4g} s",
                  sample.size(), threads, time_step, time_step / d.smallest_reduced_mass,
                  d.smallest_reduced_mass, d.smallest_single_mass, d.largest_reduced_mass,
                  d.largest_single_mass, d.critical_time_step));
  lines.push_back("time step " + time_step_rule);
  const Material& material = scene.material;
  if (material.stiffness_scaling != 1) {
    lines.push_back(fmt::format(
        "stiffness scaling {:g}: the contacts use E = {:.6g} MPa (of the grains' {:.6g} MPa); "
        "the stiffness number kappa falls with it",
        material.stiffness_scaling, material.contact_modulus() * 1e-6,
        material.youngs_modulus * 1e-6));
  }
  return lines;
}

}  // namespace granasym::dem
