#include "dem/packing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

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

// Two spheres of radius 1 mm well apart in a 10 mm cube.
const std::string kCell = " 0.01 0.01 0.01\n";
const std::string kA = "0.002 0.002 0.002 0.001\n";
const std::string kB = "0.006 0.006 0.006 0.001\n";

struct PackingCase {
  const char* name;
  std::string text;
  std::vector<std::string> mentions;  // besides the file name
};

// Every defect of a packing file, one case each.
const std::vector<PackingCase>& PackingDefects() {
  static const std::vector<PackingCase> cases = {
      {"count_below_rows",
       "1" + kCell + kA + kB,
       {"line 3", "'0.006 0.006 0.006 0.001' follows the 1 spheres", "header (line 1)"}},
      {"count_above_rows",
       "3" + kCell + kA + kB,
       {"header (line 1) announces 3 spheres", "ends after 2 (at line 3)"}},
      {"count_above_rows_by_many", "2000000000" + kCell + kA, {"announces 2000000000", "after 1"}},
      {"non_integer_count", "2.0" + kCell + kA + kB, {"line 1", "'2.0'", "digits only"}},
      {"count_with_exponent", "1.5e3" + kCell + kA, {"line 1", "'1.5e3'", "digits only"}},
      {"count_with_exponent_split",
       "1.5e3 0.01 0.01\n" + kA,
       {"line 1", "'1.5e3 0.01 0.01'", "3 fields", "exactly 4"}},
      {"negative_count", "-2" + kCell + kA + kB, {"line 1", "'-2'"}},
      {"zero_count", "0" + kCell, {"line 1", "sphere count 0", "[1, 2147483647]"}},
      {"count_too_large", "99999999999" + kCell + kA, {"line 1", "99999999999", "2147483647"}},
      {"three_header_fields", "2 0.01 0.01\n" + kA + kB, {"line 1", "3 fields", "'N Lx Ly Lz'"}},
      {"five_header_fields", "2 0.01 0.01 0.01 0.01\n" + kA + kB, {"line 1", "5 fields"}},
      {"header_of_names", "N Lx Ly Lz\n" + kA, {"line 1", "'N'"}},
      {"extra_field_in_a_row",
       "2" + kCell + kA + "0.006 0.006 0.006 0.001 7\n",
       {"line 3", "sphere 2", "5 fields", "'x y z r'"}},
      {"missing_field_in_a_row",
       "2" + kCell + "0.002 0.002 0.001\n" + kB,
       {"line 2", "sphere 1", "3 fields"}},
      {"comment_after_a_row",
       "1" + kCell + "0.002 0.002 0.002 0.001 # big\n",
       {"line 2", "6 fields"}},
      {"garbage_after_the_data",
       "2" + kCell + kA + kB + "\nend of file\n",
       {"line 5", "'end of file' follows the 2 spheres"}},
      {"text_in_a_field",
       "2" + kCell + kA + "0.006 0.006 oops 0.001\n",
       {"line 3", "field 3 ('oops')", "sphere 2"}},
      {"nan_radius",
       "2" + kCell + kA + "0.006 0.006 0.006 nan\n",
       {"line 3", "field 4 ('nan')", "not a finite number"}},
      {"infinite_radius", "1" + kCell + "0.002 0.002 0.002 inf\n", {"line 2", "'inf'"}},
      {"negative_radius",
       "2" + kCell + kA + "0.006 0.006 0.006 -0.001\n",
       {"line 3", "radius -0.001 m", "> 0"}},
      {"zero_radius", "1" + kCell + "0.002 0.002 0.002 0\n", {"line 2", "radius 0 m"}},
      {"radius_1e-300",
       "1" + kCell + "0.002 0.002 0.002 1e-300\n",
       {"line 2", "radius 1e-300 m", "[1e-09, 1000] m"}},
      {"coordinate_1e308",
       "2" + kCell + kA + "1e308 0.006 0.006 0.001\n",
       {"line 3", "coordinate x = 1e+308 m", "1000 cell sides"}},
      {"coordinate_2000_cells_away",
       "1" + kCell + "0.002 -20 0.002 0.001\n",
       {"line 2", "coordinate y = -20 m"}},
      {"nan_coordinate", "1" + kCell + "0.002 0.002 nan 0.001\n", {"line 2", "field 3 ('nan')"}},
      {"zero_cell_side", "1 0 0.01 0.01\n" + kA, {"line 1", "cell side Lx = 0 m", "> 0"}},
      {"negative_cell_side", "1 0.01 -0.01 0.01\n" + kA, {"line 1", "cell side Ly = -0.01 m"}},
      {"infinite_cell_side",
       "1 0.01 0.01 inf\n" + kA,
       {"line 1", "cell side Lz 'inf' is not a finite number"}},
      {"coincident_spheres", "3" + kCell + kA + kB + kA, {"lines 2 and 4", "coincident", "25 %"}},
      // Centres 1.4 mm apart: (2 − 1.4)/2 of the sum of the radii.
      {"overlap_of_30_percent",
       "2" + kCell + kA + "0.0034 0.002 0.002 0.001\n",
       {"lines 2 and 3", "overlap by 30 %", "at most 25 %"}},
      // 0.6 mm apart through the periodic boundary at x = 0.
      {"overlap_across_the_boundary",
       "2" + kCell + "0.0003 0.005 0.005 0.001\n" + "0.0097 0.005 0.005 0.001\n",
       {"lines 2 and 3", "overlap by 70 %"}},
      {"sphere_too_large_for_the_cell",
       "1" + kCell + "0.005 0.005 0.005 0.003\n",
       {"line 2", "radius 0.003 m", "diameter 0.006 m",
        "exceeds 0.005 m, half the smallest cell side 0.01 m"}},
      {"sphere_too_large_for_a_thin_side",
       "1 0.02 0.02 0.008\n0.01 0.01 0.004 0.0025\n",
       {"line 2", "exceeds 0.004 m, half the smallest cell side 0.008 m"}},
      {"cell_too_dilute", "1 10 10 10\n0 0 0 0.001\n", {"lines 1 and 2", "1.25e+11 cubes", "2^30"}},
      {"empty_file", "", {"empty", "'N Lx Ly Lz'"}},
      {"only_comments", "# a packing\n\n   \n", {"empty"}},
  };
  return cases;
}

TEST(Packing, EveryDefectOfAFileNamesFileLineAndValue) {
  for (const PackingCase& c : PackingDefects()) {
    const std::string path = testing::TempPath(std::string("packing_") + c.name + ".txt");
    std::ofstream(path) << c.text;
    try {
      Packing::ReadText(path);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path + ": "), std::string::npos) << c.name << ": " << message;
      for (const std::string& mention : c.mentions) {
        EXPECT_NE(message.find(mention), std::string::npos)
            << c.name << ": no '" << mention << "' in: " << message;
      }
    }
  }
}

TEST(Packing, CommentsWrappingAndOverlapsBelowTheFailureLimitAreAccepted) {
  const std::string path = testing::TempPath("packing_accepted.txt");
  // Centres 1.6 mm apart: a relative overlap of 20 %, as in compressed packings.
  std::ofstream(path) << "# exported\n\n2 0.01 0.01 0.01\n# spheres\n"
                         "-0.008 0.002 0.012 0.001\n\n0.0036 0.002 0.002 0.001\n# end\n\n";
  const Packing packing = Packing::ReadText(path);
  ASSERT_EQ(packing.size(), 2u);
  EXPECT_NEAR(packing.positions[0][0], 0.002, 1e-15);
  EXPECT_NEAR(packing.positions[0][2], 0.002, 1e-15);
  for (const auto& x : packing.positions) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(x[a], 0.0);
      EXPECT_LT(x[a], packing.cell[a]);
    }
  }
  // A sphere exactly half the cell wide, one on the cell's far face (wrapped to 0).
  std::ofstream(path) << "2 0.01 0.01 0.01\n0.005 0.005 0.005 0.0025\n0.01 0.01 0.01 0.0001\n";
  EXPECT_EQ(Packing::ReadText(path).positions[1], (std::array<double, 3>{0, 0, 0}));
}

TEST(Packing, OverlapCheckFindsAPairFarApartInTheFile) {
  // 40³ touching spheres on a lattice; the last one is moved onto the first
  // one's periodic neighbour: only a check over all nearby pairs finds it.
  const int side = 40;
  const double spacing = 1e-3, r = 0.5e-3;
  std::ostringstream text;
  text.precision(17);
  text << side * side * side << " " << side * spacing << " " << side * spacing << " "
       << side * spacing << "\n";
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        const bool last = i == side - 1 && j == side - 1 && k == side - 1;
        text << (i + 0.5) * spacing << " " << (j + 0.5) * spacing << " "
             << (last ? 0.5 + 0.1 : k + 0.5) * spacing << " " << r << "\n";
      }
    }
  }
  const std::string path = testing::TempPath("packing_lattice.txt");
  std::ofstream(path) << text.str();
  try {
    Packing::ReadText(path);
    FAIL() << "the overlap was not found";
  } catch (const InputError& error) {
    // Sphere (39, 39, 39), the last, sits 0.1 mm from (39, 39, 0) on line
    // 2 + 39·1600 + 39·40.
    const std::string message = error.what();
    EXPECT_NE(message.find("lines 63962 and 64001: spheres overlap by 90 %"), std::string::npos)
        << message;
  }
}

TEST(Packing, WriterRefusesWhatTheReaderRefuses) {
  Packing valid;
  valid.cell = {0.01, 0.01, 0.01};
  valid.positions = {{0.002, 0.002, 0.002}, {0.006, 0.006, 0.006}};
  valid.radii = {0.001, 0.001};
  std::vector<std::pair<std::string, Packing>> defects;
  defects.emplace_back("nan radius", valid);
  defects.back().second.radii[1] = std::nan("");
  defects.emplace_back("negative radius", valid);
  defects.back().second.radii[0] = -0.001;
  defects.emplace_back("infinite coordinate", valid);
  defects.back().second.positions[1][2] = INFINITY;
  defects.emplace_back("zero cell side", valid);
  defects.back().second.cell[1] = 0;
  defects.emplace_back("too large", valid);
  defects.back().second.radii[0] = 0.003;
  defects.emplace_back("coincident", valid);
  defects.back().second.positions[1] = valid.positions[0];
  defects.emplace_back("coincident through a periodic image", valid);
  defects.back().second.positions[1] = {0.012, -0.008, 0.002};
  defects.emplace_back("empty", Packing{});
  const std::string path = testing::TempPath("packing_written.txt");
  for (const auto& [name, packing] : defects) {
    std::filesystem::remove(path);
    EXPECT_THROW(packing.WriteText(path), InputError) << name;
    EXPECT_FALSE(std::filesystem::exists(path)) << name;
    EXPECT_THROW(packing.Validate("memory"), InputError) << name;
  }
  // What it writes reads back, a subnormal coordinate included.
  valid.positions[0][1] = 1e-310;
  valid.WriteText(path);
  EXPECT_EQ(Packing::ReadText(path).radii, valid.radii);
  EXPECT_EQ(Packing::ReadText(path).positions, valid.positions);
  try {
    defects[5].second.Validate("state.h5:/final_state");
    FAIL() << "coincident spheres were accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("state.h5:/final_state: spheres 1 and 2"),
              std::string::npos)
        << error.what();
  }
}

TEST(Packing, GeneratedPackingsReadBack) {
  GenerationOptions options;
  options.count = 1000;
  options.cell_size = 5.8e-3;
  const Packing generated = GeneratePacking(GrainSizeDistribution::Default(), options);
  const std::string path = testing::TempPath("packing_generated.txt");
  generated.WriteText(path);
  const Packing read = Packing::ReadText(path);
  EXPECT_EQ(read.positions, generated.positions);
  EXPECT_EQ(read.radii, generated.radii);
}

// Generation requests that cannot fit, each refused before any allocation
// that grows with the count (on a machine of 16 GB for the memory case).
TEST(Packing, GenerationThatCannotFitIsRefusedAtOnce) {
  const std::string metres = testing::TempPath("gsd_in_metres.csv");
  std::ofstream(metres) << "diameter_mm,percent_passing_by_mass\n0.0001,0\n0.0005,40\n0.002,100\n";
  const GrainSizeDistribution in_metres = GrainSizeDistribution::ReadCsv(metres);
  const GrainSizeDistribution sand = GrainSizeDistribution::Default();
  struct Case {
    const char* name;
    const GrainSizeDistribution* gsd;
    size_t count;
    double cell_size;
    std::vector<std::string> mentions;
  };
  const std::vector<Case> cases = {
      {"diameters_in_metres",
       &in_metres,
       1000,
       5.8e-3,
       {"gsd_in_metres.csv", "reaches 0.002 mm at line 4", "cubes", "2^30", "in mm (not metres)"}},
      {"count_of_a_billion",
       &sand,
       1000000000,
       0.031,
       {"1000000000 spheres", "36 GB", "16 GB of physical memory"}},
      {"cell_below_two_diameters",
       &sand,
       1000,
       1.5e-3,
       {"cell side 1.5 mm", "twice the largest generated diameter", "reaches 1 mm at line 10"}},
      {"count_too_dense", &sand, 10000000, 0.031, {"10000000 spheres fill at least", "55 %"}},
      {"count_above_the_limit", &sand, size_t{3000000000}, 0.031, {"count 3000000000"}},
      {"infinite_cell", &sand, 1000, INFINITY, {"cell_size must be a finite number"}},
      {"zero_count", &sand, 0, 0.031, {"count must be > 0"}},
  };
  for (const Case& c : cases) {
    GenerationOptions options;
    options.count = c.count;
    options.cell_size = c.cell_size;
    try {
      CheckGenerationFits(*c.gsd, options, 16e9);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("sample generation"), std::string::npos) << c.name << message;
      for (const std::string& mention : c.mentions) {
        EXPECT_NE(message.find(mention), std::string::npos)
            << c.name << ": no '" << mention << "' in: " << message;
      }
    }
  }
  // GeneratePacking checks first (it would otherwise allocate a grid of 10¹³ bins).
  GenerationOptions options;
  options.count = 1000;
  options.cell_size = 5.8e-3;
  EXPECT_THROW(GeneratePacking(in_metres, options), InputError);
  // The default scene's request fits.
  EXPECT_NO_THROW(CheckGenerationFits(sand, GenerationOptions{}, 16e9));
  EXPECT_GT(PhysicalMemoryBytes(), 0.0);
}

TEST(Packing, GenerationEstimateBoundsTheSolidFractionFromBelow) {
  const std::string wide = testing::TempPath("gsd_wide.csv");
  std::ofstream(wide) << "diameter_mm,percent_passing_by_mass\n0.02,0\n0.2,30\n2,100\n";
  for (const GrainSizeDistribution& gsd :
       {GrainSizeDistribution::Default(), GrainSizeDistribution::ReadCsv(wide)}) {
    for (size_t count : {size_t{2}, size_t{3}, size_t{10}, size_t{1000}, size_t{30000}}) {
      GenerationOptions options;
      options.count = count;
      options.cell_size = 0.02;
      const GenerationEstimate estimate = EstimateGeneration(gsd, options);
      Packing packing;
      packing.cell = {0.02, 0.02, 0.02};
      packing.radii = gsd.QuantileRadii(count);
      const double solid = packing.SolidVolume() / (0.02 * 0.02 * 0.02);
      EXPECT_LE(estimate.min_solid_fraction, solid) << gsd.origin() << " " << count;
      EXPECT_EQ(estimate.largest_diameter, 2 * packing.radii.front());
      if (count >= 1000 && gsd.origin() != wide) {
        EXPECT_GT(estimate.min_solid_fraction, 0.9 * solid) << count;
      }
    }
  }
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
