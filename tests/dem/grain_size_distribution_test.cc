// GSD tables: every defect of a table read from CSV is refused naming the
// file, the line (or column) and the value.
#include "dem/grain_size_distribution.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

struct GsdCase {
  const char* name;
  std::string text;
  std::vector<std::string> mentions;  // besides the file name
};

const std::string kHeader = "diameter_mm,percent_passing_by_mass\n";

const std::vector<GsdCase>& GsdTableCases() {
  static const std::vector<GsdCase> cases = {
      {"diameter_1e-300_mm", kHeader + "1e-300,0\n1,100\n", {"line 2", "1e-300 mm", "[1e-06"}},
      {"diameter_1e7_mm", kHeader + "0.2,0\n1e7,100\n", {"line 3", "1e+07 mm", "1e+06] mm"}},
      {"negative_diameter", kHeader + "-0.2,0\n1,100\n", {"line 2", "-0.2 mm"}},
      {"zero_diameter", kHeader + "0,0\n1,100\n", {"line 2", "diameter 0 mm"}},
      {"range_0.001_to_10_mm",
       kHeader + "0.001,0\n0.1,40\n10,100\n",
       {"0.001 mm (line 2)", "10 mm (line 4)", "ratio of 10000", "at most 100", "in mm?"}},
      {"decreasing_diameters",
       kHeader + "0.2,0\n0.6,50\n0.4,100\n",
       {"line 4", "diameter 0.4 mm", "previous 0.6 mm", "strictly increasing"}},
      {"repeated_diameter", kHeader + "0.2,0\n0.6,50\n0.6,100\n", {"line 4", "0.6 mm"}},
      {"percent_above_100",
       kHeader + "0.2,0\n0.6,120\n1,100\n",
       {"line 3", "percent passing 120", "[0, 100]"}},
      {"negative_percent", kHeader + "0.2,-5\n1,100\n", {"line 2", "percent passing -5"}},
      {"decreasing_percent",
       kHeader + "0.2,0\n0.6,60\n0.8,50\n1,100\n",
       {"line 4", "percent passing 50", "previous 60", "non-decreasing"}},
      {"not_ending_at_100",
       kHeader + "0.2,0\n0.6,50\n1,90\n",
       {"line 4", "percent passing 90", "must end at 100"}},
      {"not_starting_at_0",
       kHeader + "0.2,10\n1,100\n",
       {"line 2", "percent passing 10", "must start at 0"}},
      {"one_sieve", kHeader + "1,100\n", {"at least two sieves", "got 1"}},
      {"no_rows", kHeader, {"at least two sieves", "got 0"}},
      {"nan_diameter",
       kHeader + "0.2,0\nnan,50\n1,100\n",
       {"line 3", "column 'diameter_mm'", "'nan'", "finite"}},
      {"infinite_percent", kHeader + "0.2,0\n1,inf\n", {"line 3", "column 'percent", "'inf'"}},
      {"text_in_a_number", kHeader + "0.2,0\n1,all\n", {"line 3", "'all'"}},
      {"duplicate_column",
       "diameter_mm,percent_passing_by_mass,diameter_mm\n0.2,0,0.2\n1,100,1\n",
       {"line 1", "'diameter_mm'", "columns 1 and 3"}},
      {"unknown_column",
       "diameter_mm,percent_passing_by_mass,sieve\n0.2,0,1\n1,100,2\n",
       {"line 1", "unknown column 'sieve'", "column 3",
        "known columns: diameter_mm, percent_passing_by_mass"}},
      {"misspelt_column",
       "diameter_mm,percent_passing\n0.2,0\n1,100\n",
       {"line 1", "unknown column 'percent_passing'"}},
      {"missing_column",
       "diameter_mm\n0.2\n1\n",
       {"missing column 'percent_passing_by_mass'", "columns present: diameter_mm"}},
      {"row_with_an_extra_field",
       kHeader + "0.2,0\n0.6,50,7\n1,100\n",
       {"line 3", "3 fields", "2 columns"}},
      {"row_with_a_missing_field", kHeader + "0.2,0\n0.6\n1,100\n", {"line 3", "1 fields"}},
      {"comments_shift_the_lines",
       "# sand\n\n" + kHeader + "0.2,0\n0.1,100\n",
       {"line 5", "diameter 0.1 mm"}},
      {"empty_file", "", {"no header row"}},
  };
  return cases;
}

TEST(GrainSizeDistribution, EveryDefectOfATableNamesFileLineAndValue) {
  for (const GsdCase& c : GsdTableCases()) {
    const std::string path = testing::TempPath(std::string("gsd_") + c.name + ".csv");
    std::ofstream(path) << c.text;
    try {
      GrainSizeDistribution::ReadCsv(path);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path), std::string::npos) << c.name << ": " << message;
      for (const std::string& mention : c.mentions) {
        EXPECT_NE(message.find(mention), std::string::npos)
            << c.name << ": no '" << mention << "' in: " << message;
      }
    }
  }
}

TEST(GrainSizeDistribution, ColumnsInAnyOrderCommentsAndTheWidestRatioAreAccepted) {
  const std::string path = testing::TempPath("gsd_valid.csv");
  std::ofstream(path) << "# a comment\npercent_passing_by_mass,diameter_mm\n0,0.01\n"
                         "0,0.02\n50,0.5\n100,2\n100,4\n";
  const GrainSizeDistribution gsd = GrainSizeDistribution::ReadCsv(path);
  EXPECT_DOUBLE_EQ(gsd.min_diameter(), 0.02e-3);
  EXPECT_DOUBLE_EQ(gsd.max_diameter(), 2e-3);  // a ratio of exactly kMaxDiameterRatio
  EXPECT_EQ(gsd.RowName(gsd.MaxDiameterRow()), "line 6");
  EXPECT_EQ(GrainSizeDistribution({1e-3, 2e-3}, {0, 100}).RowName(1), "row 2");
}

TEST(GrainSizeDistribution, OneQuantileRadiusEqualsItsPlaceInTheFullSet) {
  const GrainSizeDistribution gsd = GrainSizeDistribution::Default();
  const std::vector<double> radii = gsd.QuantileRadii(997);
  for (size_t k : {size_t{0}, size_t{1}, size_t{500}, size_t{996}}) {
    EXPECT_EQ(gsd.QuantileRadius(k, 997), radii[k]) << k;
  }
}

TEST(GrainSizeDistribution, MeanSphereVolumeIsTheLimitOfTheQuantileRadii) {
  const GrainSizeDistribution gsd = GrainSizeDistribution::Default();
  const size_t count = 200000;
  double volume = 0.0;
  for (double r : gsd.QuantileRadii(count))
    volume += 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
  EXPECT_NEAR(volume / count / gsd.MeanSphereVolume(), 1.0, 1e-3);
}

}  // namespace
}  // namespace granasym::dem
