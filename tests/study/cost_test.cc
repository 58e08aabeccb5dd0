#include "study/cost.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "common/error.h"
#include "common/text_file.h"
#include "study/parallelism.h"
#include "study/plan.h"
#include "study/programme.h"

namespace granasym::study {
namespace {

std::string PaperProgrammePath() { return std::string(GRANASYM_PROGRAMMES_DIR) + "/paper.toml"; }

MeasuredRate SomeRate() {
  MeasuredRate rate;
  rate.cpu_model = "test CPU";
  rate.threads = 1;
  rate.spheres = 800;
  rate.results_key = "key";
  rate.particle_steps_per_second = 4e6;
  rate.loose_particle_steps_per_second = 9e6;
  rate.still_particle_steps_per_second = 2e7;
  rate.controlled_particle_steps_per_second = 3e6;
  rate.generation_seconds = 0.5;
  rate.measured_at = "2026-12-06T00:00:00Z";
  return rate;
}

TEST(StudyCost, TinyPaperPlanListsEveryCaseWithDepthAndStepsAndTheTotalsAddUp) {
  const Programme programme = Programme::Load(PaperProgrammePath(), Scale::kTiny);
  const Plan plan = Plan::Make(programme, 1, "study");
  const MeasuredRate rate = SomeRate();
  const PlanCost cost = EstimateCost(plan, rate, 1, 0);
  ASSERT_EQ(cost.cases.size(), plan.cases.size());
  double particle_steps = 0, seconds = 0, earliest_seconds = 0;
  for (size_t k = 0; k < cost.cases.size(); ++k) {
    const CaseCost& c = cost.cases[k];
    const PlannedCase& planned = plan.cases[k];
    EXPECT_EQ(c.index, static_cast<int>(k));
    EXPECT_GT(planned.time_step, 0) << planned.id;
    EXPECT_GT(c.steps, 0) << planned.id;
    EXPECT_DOUBLE_EQ(c.particle_steps, c.steps * static_cast<double>(planned.particles));
    // Each kind of step at its own rate: loose ones before the generated
    // sample jams, those that sum the stress on every step, the others.
    const double n = static_cast<double>(planned.particles);
    EXPECT_NEAR(c.seconds,
                n * (planned.estimated_loose_steps - planned.estimated_still_steps) /
                        rate.loose_particle_steps_per_second +
                    n * planned.estimated_still_steps / rate.still_particle_steps_per_second +
                    n * planned.estimated_stress_steps / rate.controlled_particle_steps_per_second +
                    n *
                        (planned.estimated_steps - planned.estimated_loose_steps -
                         planned.estimated_stress_steps) /
                        rate.particle_steps_per_second,
                1e-9 * c.seconds)
        << planned.id;
    EXPECT_LE(planned.estimated_still_steps, planned.estimated_loose_steps) << planned.id;
    EXPECT_LE(planned.estimated_loose_steps + planned.estimated_stress_steps,
              planned.estimated_steps * (1 + 1e-12))
        << planned.id;
    EXPECT_EQ(c.at_most, planned.steps_at_most) << planned.id;
    // The low end of a bound's range: no more than the bound, the same
    // where the case cannot liquefy.
    EXPECT_LE(c.earliest_steps, c.steps * (1 + 1e-12)) << planned.id;
    EXPECT_LE(c.earliest_seconds, c.seconds * (1 + 1e-12)) << planned.id;
    if (!c.at_most) {
      EXPECT_DOUBLE_EQ(c.earliest_steps, c.steps) << planned.id;
      EXPECT_DOUBLE_EQ(c.earliest_seconds, c.seconds) << planned.id;
    }
    earliest_seconds += c.earliest_seconds;
    if (planned.id == "r1/ncl") {
      EXPECT_GT(planned.estimated_loose_steps, 0);
    }
    if (planned.id == "r1/nc50_triaxial") {
      EXPECT_DOUBLE_EQ(planned.estimated_stress_steps, planned.estimated_steps);
    }
    if (planned.id == "r1/nc100_psi120") {
      EXPECT_TRUE(c.at_most);  // may liquefy
    }
    if (planned.id == "r1/nc100_psi90") {
      EXPECT_FALSE(c.at_most);
    }
    if (planned.parent < 0) {
      EXPECT_EQ(c.depth, 1) << planned.id;
    } else {
      EXPECT_EQ(c.depth, cost.cases[static_cast<size_t>(planned.parent)].depth + 1) << planned.id;
    }
    particle_steps += c.particle_steps;
    seconds += c.seconds;
  }
  EXPECT_GE(cost.max_depth(), 2);  // the paper's cases fork from the NCL
  EXPECT_NEAR(cost.particle_steps, particle_steps, 1e-9 * particle_steps);
  EXPECT_NEAR(cost.case_seconds, seconds, 1e-9 * seconds);
  EXPECT_GT(cost.at_most_cases, 0);
  EXPECT_GT(cost.at_most_seconds, 0);
  EXPECT_LT(cost.at_most_seconds, cost.case_seconds);
  EXPECT_DOUBLE_EQ(cost.generation_seconds,
                   rate.generation_seconds * static_cast<double>(plan.samples.size()));
  EXPECT_NEAR(cost.earliest_case_seconds, earliest_seconds, 1e-9 * earliest_seconds);
  EXPECT_LT(cost.earliest_case_seconds, cost.case_seconds);  // the extension paths liquefy
  // One job runs the cases one after another.
  EXPECT_NEAR(cost.wall_seconds, cost.generation_seconds + seconds, 1e-9 * seconds);
  EXPECT_NEAR(cost.earliest_wall_seconds, cost.generation_seconds + earliest_seconds,
              1e-9 * earliest_seconds);
  EXPECT_LE(cost.critical_seconds, seconds * (1 + 1e-12));
  EXPECT_DOUBLE_EQ(cost.peak_memory_bytes,
                   kCaseBytesPerSphere * static_cast<double>(programme.Current().count));
}

TEST(StudyCost, MoreJobsShortenTheWallTimeDownToTheLongestChain) {
  const Plan plan = Plan::Make(Programme::Load(PaperProgrammePath(), Scale::kSmall), 1, "study");
  const MeasuredRate rate = SomeRate();
  const PlanCost one = EstimateCost(plan, rate, 1, 0);
  const PlanCost four = EstimateCost(plan, rate, 4, 0);
  const PlanCost many = EstimateCost(plan, rate, 1000, 0);
  EXPECT_LT(four.wall_seconds, one.wall_seconds);
  EXPECT_GE(four.wall_seconds, one.generation_seconds + one.case_seconds / 4 - 1e-6);
  EXPECT_LE(many.wall_seconds, four.wall_seconds);
  EXPECT_NEAR(many.wall_seconds, many.generation_seconds + many.critical_seconds,
              1e-9 * many.wall_seconds);
  EXPECT_DOUBLE_EQ(four.peak_memory_bytes, 4 * one.peak_memory_bytes);
}

TEST(StudyCost, ShardsCoverEveryCaseAndTheTimeLimitCoversTheLongestShard) {
  const Plan plan = Plan::Make(Programme::Load(PaperProgrammePath(), Scale::kSmall), 1, "study");
  const PlanCost cost = EstimateCost(plan, SomeRate(), 1, 4);
  ASSERT_EQ(cost.shards.size(), 4u);
  double longest = 0;
  int cases = 0;
  for (const ShardCost& shard : cost.shards) {
    EXPECT_GT(shard.cases, 0);
    EXPECT_GT(shard.seconds, 0);
    EXPECT_GT(shard.earliest_seconds, 0);
    EXPECT_LE(shard.earliest_seconds, shard.seconds * (1 + 1e-12));
    longest = std::max(longest, shard.seconds);
    cases += shard.cases;
  }
  EXPECT_GE(cases, static_cast<int>(plan.cases.size()));  // ancestors may be counted twice
  EXPECT_GE(cost.shard_time_limit_seconds, kTimeLimitMargin * longest);
  EXPECT_LT(cost.shard_time_limit_seconds, kTimeLimitMargin * longest + 60);
  EXPECT_EQ(SlurmTime(cost.shard_time_limit_seconds).back(), '0');  // whole minutes
}

TEST(StudyCost, DurationsAndSlurmTimes) {
  EXPECT_EQ(DurationText(42), "42 s");
  EXPECT_EQ(DurationText(600), "10 min");
  EXPECT_EQ(DurationText(10800), "3.0 h");
  EXPECT_EQ(DurationText(3 * 86400), "3.0 d");
  EXPECT_EQ(SlurmTime(0), "0-00:00:00");
  EXPECT_EQ(SlurmTime(90061), "1-01:01:01");
}

class RateCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("granasym_rate_cache_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    path_ = (dir_ / "granasym" / "rates.toml").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(RateCacheTest, StoredRatesAreFoundByTheirWholeKeyAndReplaced) {
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 1, 800, "key"));
  MeasuredRate rate = SomeRate();
  StoreRate(path_, rate);  // creates the folder
  MeasuredRate other = rate;
  other.spheres = 3000;
  other.particle_steps_per_second = 3e6;
  StoreRate(path_, other);
  const std::optional<MeasuredRate> found = ReadCachedRate(path_, "test CPU", 1, 800, "key");
  ASSERT_TRUE(found);
  EXPECT_TRUE(found->cached);
  EXPECT_DOUBLE_EQ(found->particle_steps_per_second, 4e6);
  EXPECT_DOUBLE_EQ(found->generation_seconds, 0.5);
  EXPECT_EQ(found->measured_at, rate.measured_at);
  // Every part of the key counts.
  EXPECT_FALSE(ReadCachedRate(path_, "another CPU", 1, 800, "key"));
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 2, 800, "key"));
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 1, 801, "key"));
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 1, 800, "another key"));
  rate.particle_steps_per_second = 5e6;
  StoreRate(path_, rate);  // replaces the entry of its key
  EXPECT_DOUBLE_EQ(ReadCachedRate(path_, "test CPU", 1, 800, "key")->particle_steps_per_second,
                   5e6);
  EXPECT_DOUBLE_EQ(ReadCachedRate(path_, "test CPU", 1, 3000, "key")->particle_steps_per_second,
                   3e6);
  const std::string text = ReadTextFile(path_);
  EXPECT_EQ(text.find("spheres = 800"), text.rfind("spheres = 800"));
}

TEST_F(RateCacheTest, AnEntryWithoutTheLooseAndControlledRatesIsMeasuredAgain) {
  // An older granasym's entry (one rate, of a loose packing) is not used
  // and is replaced when the new measurement is stored.
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path());
  std::ofstream(path_) << "[[rate]]\ncpu = \"test CPU\"\nthreads = 1\nspheres = 800\n"
                          "results_key = \"key\"\nparticle_steps_per_second = 4.7e7\n"
                          "generation_seconds = 0\nmeasured = \"t\"\n";
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 1, 800, "key"));
  // One with some of the rates only, likewise.
  std::ofstream(path_, std::ios::app)
      << "[[rate]]\ncpu = \"test CPU\"\nthreads = 1\nspheres = 3000\n"
         "results_key = \"key\"\nparticle_steps_per_second = 4.7e7\n"
         "loose_particle_steps_per_second = 5e7\ncontrolled_particle_steps_per_second = 2e7\n"
         "generation_seconds = 0\nmeasured = \"t\"\n";
  EXPECT_FALSE(ReadCachedRate(path_, "test CPU", 1, 3000, "key"));
  StoreRate(path_, SomeRate());
  const std::optional<MeasuredRate> found = ReadCachedRate(path_, "test CPU", 1, 800, "key");
  ASSERT_TRUE(found);
  EXPECT_DOUBLE_EQ(found->loose_particle_steps_per_second, 9e6);
  EXPECT_DOUBLE_EQ(found->still_particle_steps_per_second, 2e7);
  EXPECT_DOUBLE_EQ(found->controlled_particle_steps_per_second, 3e6);
  const std::string text = ReadTextFile(path_);
  EXPECT_EQ(text.find("4.7e"), std::string::npos) << text;
}

TEST_F(RateCacheTest, AMalformedCacheIsRefusedNamingTheFileAndKey) {
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path());
  std::ofstream(path_) << "[[rate]]\ncpu = \"c\"\nthreads = 1\nspheres = 800\nresults_key = \"k\"\n"
                          "particle_steps_per_second = -1\ngeneration_seconds = 0\n"
                          "measured = \"t\"\n";
  try {
    ReadCachedRate(path_, "c", 1, 800, "k");
    FAIL() << "a negative rate was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path_), std::string::npos) << message;
    EXPECT_NE(message.find("particle_steps_per_second"), std::string::npos) << message;
  }
}

TEST(RateCache, PathFollowsXdgCacheHomeThenHome) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const std::string saved_xdg = xdg ? xdg : "", saved_home = home ? home : "";
  setenv("XDG_CACHE_HOME", "/x", 1);
  EXPECT_EQ(RateCachePath(), "/x/granasym/rates.toml");
  unsetenv("XDG_CACHE_HOME");
  setenv("HOME", "/h", 1);
  EXPECT_EQ(RateCachePath(), "/h/.cache/granasym/rates.toml");
  unsetenv("HOME");
  EXPECT_EQ(RateCachePath(), "");
  if (xdg) setenv("XDG_CACHE_HOME", saved_xdg.c_str(), 1);
  if (home) setenv("HOME", saved_home.c_str(), 1);
}

}  // namespace
}  // namespace granasym::study
