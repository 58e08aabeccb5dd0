// A study's plan: the programme expanded at one scale and thread count into
// samples and cases, each with its folder, its scene and the cache key of
// its inputs. Layout of a study folder:
//
//   DIR/study.toml                   the programme's name and hash, scale, threads, version
//   DIR/plan.tsv                     the programme's cases (what the folder's study is)
//   DIR/shards/<K>-of-<N>.toml       how shard K of a sharded run ended
//   DIR/samples/r<K>/packing.txt     the generated sample of replicate K (+ generation.txt, key,
//                                    packing.sha256: its hash as generated)
//   DIR/cases/r<K>/<case>/scene.toml the scene the case runs (forks from its parent's result)
//   DIR/cases/r<K>/<case>/case.toml  what the case is: key, parent, run, variables
//   DIR/cases/r<K>/<case>/result.h5  its result (result.h5.ckpt while it runs)
//   DIR/cases/r<K>/<case>/run.log    the DEM run's report (time step, stage ends, validity)
//   DIR/cases/r<K>/<case>/done.toml  written last: the key it was computed for, how it ended
//   DIR/models/<name>/               element tests of the constitutive models
//   DIR/asymptotic_states.csv/.h5    the state table (study/state_table.h)
//   DIR/index.html, DIR/report.md    the report (analysis/report.h)
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/results_version.h"
#include "dem/packing.h"
#include "study/programme.h"
#include "study/stage_steps.h"
#include "study/study_folder.h"

namespace granasym::study {

struct PlannedSample {
  int replicate = 1;
  dem::GenerationOptions options;
  std::string gsd_path;   // empty: the default table
  std::string key;        // SHA-256 of what generates it
  std::string directory;  // DIR/samples/r<K>
  std::string packing_path() const { return directory + "/packing.txt"; }
  // The SHA-256 of packing.txt as generated (hex), written beside it.
  std::string packing_sha256_path() const { return directory + "/packing.sha256"; }
};

struct PlannedCase {
  std::string id;  // "r<K>/<name>"
  int replicate = 1;
  CaseSpec spec;
  int parent = -1;  // index into Plan::cases; -1: the replicate's sample
  std::vector<int> children;
  std::string directory;   // DIR/cases/r<K>/<name>
  std::string scene_text;  // the complete scene, [sample] included
  std::string key;         // SHA-256 of the canonical scene, the parent's key, results key, threads
  KeyInputs inputs;        // what the key is made of (recorded in done.toml)
  int64_t particles = 0;
  double time_step = 0;  // (s): the scene's fixed step, or its adaptive rule's upper bound
  // The steps its stages' stop conditions imply at that step (ETA, shards,
  // study plan: study/stage_steps.h), of them those before the generated
  // sample jams and those that sum the stress on every step (their rates
  // differ: study/cost.h), and whether the figure is a bound (a stage that
  // may end earlier on liquefaction).
  double estimated_steps = 0;
  double estimated_loose_steps = 0;
  double estimated_still_steps = 0;  // of the loose ones, those whose grains do not collide
  double estimated_stress_steps = 0;
  bool steps_at_most = false;
  // The same if each stage that may liquefy does so as early as the model
  // allows (StageSteps::earliest): the low end of a bound's range.
  struct Earliest {
    double steps = 0, loose_steps = 0, still_steps = 0, stress_steps = 0;
  } estimated_earliest;
  std::vector<StageSteps> stage_steps;  // per stage, in order
  std::string result_path() const { return directory + "/result.h5"; }
};

// A constitutive-model element test of the programme (not replicated: the
// models are deterministic). Files: DIR/models/<name>/{test.toml, result.h5,
// result.csv, done.toml}.
struct PlannedModelCase {
  std::string id;  // "models/<name>"
  ModelCaseSpec spec;
  std::string directory;
  std::string key;  // SHA-256 of the test's TOML and the results key
};

struct Plan {
  Programme programme;
  Scale scale = Scale::kTiny;
  int threads = 1;
  std::string directory;
  std::string program_version;  // provenance only: no key depends on it
  std::string results_key;      // common/results_version.h: every key depends on it
  // SHA-256 of the programme as expanded at the scale (its name, sample,
  // cases with their scenes, parents and figures, model runs): the study's
  // identity in study.toml, beside the name, so that shards of two
  // programmes of one name are never mixed.
  std::string programme_sha256;
  std::vector<PlannedSample> samples;  // one per replicate
  std::vector<PlannedCase> cases;      // parents before children
  std::vector<PlannedModelCase> model_cases;

  // Plans the programme at the scale it was expanded at (Programme::scale);
  // every case's scene is parsed here, so that bad input fails before
  // anything runs (the message names the programme and the case).
  // The keys depend on `results_key` (common/results_version.h, this
  // build's by default), never on the program version.
  static Plan Make(const Programme& programme, int threads, const std::string& directory,
                   const std::string& results_key = ResultsKey());
  // The cases of shard `index` (1-based) of `count`: the leaves are dealt
  // out by estimated cost (longest first to the least loaded shard), and
  // every shard includes the ancestors of its leaves (computed once, by
  // whichever shard gets there first). In dependency order.
  std::vector<int> Shard(int index, int count) const;
  // The cases of the replicates in `sample_keys` keyed on those sample keys
  // instead of their samples' (and their descendants on their new keys): a
  // sample whose packing.txt is not the one its key generates (an edited
  // file) is keyed on its content (PackingSampleKey), so that the NCL and
  // everything forked from it are computed again from it.
  void KeyOnSamples(const std::map<int, std::string>& sample_keys);
  int Find(const std::string& id) const;  // -1 when absent
};

// The key standing in for a sample's key when its packing's SHA-256 is not
// the one recorded when it was generated.
std::string PackingSampleKey(const std::string& sample_key, const std::string& packing_sha256);

// The text of DIR/study.toml for a plan.
std::string StudyRecordText(const Plan& plan);

}  // namespace granasym::study
