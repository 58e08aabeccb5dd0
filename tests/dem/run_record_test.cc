// Runs that fork from saved states, the provenance of result files, and the
// records shared by result files and checkpoints.
#include "dem/run_record.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <vector>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

using testing::SampleToml;

// Per process: ctest may run the tests of this file in parallel processes.
std::string TempPath(const std::string& name) {
  return testing::TempPath(std::to_string(getpid()) + "_" + name);
}

const std::string kStageA = testing::NclStage(150.0);
const std::string kStageB = testing::TriaxialStage(150.0, 0.02);
const char* kOutput = "[output]\ninterval_strain = 0.004\n";

RunSummary RunToFile(const std::string& text, const std::string& name, int threads = 2) {
  const Scene scene = Scene::Parse(text, name + ".toml", "");
  RunOptions options;
  options.output_path = TempPath(name + ".h5");
  options.threads = threads;
  const RunSummary summary = RunScene(scene, options);
  EXPECT_EQ(summary.termination, Termination::kCompleted) << name << ": " << summary.message;
  return summary;
}

TimeSeries SeriesOf(const std::string& name) {
  return TimeSeries::Read(Hdf5File::OpenRead(TempPath(name + ".h5")), record::kSeries);
}

std::string ForkScene(const std::string& parent, const std::string& stage) {
  std::string text = "[sample]\nstate = '" + TempPath(parent + ".h5") + "'\n";
  if (!stage.empty()) text += "stage = '" + stage + "'\n";
  return text + "[numerics]\ntime_step_s = 1.2e-7\n" + kOutput + kStageB;
}

// Rows of `series` whose stage column equals `stage`.
std::vector<size_t> RowsOfStage(const TimeSeries& series, double stage) {
  std::vector<size_t> rows;
  const auto& column = series.Values(record::kColumnStage);
  for (size_t r = 0; r < column.size(); ++r) {
    if (column[r] == stage) rows.push_back(r);
  }
  return rows;
}

// B's rows of the straight run against the rows of the fork: the same bytes
// in every column; the stage column counts the stages of each scene.
void ExpectSameRows(const TimeSeries& straight, const TimeSeries& fork) {
  const std::vector<size_t> b = RowsOfStage(straight, 1);
  ASSERT_EQ(b.size(), fork.rows());
  ASSERT_GT(b.size(), 5u);
  for (const auto& column : straight.columns()) {
    const auto& expected = straight.Values(column.name);
    const auto& actual = fork.Values(column.name);
    for (size_t k = 0; k < b.size(); ++k) {
      if (column.name == record::kColumnStage) {
        EXPECT_EQ(actual[k], 0.0);
      } else {
        ASSERT_EQ(std::memcmp(&expected[b[k]], &actual[k], sizeof(double)), 0)
            << column.name << " row " << k << ": " << expected[b[k]] << " vs " << actual[k];
      }
    }
  }
}

class Fork : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string sample = SampleToml(600, 4.9, 21);
    RunToFile(sample + kOutput + kStageA + kStageB, "fork_straight");
    RunToFile(sample + kOutput + kStageA, "fork_parent");
  }
};

TEST_F(Fork, FromTheFinalStateOfAnotherRunGivesTheSameBytesAsOneRun) {
  RunToFile(ForkScene("fork_parent", ""), "fork_child");
  ExpectSameRows(SeriesOf("fork_straight"), SeriesOf("fork_child"));
  // The final states agree as well.
  const Hdf5File a = Hdf5File::OpenRead(TempPath("fork_straight.h5"));
  const Hdf5File b = Hdf5File::OpenRead(TempPath("fork_child.h5"));
  size_t rows = 0, cols = 0;
  EXPECT_EQ(a.ReadMatrix("/final_state/positions", &rows, &cols),
            b.ReadMatrix("/final_state/positions", &rows, &cols));
}

TEST_F(Fork, FromAStageEndGivesTheSameBytesAsOneRun) {
  RunToFile(ForkScene("fork_straight", "ncl"), "fork_stage_child");
  ExpectSameRows(SeriesOf("fork_straight"), SeriesOf("fork_stage_child"));
  // The last stage of a completed run forks from its final state.
  RunToFile(ForkScene("fork_parent", "ncl"), "fork_last_stage_child");
  ExpectSameRows(SeriesOf("fork_straight"), SeriesOf("fork_last_stage_child"));
}

TEST_F(Fork, RecordsItsParentInTheProvenance) {
  RunToFile(ForkScene("fork_straight", "ncl"), "fork_provenance");
  const Hdf5File parent = Hdf5File::OpenRead(TempPath("fork_straight.h5"));
  const Hdf5File child = Hdf5File::OpenRead(TempPath("fork_provenance.h5"));
  const Provenance p = ReadProvenance(parent);
  const Provenance c = ReadProvenance(child);
  EXPECT_EQ(p.start_kind, "generated");
  EXPECT_EQ(c.start_kind, "state");
  EXPECT_EQ(c.parent_stage, "ncl");
  EXPECT_EQ(c.parent_file, TempPath("fork_straight.h5"));
  EXPECT_EQ(c.parent_scene_sha256, p.scene_sha256);
  EXPECT_EQ(c.start_sha256.size(), 64u);
  EXPECT_NE(c.start_sha256, p.start_sha256);
  EXPECT_EQ(c.threads, 2);
  EXPECT_FALSE(c.program_version.empty());
  EXPECT_FALSE(c.cpu_model.empty());
}

TEST_F(Fork, BadParentsAreRejectedWithTheReason) {
  auto error_of = [](const std::string& text, const std::string& out) {
    try {
      const Scene scene = Scene::Parse(text, "child.toml", "");
      RunOptions options;
      options.output_path = out;
      RunScene(scene, options);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  const std::string unknown = error_of(ForkScene("fork_straight", "nothing"), TempPath("x.h5"));
  EXPECT_NE(unknown.find("no completed stage named 'nothing'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("'ncl'"), std::string::npos) << unknown;
  const std::string missing = error_of(ForkScene("fork_absent", ""), TempPath("x.h5"));
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  const std::string self = error_of(ForkScene("fork_parent", ""), TempPath("fork_parent.h5"));
  EXPECT_NE(self.find("no output overwrites an input"), std::string::npos) << self;
  const std::string both =
      error_of("[sample]\nstate = 'a.h5'\npacking = 'b.txt'\n" + kStageB, TempPath("x.h5"));
  EXPECT_NE(both.find("exactly one"), std::string::npos) << both;
  const std::string stray = error_of(SampleToml() + "[sample]\nstage = 'ncl'\n", TempPath("x.h5"));
  EXPECT_FALSE(stray.empty());
}

// With the adaptive step (Hertz–Mindlin: Δt changes during the run) a fork
// from a stage end steps exactly as the run that went on: the rule is
// evaluated at every stage start and then every check interval of the stage.
TEST(ForkWithAdaptiveTimeStep, FromAStageEndGivesTheSameBytesAsOneRun) {
  const std::string numerics =
      "[material]\ncontact_law = 'hertz_mindlin'\npoissons_ratio = 0.25\n"
      "[numerics]\ntime_step_fraction = 0.1\ntime_step_check_interval = 30\n";
  const std::string sample =
      "[sample.generate]\ncount = 400\ncell_size_mm = 4.3\nseed = 4\n" + numerics + kOutput;
  RunToFile(sample + kStageA + kStageB, "adaptive_straight");
  RunToFile("[sample]\nstate = '" + TempPath("adaptive_straight.h5") + "'\nstage = 'ncl'\n" +
                numerics + kOutput + kStageB,
            "adaptive_fork");
  const TimeSeries straight = SeriesOf("adaptive_straight");
  const auto& dt = straight.Values(record::kColumnTimeStep);
  ASSERT_LT(*std::min_element(dt.begin(), dt.end()), 0.9 * *std::max_element(dt.begin(), dt.end()));
  ExpectSameRows(straight, SeriesOf("adaptive_fork"));
}

TEST(ForkWithAnotherMaterial, StartsTheHistoriesTheParentDidNotKeepFromZero) {
  // A frictionless parent keeps no shear history; the child adds friction and
  // rolling resistance, so both histories start at zero in every pair.
  RunToFile(SampleToml(300, 3.9, 8) + "[material]\nfriction_angle_rad = 0.0\n" + kOutput + kStageA,
            "fork_frictionless_parent");
  std::string child = ForkScene("fork_frictionless_parent", "");
  child += "[material]\nfriction_angle_rad = 0.5\nrolling_friction = 0.1\n";
  const RunSummary summary = RunToFile(child, "fork_frictional_child");
  EXPECT_GT(summary.steps, 0);
  const Hdf5File file = Hdf5File::OpenRead(TempPath("fork_frictional_child.h5"));
  const Engine::State state = ReadEngineState(file, "/final_state/engine");
  EXPECT_EQ(state.neighbors.shear.size(), state.neighbors.neighbors.size());
  EXPECT_EQ(state.neighbors.rolling.size(), state.neighbors.neighbors.size());
  double largest = 0;
  for (const Vec3& f : state.neighbors.shear) largest = std::max(largest, Norm(f));
  EXPECT_GT(largest, 0.0);  // the child's contacts built up shear forces
  // The material a run used reads back from its file (the analyses' κ).
  const Material material = ReadMaterial(file);
  EXPECT_EQ(material.friction_angle, 0.5);
  EXPECT_EQ(material.rolling_friction, 0.1);
  EXPECT_EQ(material.contact_law, Material{}.contact_law);
  EXPECT_EQ(material.youngs_modulus, Material{}.youngs_modulus);
}

TEST(Provenance, ARestartWithAnotherSceneIsRejected) {
  const std::string text = SampleToml(300, 3.9, 6) + kOutput + kStageA;
  RunOptions options;
  options.output_path = TempPath("restart_other_scene.h5");
  options.stop_requested = [](int64_t step) { return step >= 200; };
  ASSERT_EQ(RunScene(Scene::Parse(text, "a.toml", ""), options).termination,
            Termination::kInterrupted);
  options.stop_requested = nullptr;
  options.restart = true;
  // Comments and layout do not matter; a changed value does.
  EXPECT_EQ(RunScene(Scene::Parse("# same\n" + text, "a.toml", ""), options).termination,
            Termination::kCompleted);
  ASSERT_EQ(RunScene(Scene::Parse(text, "a.toml", ""),
                     [&] {
                       RunOptions again = options;
                       again.restart = false;
                       again.stop_requested = [](int64_t step) { return step >= 200; };
                       return again;
                     }())
                .termination,
            Termination::kInterrupted);
  const std::string other = SampleToml(300, 3.9, 6) + kOutput + testing::NclStage(160.0);
  try {
    RunScene(Scene::Parse(other, "b.toml", ""), options);
    ADD_FAILURE() << "a restart with another scene was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("differs from the scene of the checkpoint"),
              std::string::npos)
        << error.what();
  }
}

TEST(Provenance, TheSceneHashIgnoresFormattingAndExplicitDefaults) {
  const std::string base = SampleToml(200, 3.5, 1) + kOutput + kStageA;
  const Scene a = Scene::Parse(base, "a.toml", "");
  const Scene b = Scene::Parse(
      "# a comment\n" + SampleToml(200, 3.5, 1) + kOutput + "\n\n" + kStageA, "b.toml", "");
  EXPECT_EQ(a.Canonical(), b.Canonical());
  const Scene explicit_default = Scene::Parse(
      SampleToml(200, 3.5, 1) + kOutput + "[material]\nlocal_damping = 0.5\n" + kStageA, "c.toml",
      "");
  EXPECT_EQ(a.Canonical(), explicit_default.Canonical());
  const Scene other = Scene::Parse(SampleToml(200, 3.5, 2) + kOutput + kStageA, "d.toml", "");
  EXPECT_NE(a.Canonical(), other.Canonical());
  EXPECT_NE(a.Canonical().find("stage[0].stop.mean_stress_kpa = 150"), std::string::npos)
      << a.Canonical();
}

TEST(RunRecord, TheEngineStateRoundTripsThroughAFile) {
  RunToFile(SampleToml(300, 3.9, 5) + kOutput + kStageA, "record_roundtrip");
  const Hdf5File file = Hdf5File::OpenRead(TempPath("record_roundtrip.h5"));
  const Engine::State state = ReadEngineState(file, "/final_state/engine");
  const std::string copy = TempPath("record_copy.h5");
  {
    Hdf5File out = Hdf5File::CreateAtomic(copy);
    WriteEngineState(out, "/state", state, 3);
    out.Commit();
  }
  int threads = 0;
  const Engine::State again = ReadEngineState(Hdf5File::OpenRead(copy), "/state", &threads);
  EXPECT_EQ(threads, 3);
  EXPECT_EQ(again.id, state.id);
  EXPECT_EQ(again.position.size(), 300u);
  for (size_t i = 0; i < state.position.size(); ++i) {
    EXPECT_EQ(std::memcmp(&again.position[i], &state.position[i], sizeof(Vec4)), 0);
    EXPECT_EQ(std::memcmp(&again.velocity[i], &state.velocity[i], sizeof(Vec4)), 0);
  }
  EXPECT_EQ(again.neighbors.offsets, state.neighbors.offsets);
  EXPECT_EQ(again.neighbors.neighbors, state.neighbors.neighbors);
  EXPECT_EQ(again.neighbors.shear.size(), state.neighbors.shear.size());
  EXPECT_TRUE(again.forces_current);  // the run ended on a stop, not after a step
  const RunSummary summary = ReadSummary(file);
  EXPECT_EQ(summary.termination, Termination::kCompleted);
  EXPECT_EQ(summary.stages_completed, 1);
  const std::vector<StageRecord> records = ReadStageRecords(file);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].name, "ncl");
  EXPECT_EQ(records[0].type, "strain_path");
  EXPECT_FALSE(records[0].end_state);  // the last stage's end is the final state
}

// A final state that a text packing could not hold is refused on export
// (naming the file, the group and the spheres); the sample of a restart is
// read without these checks.
TEST(RunRecord, ResultPackingsAreCheckedLikeTextPackings) {
  Packing packing;
  packing.cell = {0.01, 0.01, 0.01};
  packing.positions = {{0.002, 0.002, 0.002}, {0.0034, 0.002, 0.002}};
  packing.radii = {0.001, 0.001};
  const std::string path = TempPath("overlapping_state.h5");
  {
    Hdf5File out = Hdf5File::CreateAtomic(path);
    WritePacking(out, "/final_state", packing);
    WritePacking(out, "/sample", packing);
    out.Commit();
  }
  try {
    ReadResultPacking(path, "/final_state");
    FAIL() << "a 30 % overlap was exported";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path + ":/final_state: spheres 1 and 2: spheres overlap by 30 %"),
              std::string::npos)
        << message;
  }
  Packing sample;
  ReadSample(Hdf5File::OpenRead(path), &sample, nullptr);
  EXPECT_EQ(sample.positions, packing.positions);
}

// A state whose checksums match but whose data cannot be a state is refused
// on reading, naming the file and the dataset: written through Hdf5File.
TEST(RunRecord, AStateThatBreaksItsInvariantsIsRefusedNamingTheDataset) {
  RunToFile(SampleToml(300, 3.9, 5) + kOutput + kStageA, "record_invariants");
  const Engine::State good =
      ReadEngineState(Hdf5File::OpenRead(TempPath("record_invariants.h5")), "/final_state/engine");
  ASSERT_GT(good.neighbors.neighbors.size(), 10u);
  ASSERT_FALSE(good.neighbors.shear.empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The first i with two neighbours (to unsort them).
  size_t two = 0;
  while (good.neighbors.offsets[two + 1] - good.neighbors.offsets[two] < 2) ++two;
  const struct {
    const char* expected;
    std::function<void(Engine::State&)> change;
  } cases[] = {
      {"dataset /state/list/offsets decreases from",
       [](Engine::State& s) { s.neighbors.offsets[20] = s.neighbors.offsets[21] + 3; }},
      {"dataset /state/list/offsets runs from 1 to",
       [](Engine::State& s) { s.neighbors.offsets[0] = 1; }},
      {"dataset /state/list/offsets has 300 entries for 300 particles",
       [](Engine::State& s) { s.neighbors.offsets.pop_back(); }},
      {"dataset /state/list/neighbors entry",
       [two](Engine::State& s) {
         std::swap(s.neighbors.neighbors[s.neighbors.offsets[two]],
                   s.neighbors.neighbors[s.neighbors.offsets[two] + 1]);
       }},
      {"dataset /state/list/neighbors entry 0 = 300",
       [](Engine::State& s) { s.neighbors.neighbors[0] = 300; }},
      {"dataset /state/list/shear has", [](Engine::State& s) { s.neighbors.shear.pop_back(); }},
      {"dataset /state/list/shear row 2 is not finite",
       [nan](Engine::State& s) { s.neighbors.shear[2].y = nan; }},
      {"dataset /state/id is not a permutation of 0..299: entry 3 = 300 is out of range",
       [](Engine::State& s) { s.id[3] = 300; }},
      {"dataset /state/id is not a permutation of 0..299: entry 4 = ",
       [](Engine::State& s) { s.id[4] = s.id[0]; }},
      {"dataset /state/position row 5", [nan](Engine::State& s) { s.position[5].x = nan; }},
      {"dataset /state/position row 6", [](Engine::State& s) { s.position[6].w = 0; }},
      {"dataset /state/velocity row 7", [](Engine::State& s) { s.velocity[7].w = -1; }},
      {"dataset /state/velocity has 299 rows for 300 particles",
       [](Engine::State& s) { s.velocity.pop_back(); }},
      {"dataset /state/spin row 8",
       [](Engine::State& s) { s.spin[8].z = std::numeric_limits<double>::infinity(); }},
      {"dataset /state/cell holds the cell sides", [](Engine::State& s) { s.cell[1] = -1; }},
      {"dataset /state/list/build_positions has 299 rows",
       [](Engine::State& s) { s.neighbors.build_positions.pop_back(); }},
  };
  const std::string path = TempPath("record_invalid.h5");
  for (const auto& c : cases) {
    Engine::State bad = good;
    c.change(bad);
    {
      Hdf5File out = Hdf5File::CreateAtomic(path);
      WriteEngineState(out, "/state", bad, 1);
      out.Commit();
    }
    try {
      ReadEngineState(Hdf5File::OpenRead(path), "/state");
      ADD_FAILURE() << "accepted: " << c.expected;
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
  }
}

TEST(RunRecord, APackingWithoutPositiveRadiiIsRefused) {
  Packing packing;
  packing.cell = {1e-3, 1e-3, 1e-3};
  packing.positions = {{1e-4, 1e-4, 1e-4}, {5e-4, 5e-4, 5e-4}};
  packing.radii = {1e-4, 0.0};
  const std::string path = TempPath("record_packing.h5");
  {
    Hdf5File out = Hdf5File::CreateAtomic(path);
    WritePacking(out, "/p", packing);
    out.Commit();
  }
  try {
    ReadPacking(Hdf5File::OpenRead(path), "/p");
    ADD_FAILURE() << "a zero radius was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("dataset /p/radii entry 1 = 0 is not a radius"),
              std::string::npos)
        << error.what();
  }
}

// What `granasym export --info` prints, and the note on partial results.
TEST(RunRecord, TheDescriptionOfAResultSaysWhetherItIsFinal) {
  const std::string text = SampleToml(300, 3.9, 6) + kOutput + kStageA + kStageB;
  RunOptions options;
  options.output_path = TempPath("record_describe.h5");
  options.stop_requested = [](int64_t step) { return step >= 300; };
  ASSERT_EQ(RunScene(Scene::Parse(text, "describe.toml", ""), options).termination,
            Termination::kInterrupted);
  {
    const Hdf5File file = Hdf5File::OpenRead(options.output_path);
    const std::string note = PartialResultNote(file);
    EXPECT_NE(note.find("is a partial result"), std::string::npos) << note;
    EXPECT_NE(note.find("--restart"), std::string::npos) << note;
    const std::string info = DescribeResult(file);
    EXPECT_NE(info.find("\ntermination: interrupted\n"), std::string::npos) << info;
    EXPECT_NE(info.find("\nfinal: no: "), std::string::npos) << info;
    EXPECT_NE(info.find("\ncheckpoint: " + options.output_path + ".ckpt\n"), std::string::npos)
        << info;
    EXPECT_NE(info.find("\nscene: describe.toml\n"), std::string::npos) << info;
  }
  options.stop_requested = nullptr;
  options.restart = true;
  ASSERT_EQ(RunScene(Scene::Parse(text, "describe.toml", ""), options).termination,
            Termination::kCompleted);
  const Hdf5File file = Hdf5File::OpenRead(options.output_path);
  EXPECT_EQ(PartialResultNote(file), "");
  const std::string info = DescribeResult(file);
  EXPECT_NE(info.find("\nfinal: yes\n"), std::string::npos) << info;
  EXPECT_NE(info.find("\ncheckpoint: none\n"), std::string::npos) << info;
  EXPECT_NE(info.find("\nstage 000: 'ncl' (strain_path), rows 0.."), std::string::npos) << info;
  EXPECT_NE(info.find("\nstage 001: 'triaxial' (triaxial), rows "), std::string::npos) << info;
  EXPECT_NE(info.find("stop: strain target reached"), std::string::npos) << info;
  // The loop's time in full precision (bench/external/compare.sh reads it).
  const RunSummary summary = ReadSummary(file);
  EXPECT_NE(info.find(fmt::format("\nloop_wall_s: {:.6g}\n", summary.loop_seconds)),
            std::string::npos)
      << info;
  ASSERT_GT(summary.particle_steps_per_second, 0);
  EXPECT_NE(info.find(fmt::format("\nus_per_particle_step: {:.6g}\n",
                                  1e6 / summary.particle_steps_per_second)),
            std::string::npos)
      << info;
  EXPECT_NE(info.find(fmt::format("\nneighbor_builds: {}\n", summary.neighbor_builds)),
            std::string::npos)
      << info;
  // One item per line, each "key: value".
  size_t start = 0;
  while (start < info.size()) {
    const size_t end = info.find('\n', start);
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(info.substr(start, end - start).find(": "), std::string::npos)
        << info.substr(start, end - start);
    start = end + 1;
  }
}

// A caller hears of every stage's end, however short the stage against the
// progress period (a scene that ends in 0.1 s still reports), with ETA 0.
TEST(RunProgress, EveryStageEndIsReportedWhateverThePeriod) {
  const std::string text = SampleToml(300, 3.9, 6) + kOutput + kStageA + kStageB;
  RunOptions options;
  options.output_path = TempPath("record_progress.h5");
  options.progress_period_s = 1e9;
  std::vector<RunProgress> reports;
  options.progress = [&reports](const RunProgress& progress) { reports.push_back(progress); };
  ASSERT_EQ(RunScene(Scene::Parse(text, "progress.toml", ""), options).termination,
            Termination::kCompleted);
  ASSERT_EQ(reports.size(), 2u);
  for (int64_t k = 0; k < 2; ++k) {
    EXPECT_EQ(reports[k].stage, k);
    EXPECT_EQ(reports[k].stages, 2);
    EXPECT_EQ(reports[k].eta_seconds, 0);
    EXPECT_GT(reports[k].step, 0);
    EXPECT_GT(reports[k].mean_stress_kpa, 0);
  }
  EXPECT_EQ(reports[0].stage_name, "ncl");
  EXPECT_EQ(reports[1].stage_name, "triaxial");
  EXPECT_GT(reports[1].step, reports[0].step);
}

}  // namespace
}  // namespace granasym::dem
