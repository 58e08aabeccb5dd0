// Restarts from damaged checkpoints (dem/simulation.cc LoadCheckpoint, the
// readers of dem/run_record.cc): a flipped bit in any dataset fails its
// checksum, and data that break the state's invariants under matching
// checksums are refused, each with an InputError naming the file and the
// dataset, before the engine uses them. Never a crash, never a restart that
// goes on with other numbers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "common/error.h"
#include "dem/run_record_names.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "test_util.h"
#include "tests/common/hdf5_tamper.h"

namespace granasym::dem {
namespace {

std::string TempPath(const std::string& name) {
  return testing::TempPath(std::to_string(getpid()) + "_" + name);
}

// 300 spheres with friction (a shear history), interrupted in the triaxial
// stage after the isotropic one: its record, the runner's state and the
// series are all in the checkpoint.
const std::string kScene = testing::SampleToml(300, 3.9, 8) +
                           "[output]\ninterval_strain = 0.004\n" + testing::NclStage(150.0) +
                           testing::TriaxialStage(150.0, 0.02);

class CorruptCheckpoint : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    RunOptions options;
    options.output_path = TempPath("corrupt_base.h5");
    std::filesystem::remove(options.output_path + ".ckpt");
    options.stop_requested = [](int64_t step) { return step >= 10700; };
    const RunSummary summary = RunScene(Scene::Parse(kScene, "corrupt.toml", ""), options);
    ASSERT_EQ(summary.termination, Termination::kInterrupted) << summary.message;
    ASSERT_EQ(summary.stages_completed, 1) << "the checkpoint should hold a stage record";
  }

  // A copy of the checkpoint for `name`, damaged by `damage`; the restart's error.
  static std::string RestartAfter(const std::string& name,
                                  const std::function<void(const std::string&)>& damage) {
    RunOptions options;
    options.output_path = TempPath(name + ".h5");
    const std::string checkpoint = options.output_path + ".ckpt";
    std::filesystem::copy_file(TempPath("corrupt_base.h5.ckpt"), checkpoint,
                               std::filesystem::copy_options::overwrite_existing);
    damage(checkpoint);
    options.restart = true;
    try {
      const RunSummary summary = RunScene(Scene::Parse(kScene, "corrupt.toml", ""), options);
      return "restarted: " + std::string(ToString(summary.termination));
    } catch (const InputError& error) {
      return error.what();
    }
  }

  static void ExpectChecksumFailure(const std::string& dataset, int64_t byte, int bit) {
    const std::string message = RestartAfter("flipped", [&](const std::string& checkpoint) {
      granasym::testing::FlipDatasetBit(checkpoint, dataset, byte, bit);
    });
    EXPECT_NE(message.find("_flipped.h5.ckpt: dataset '" + dataset +
                           "' fails its checksum (the file is corrupt)"),
              std::string::npos)
        << message;
  }

  static void ExpectRefused(const std::string& expected,
                            const std::function<void(const std::string&)>& damage) {
    const std::string message = RestartAfter("invalid", damage);
    EXPECT_NE(message.find("_invalid.h5.ckpt: "), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
};

TEST_F(CorruptCheckpoint, AnIntactCopyRestartsToTheEnd) {
  EXPECT_EQ(RestartAfter("intact", [](const std::string&) {}), "restarted: completed");
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheNeighbourOffsetsFailsTheirChecksum) {
  ExpectChecksumFailure("/engine/list/offsets", 8 * 10 + 1, 3);
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheParticleIdsFailsTheirChecksum) {
  ExpectChecksumFailure("/engine/id", 8 * 5, 1);
}

TEST_F(CorruptCheckpoint, AFlippedBitInThePositionsFailsTheirChecksum) {
  ExpectChecksumFailure("/engine/position", 32 * 7 + 2, 4);
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheVelocitiesFailsTheirChecksum) {
  ExpectChecksumFailure("/engine/velocity", 32 * 11 + 6, 0);
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheShearHistoryFailsItsChecksum) {
  ExpectChecksumFailure("/engine/list/shear", 24 * 3 + 1, 5);
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheStoredSeriesFailsItsChecksum) {
  ExpectChecksumFailure("/series/p_kpa", 8 * 2 + 3, 2);
}

TEST_F(CorruptCheckpoint, AFlippedBitInTheSampleFailsItsChecksum) {
  ExpectChecksumFailure("/sample/radii", 8 * 4 + 5, 6);
}

// Matching checksums, impossible data: rewritten through HDF5.
TEST_F(CorruptCheckpoint, DecreasingNeighbourOffsetsAreRefused) {
  ExpectRefused("dataset /engine/list/offsets decreases", [](const std::string& checkpoint) {
    granasym::testing::RewriteInts(
        checkpoint, "/engine/list/offsets",
        [](std::vector<int64_t>& offsets) { offsets[10] = offsets[11] + 5; });
  });
}

TEST_F(CorruptCheckpoint, OffsetsThatDoNotEndAtTheEntriesAreRefused) {
  ExpectRefused("dataset /engine/list/offsets runs from 0 to", [](const std::string& checkpoint) {
    granasym::testing::RewriteInts(checkpoint, "/engine/list/offsets",
                                   [](std::vector<int64_t>& offsets) { offsets.back() += 1; });
  });
}

TEST_F(CorruptCheckpoint, ANeighbourBeyondTheParticlesIsRefused) {
  ExpectRefused("dataset /engine/list/neighbors entry 0 = 100000",
                [](const std::string& checkpoint) {
                  granasym::testing::RewriteInts(
                      checkpoint, "/engine/list/neighbors",
                      [](std::vector<int64_t>& neighbors) { neighbors[0] = 100000; });
                });
}

TEST_F(CorruptCheckpoint, IdsThatAreNoPermutationAreRefused) {
  ExpectRefused("dataset /engine/id is not a permutation of 0..299",
                [](const std::string& checkpoint) {
                  granasym::testing::RewriteInts(checkpoint, "/engine/id",
                                                 [](std::vector<int64_t>& id) { id[1] = id[0]; });
                });
}

TEST_F(CorruptCheckpoint, ARunnerStageBeyondTheSceneIsRefused) {
  ExpectRefused("/runner attribute stage = 7 is not a stage of the scene's 2",
                [](const std::string& checkpoint) {
                  granasym::testing::RewriteIntAttribute(checkpoint, "/runner", "stage", 7);
                });
}

TEST_F(CorruptCheckpoint, ARunnerStageThatDisagreesWithTheStageRecordsIsRefused) {
  ExpectRefused("/stages holds 1 stage records for the 0 stages done",
                [](const std::string& checkpoint) {
                  granasym::testing::RewriteIntAttribute(checkpoint, "/runner", "stage", 0);
                });
}

}  // namespace
}  // namespace granasym::dem
