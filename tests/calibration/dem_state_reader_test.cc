// DEM result files → asymptotic states: a file with the layout that
// dem/simulation.cc writes (series with units, stage groups with attributes).
#include "calibration/dem_state_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"

namespace granasym::calibration {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

// Stage 0: ψ_ε = 0 from 1 to 1000 kPa (NCL); stage 1: ψ_ε = 180° unloading;
// stage 2: ψ_ε = 90° with a detected asymptote; stage 3: 60° not detected.
std::string WriteDemFile() {
  const std::string path = TempPath("granasym_dem_states.h5");
  std::vector<double> p, e, psi;
  for (int i = 0; i <= 30; ++i) {  // rows 0..30: NCL
    const double pi = std::pow(10.0, 3.0 * i / 30);
    p.push_back(pi);
    e.push_back(std::exp(0.8 - 0.05 * std::log(pi)) - 1);
    psi.push_back(0.1);
  }
  for (int i = 1; i <= 10; ++i) {  // rows 31..40: unloading to 100 kPa
    const double pi = 1000.0 * std::pow(0.1, i / 10.0);
    p.push_back(pi);
    e.push_back(std::exp(0.8 - 0.05 * std::log(1000.0) - 0.01 * std::log(pi / 1000.0)) - 1);
    psi.push_back(0.0);
  }
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.WriteDoubles("/series/p_kpa", p, "kPa");
  file.WriteDoubles("/series/e", e, "1");
  file.WriteDoubles("/series/psi_sigma_deg", psi, "deg");
  file.CreateGroup("/stages");
  auto stage = [&file](int index, const char* name, double psi_e, int64_t first, int64_t last) {
    const std::string g = "/stages/00" + std::to_string(index);
    file.CreateGroup(g);
    file.SetAttribute(g, "name", name);
    file.SetAttribute(g, "type", "strain_path");
    file.SetAttribute(g, "first_row", first);
    file.SetAttribute(g, "last_row", last);
    file.SetAttribute(g, "stop_reason", "mean_stress");
    file.SetAttribute(g, "psi_epsilon_deg", psi_e);
    file.SetAttribute(g, "stretching_rate_per_s", 167.0);
    return g;
  };
  stage(0, "ncl", 0.0, 0, 30);
  stage(1, "unload", 180.0, 31, 40);
  const std::string csl = stage(2, "psi90", 90.0, 41, 40);
  file.SetAttribute(csl, "asymptote_detected", int64_t{1});
  file.SetAttribute(csl, "asymptote_psi_sigma_deg", 30.5);
  file.SetAttribute(csl, "asymptote_p_kpa", 321.0);
  file.SetAttribute(csl, "asymptote_e", 0.61);
  const std::string missed = stage(3, "psi60", 60.0, 41, 40);
  file.SetAttribute(missed, "asymptote_detected", int64_t{0});
  file.Commit();
  return path;
}

TEST(DemStateReader, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(DemReadOptions().IsValid(&why)) << why;
  DemReadOptions bad;
  bad.max_line_points = 1;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("max_line_points"), std::string::npos);
}

TEST(DemStateReader, TakesNclRowsUnloadingRowsAndDetectedAsymptotes) {
  const std::string path = WriteDemFile();
  DemReadOptions options;
  options.ncl_min_p_kpa = 10.0;
  options.max_line_points = 8;
  const StateDataset d = ReadStatesDem(path, "dem", options);
  EXPECT_EQ(d.Count(StateKind::kNcl), 8u);
  EXPECT_EQ(d.Count(StateKind::kCsl), 1u);
  EXPECT_GE(d.Count(StateKind::kUnloading), 5u);
  for (const AsymptoticStatePoint& point : d.points) {
    if (point.kind == StateKind::kNcl) {
      EXPECT_GE(point.mean_stress, 10.0);
      EXPECT_NEAR(std::log1p(point.void_ratio), 0.8 - 0.05 * std::log(point.mean_stress), 1e-12);
    }
    if (point.kind == StateKind::kCsl) {
      EXPECT_DOUBLE_EQ(point.mean_stress, 321.0);
      EXPECT_NEAR(point.psi_sigma, 30.5 * kDegree, 1e-15);
      EXPECT_NE(point.source.find("/stages/002 (psi90)"), std::string::npos) << point.source;
    }
  }
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("psi60"), std::string::npos) << d.warnings[0];
  EXPECT_NE(d.warnings[0].find("no asymptote detected"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(DemStateReader, RejectsFilesThatAreNotDemResults) {
  const std::string path = TempPath("granasym_not_dem.h5");
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.WriteDoubles("/x", {1.0});
  file.Commit();
  try {
    ReadStatesDem(path, "dem", {});
    FAIL() << "accepted a file without stages";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("not a granasym DEM result file"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace granasym::calibration
