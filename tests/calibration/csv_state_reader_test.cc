// CSV datasets: documented columns and units, and clear errors for bad data.
#include "calibration/csv_state_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/state_measures.h"
#include "tests/common/enum_spellings.h"

namespace granasym::calibration {
namespace {

std::string ErrorOf(const std::string& text, const CsvReadOptions& options = {}) {
  try {
    ParseStatesCsv(text, "lab.csv", "lab", options);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(CsvStateReader, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(CsvReadOptions().IsValid(&why)) << why;
  CsvReadOptions bad;
  bad.kind = "critical";
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("kind"), std::string::npos);
  EXPECT_NE(why.find("must be auto, ncl, csl, compression, extension, asbs or unloading"),
            std::string::npos)
      << why;
}

TEST(CsvStateReader, ReadsDocumentedColumnsAndConvertsUnits) {
  const std::string text =
      "# lab end states\n"
      "p_mpa,ln_1_plus_e,psi_sigma_rad,psi_epsilon_deg,weight,psi_sigma_uncertainty_deg\n"
      "0.2,0.7,0.0,0.0,2.0,0.25\n"
      "0.1,0.68,0.5,90.0,1.0,1.0\n"
      "0.1,0.66,0.3,45.0,1.0,1.0\n"
      "0.05,0.70,-0.2,-60.0,1.0,1.0\n";
  const StateDataset d = ParseStatesCsv(text, "lab.csv", "lab", {});
  ASSERT_EQ(d.points.size(), 4u);
  EXPECT_DOUBLE_EQ(d.points[0].mean_stress, 200.0);
  EXPECT_NEAR(std::log1p(d.points[0].void_ratio), 0.7, 1e-14);
  EXPECT_EQ(d.points[0].kind, StateKind::kNcl);
  EXPECT_EQ(d.points[1].kind, StateKind::kCsl);
  EXPECT_EQ(d.points[2].kind, StateKind::kCompression);
  EXPECT_EQ(d.points[3].kind, StateKind::kExtension);
  EXPECT_DOUBLE_EQ(d.points[1].psi_sigma, 0.5);
  EXPECT_DOUBLE_EQ(d.points[0].weight, 2.0);
  EXPECT_NEAR(d.points[0].psi_sigma_uncertainty, 0.25 * kDegree, 1e-15);
  EXPECT_NEAR(d.points[0].ln_volume_uncertainty, CsvReadOptions().ln_volume_uncertainty, 0);
  EXPECT_EQ(d.points[2].source, "lab.csv:5");
}

TEST(CsvStateReader, DerivesPsiSigmaFromDeviatorAndAcceptsAsbsWithoutStretching) {
  CsvReadOptions options;
  options.kind = "asbs";
  const StateDataset d = ParseStatesCsv("p_kpa,q_kpa,e\n100,60,0.8\n", "x.csv", "x", options);
  ASSERT_EQ(d.points.size(), 1u);
  EXPECT_NEAR(std::tan(d.points[0].psi_sigma), std::sqrt(2.0) / 3.0 * 0.6, 1e-14);
  EXPECT_EQ(d.points[0].kind, StateKind::kAsbs);
}

TEST(CsvStateReader, RejectsMissingColumnsNamingThem) {
  const std::string message = ErrorOf("p_kpa,psi_sigma_deg,psi_epsilon_deg\n100,0,0\n");
  EXPECT_NE(message.find("lab.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("void ratio"), std::string::npos) << message;
  EXPECT_NE(ErrorOf("p_kpa,e,psi_sigma_deg\n100,0.8,0\n").find("psi_epsilon_deg"),
            std::string::npos);
}

TEST(CsvStateReader, RejectsUnknownUnits) {
  const std::string message = ErrorOf("p_psi,e,psi_sigma_deg,psi_epsilon_deg\n14,0.8,0,0\n");
  EXPECT_NE(message.find("unknown units 'psi'"), std::string::npos) << message;
  EXPECT_NE(message.find("p_kpa"), std::string::npos) << message;
  EXPECT_NE(ErrorOf("p_kpa,e,psi_sigma_grad,psi_epsilon_deg\n1,0.8,0,0\n").find("unknown units"),
            std::string::npos);
}

TEST(CsvStateReader, RejectsUnknownColumnsUnlessIgnored) {
  const std::string text = "p_kpa,e,psi_sigma_deg,psi_epsilon_deg,time_s\n100,0.8,0,0,3\n";
  EXPECT_NE(ErrorOf(text).find("unknown column 'time_s'"), std::string::npos);
  CsvReadOptions options;
  options.ignore_columns = {"time_s"};
  EXPECT_EQ(ErrorOf(text, options), "");
}

TEST(CsvStateReader, RejectsNanNamingLineAndColumn) {
  const std::string message =
      ErrorOf("p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n100,0.8,0,0\n200,nan,0,0\n");
  EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  EXPECT_NE(message.find("'e'"), std::string::npos) << message;
}

TEST(CsvStateReader, RejectsEmptyFilesAndInvalidValues) {
  EXPECT_NE(ErrorOf("p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n").find("empty"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("empty"), std::string::npos);
  const std::string negative = ErrorOf("p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n-5,0.8,0,0\n");
  EXPECT_NE(negative.find("p_kpa = -5"), std::string::npos) << negative;
  const std::string tension = ErrorOf("p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n5,0.8,60,90\n");
  EXPECT_NE(tension.find("psi_sigma_deg = 60"), std::string::npos) << tension;
}

TEST(CsvStateReader, RoundTripsThroughWriteStatesCsv) {
  const StateDataset d = ParseStatesCsv(
      "p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n100,0.8,0,0\n50,0.85,30,90\n", "a.csv", "a", {});
  const std::string path =
      (std::filesystem::temp_directory_path() / "granasym_states_roundtrip.csv").string();
  WriteStatesCsv(d, path);
  const StateDataset back = ReadStatesCsv(path, "b", {});
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_NEAR(back.points[1].psi_sigma, d.points[1].psi_sigma, 1e-14);
  EXPECT_NEAR(back.points[1].void_ratio, 0.85, 1e-14);
  EXPECT_EQ(back.points[1].kind, StateKind::kCsl);
  std::filesystem::remove(path);
}

// The column rules of the reader, one case each: the message names the file,
// the line, the columns and the values at fault.
TEST(CsvStateReader, ColumnRuleBreaksNameFileLineAndColumns) {
  struct Case {
    const char* name;
    std::string text;
    std::vector<std::string> mentions;
  };
  const std::string h = "p_kpa,e,psi_sigma_deg,psi_epsilon_deg";
  const std::vector<Case> cases = {
      {"two_mean_stress_units",
       "p_kpa,e,psi_sigma_deg,psi_epsilon_deg,p_mpa\n100,0.8,0,0,0.1\n",
       {"line 1", "'p_kpa' (column 1)", "'p_mpa' (column 5)", "mean stress", "give one"}},
      {"three_mean_stress_units",
       "p_pa,p_mpa,p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n1,1,1,1,0,0\n",
       {"line 1", "'p_kpa' (column 3)", "'p_mpa' (column 2)"}},
      {"angle_in_degrees_and_radians",
       "# lab\np_kpa,e,psi_sigma_deg,psi_sigma_rad,psi_epsilon_deg\n100,0.8,0,0,0\n",
       {"line 2", "'psi_sigma_deg' (column 3)", "'psi_sigma_rad' (column 4)", "stress direction"}},
      {"direction_and_deviator",
       h + ",q_kpa\n100,0.8,0,0,0\n",
       {"line 1", "'psi_sigma_deg'", "'q_kpa'", "stress direction"}},
      {"stretching_in_two_units",
       h + ",psi_epsilon_rad\n100,0.8,0,0,0\n",
       {"line 1", "'psi_epsilon_deg'", "'psi_epsilon_rad'", "stretching direction"}},
      {"void_ratio_measures_disagree",
       "p_kpa,e,ln_1_plus_e,psi_sigma_deg,psi_epsilon_deg\n100,0.8,0.587787,0,0\n100,0.8,0.7,0,0\n",
       {"lab.csv:3", "'e' = 0.8", "'ln_1_plus_e' = 0.7", "disagree"}},
      {"duplicate_column", h + ",e\n100,0.8,0,0,0.8\n", {"line 1", "'e'", "columns 2 and 5"}},
      {"unknown_column",
       h + ",time_s\n100,0.8,0,0,3\n",
       {"line 1", "unknown column 'time_s'", "column 5", "known columns: p_kpa", "ignore_columns"}},
      {"unknown_units",
       "p_psi,e,psi_sigma_deg,psi_epsilon_deg\n14,0.8,0,0\n",
       {"line 1", "'p_psi'", "unknown units 'psi'", "p_kpa, p_mpa, p_pa"}},
      {"row_with_an_extra_field", h + "\n100,0.8,0,0\n100,0.8,0,0,5\n", {"line 3", "5 fields"}},
      {"text_in_a_number", h + "\n100,0.8,zero,0\n", {"line 2", "'psi_sigma_deg'", "'zero'"}},
      {"infinite_value", h + "\n100,inf,0,0\n", {"line 2", "'e'", "'inf'"}},
  };
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.text);
    ASSERT_NE(message, "") << c.name << ": accepted";
    EXPECT_NE(message.find("lab.csv"), std::string::npos) << c.name << ": " << message;
    for (const std::string& mention : c.mentions) {
      EXPECT_NE(message.find(mention), std::string::npos)
          << c.name << ": no '" << mention << "' in: " << message;
    }
  }
}

TEST(CsvStateReader, AnIgnoredColumnIsNeverReadEvenWhenItIsKnown) {
  CsvReadOptions options;
  options.ignore_columns = {"p_mpa", "q_kpa"};
  const StateDataset d =
      ParseStatesCsv("p_mpa,p_kpa,e,psi_sigma_deg,psi_epsilon_deg,q_kpa\n0.5,100,0.8,0,0,7\n",
                     "x.csv", "x", options);
  ASSERT_EQ(d.points.size(), 1u);
  EXPECT_DOUBLE_EQ(d.points[0].mean_stress, 100.0);
  EXPECT_DOUBLE_EQ(d.points[0].psi_sigma, 0.0);
}

TEST(CsvStateReader, ConsistentVoidRatioAndItsLogarithmMayBothBeGiven) {
  const StateDataset d =
      ParseStatesCsv("p_kpa,e,ln_1_plus_e,psi_sigma_deg,psi_epsilon_deg\n100,0.8,0.587787,0,0\n",
                     "x.csv", "x", {});
  ASSERT_EQ(d.points.size(), 1u);
  EXPECT_DOUBLE_EQ(d.points[0].void_ratio, 0.8);
}

TEST(StateDataset, KindsFollowTheStretchingDirection) {
  const double t = 0.5 * kDegree;
  EXPECT_EQ(KindFromStretching(0.2 * kDegree, t), StateKind::kNcl);
  EXPECT_EQ(KindFromStretching(89.8 * kDegree, t), StateKind::kCsl);
  EXPECT_EQ(KindFromStretching(45 * kDegree, t), StateKind::kCompression);
  EXPECT_EQ(KindFromStretching(100 * kDegree, t), StateKind::kExtension);
  EXPECT_EQ(KindFromStretching(-20 * kDegree, t), StateKind::kExtension);
  EXPECT_EQ(KindFromStretching(-180 * kDegree, t), StateKind::kUnloading);
  StateKind kind;
  for (const char* name : {"ncl", "csl", "compression", "extension", "asbs", "unloading"}) {
    ASSERT_TRUE(FromString(name, &kind));
    EXPECT_EQ(std::string(ToString(kind)), name);
  }
  EXPECT_FALSE(FromString("nel", &kind));
}

// CSV kind settings, the HDF5 record and the plot data use these spellings.
TEST(StateDataset, KindNamesAreSpelledAsInFilesAndResults) {
  ExpectSpellings<StateKind>({{StateKind::kNcl, "ncl"},
                              {StateKind::kCsl, "csl"},
                              {StateKind::kCompression, "compression"},
                              {StateKind::kExtension, "extension"},
                              {StateKind::kAsbs, "asbs"},
                              {StateKind::kUnloading, "unloading"}});
}

}  // namespace
}  // namespace granasym::calibration
