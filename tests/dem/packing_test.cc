#include "dem/packing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/error.h"
#include "dem/grain_size_distribution.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

TEST(GrainSizeDistribution, QuantileRadiiReproduceTheDefaultTable) {
  const GrainSizeDistribution gsd = GrainSizeDistribution::Default();
  const std::vector<double> radii = gsd.QuantileRadii(20000);
  const std::vector<double> achieved = gsd.AchievedPercentPassing(radii);
  for (size_t k = 0; k < achieved.size(); ++k) {
    EXPECT_NEAR(achieved[k], gsd.percent_passing()[k], 0.5) << "sieve " << k;
  }
  EXPECT_GE(2 * radii.back(), 0.2e-3 * (1 - 1e-12));
  EXPECT_LE(2 * radii.front(), 1.0e-3 * (1 + 1e-12));
  EXPECT_TRUE(std::is_sorted(radii.rbegin(), radii.rend()));
}

TEST(GrainSizeDistribution, UniformSizeWithinOneSieveInterval) {
  // All mass between 1 and 1.001 mm: radii lie in that interval.
  const GrainSizeDistribution gsd({1e-3, 1.001e-3}, {0, 100});
  for (double r : gsd.QuantileRadii(100)) {
    EXPECT_GE(r, 0.5e-3);
    EXPECT_LE(r, 0.5005e-3);
  }
}

TEST(GrainSizeDistribution, BadTablesAreRejected) {
  EXPECT_THROW(GrainSizeDistribution({1e-3, 0.5e-3}, {0, 100}), InputError);
  EXPECT_THROW(GrainSizeDistribution({1e-3, 2e-3}, {10, 100}), InputError);
  EXPECT_THROW(GrainSizeDistribution({1e-3, 2e-3, 3e-3}, {0, 60, 50}), InputError);
  EXPECT_THROW(GrainSizeDistribution({-1e-3, 2e-3}, {0, 100}), InputError);
  EXPECT_THROW(GrainSizeDistribution({1e-3}, {100}), InputError);
}

TEST(Packing, GenerationIsDeterministicNonOverlappingAndMatchesTheGsd) {
  GenerationOptions options;
  options.count = 3000;
  options.cell_size = 31e-3 * std::cbrt(3000.0 / 150000.0);
  options.seed = 11;
  GenerationReport report;
  const GrainSizeDistribution gsd = GrainSizeDistribution::Default();
  const Packing a = GeneratePacking(gsd, options, &report);
  const Packing b = GeneratePacking(gsd, options);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_NEAR(report.porosity, 0.595, 0.02);
  for (size_t k = 0; k < report.achieved_passing.size(); ++k) {
    EXPECT_NEAR(report.achieved_passing[k], report.target_passing[k], 1.5);
  }
  // Brute-force overlap check with minimum images.
  const double side = options.cell_size;
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = i + 1; j < a.size(); ++j) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        double delta = a.positions[j][d] - a.positions[i][d];
        delta -= side * std::nearbyint(delta / side);
        d2 += delta * delta;
      }
      ASSERT_GE(d2, (a.radii[i] + a.radii[j]) * (a.radii[i] + a.radii[j])) << i << " " << j;
    }
  }
  options.seed = 12;
  EXPECT_NE(GeneratePacking(gsd, options).positions, a.positions);
}

TEST(Packing, TooDenseARequestIsRejected) {
  GenerationOptions options;
  options.count = 3000;
  options.cell_size = 0.5 * 31e-3 * std::cbrt(3000.0 / 150000.0);
  EXPECT_THROW(GeneratePacking(GrainSizeDistribution::Default(), options), InputError);
}

TEST(Packing, TextRoundTripIsExact) {
  Packing packing;
  packing.cell = {0.01, 0.011, 0.012};
  packing.positions = {{0.001, 0.002, 0.003}, {0.1 / 3, 0.005, 0.0071}};
  packing.positions[1][0] = 0.004 + 1e-17;
  packing.radii = {1e-3 / 3, 0.4e-3};
  const std::string path = testing::TempPath("packing.txt");
  packing.WriteText(path);
  const Packing read = Packing::ReadText(path);
  EXPECT_EQ(read.cell, packing.cell);
  EXPECT_EQ(read.positions, packing.positions);
  EXPECT_EQ(read.radii, packing.radii);
}

TEST(Packing, MalformedFilesNameTheLine) {
  const std::string path = testing::TempPath("bad_packing.txt");
  std::ofstream(path) << "2 0.01 0.01 0.01\n0.001 0.002 0.003 0.0004\n0.001 0.002 oops 0.0004\n";
  try {
    Packing::ReadText(path);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("line 3"), std::string::npos) << error.what();
  }
  std::ofstream(path) << "3 0.01 0.01 0.01\n0.001 0.002 0.003 0.0004\n";
  EXPECT_THROW(Packing::ReadText(path), InputError);
  std::ofstream(path) << "1 0.01 -0.01 0.01\n0.001 0.002 0.003 0.0004\n";
  EXPECT_THROW(Packing::ReadText(path), InputError);
}

}  // namespace
}  // namespace granasym::dem
