// DEM result files → asymptotic states: a file with the layout that
// dem/simulation.cc writes (series with units, stage groups with attributes).
#include "calibration/dem_state_reader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"

namespace granasym::calibration {
namespace {

// Per process: ctest runs the tests of this file in parallel processes,
// and each writes its file.
std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name))
      .string();
}

// Stage 0: ψ_ε = 0 from 1 to 1000 kPa (NCL); stage 1: ψ_ε = 180° unloading;
// stage 2: ψ_ε = 90° with a detected asymptote (isochoric: slope 0); stage 3:
// 60° not detected; stage 4: 30° detected, on the line of kSlope through
// (kAsymptoteP, kAsymptoteE); stage 5: 45° detected, without a slope attribute.
constexpr double kSlope = -0.05, kAsymptoteP = 200.0, kAsymptoteE = 0.75;
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
  file.SetAttribute(csl, "asymptote_dln1pe_dlnp", 0.0);
  const std::string missed = stage(3, "psi60", 60.0, 41, 40);
  file.SetAttribute(missed, "asymptote_detected", int64_t{0});
  const std::string compression = stage(4, "psi30", 30.0, 41, 40);
  file.SetAttribute(compression, "asymptote_detected", int64_t{1});
  file.SetAttribute(compression, "asymptote_psi_sigma_deg", 12.0);
  file.SetAttribute(compression, "asymptote_p_kpa", kAsymptoteP);
  file.SetAttribute(compression, "asymptote_e", kAsymptoteE);
  file.SetAttribute(compression, "asymptote_dln1pe_dlnp", kSlope);
  const std::string old_file = stage(5, "psi45", 45.0, 41, 40);
  file.SetAttribute(old_file, "asymptote_detected", int64_t{1});
  file.SetAttribute(old_file, "asymptote_psi_sigma_deg", 18.0);
  file.SetAttribute(old_file, "asymptote_p_kpa", 250.0);
  file.SetAttribute(old_file, "asymptote_e", 0.7);
  // A drained triaxial stage: no psi_epsilon of its own, the asymptote's
  // measured from the strain increments (a critical state).
  const std::string triaxial = "/stages/006";
  file.CreateGroup(triaxial);
  file.SetAttribute(triaxial, "name", "triaxial");
  file.SetAttribute(triaxial, "type", "triaxial");
  file.SetAttribute(triaxial, "first_row", int64_t{41});
  file.SetAttribute(triaxial, "last_row", int64_t{40});
  file.SetAttribute(triaxial, "stop_reason", "asymptote");
  file.SetAttribute(triaxial, "asymptote_detected", int64_t{1});
  file.SetAttribute(triaxial, "asymptote_psi_epsilon_deg", 90.4);
  file.SetAttribute(triaxial, "asymptote_psi_sigma_deg", 22.0);
  file.SetAttribute(triaxial, "asymptote_p_kpa", 280.0);
  file.SetAttribute(triaxial, "asymptote_e", 0.65);
  file.SetAttribute(triaxial, "asymptote_dln1pe_dlnp", 0.0);
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
  EXPECT_EQ(d.Count(StateKind::kCsl), 2u);  // the 90° path and the drained triaxial
  EXPECT_GE(d.Count(StateKind::kUnloading), 5u);
  for (const AsymptoticStatePoint& point : d.points) {
    if (point.kind == StateKind::kNcl) {
      EXPECT_GE(point.mean_stress, 10.0);
      EXPECT_NEAR(std::log1p(point.void_ratio), 0.8 - 0.05 * std::log(point.mean_stress), 1e-12);
    }
    if (point.kind == StateKind::kCsl && point.source.find("psi90") != std::string::npos) {
      EXPECT_DOUBLE_EQ(point.mean_stress, 321.0);
      EXPECT_NEAR(point.psi_sigma, 30.5 * kDegree, 1e-15);
      EXPECT_NE(point.source.find("/stages/002 (psi90)"), std::string::npos) << point.source;
    } else if (point.kind == StateKind::kCsl) {
      EXPECT_NE(point.source.find("/stages/006 (triaxial)"), std::string::npos) << point.source;
      EXPECT_DOUBLE_EQ(point.mean_stress, 280.0);
      EXPECT_NEAR(point.psi_epsilon, 90.4 * kDegree, 1e-15);
    }
  }
  ASSERT_EQ(d.warnings.size(), 2u);
  EXPECT_NE(d.warnings[0].find("psi60"), std::string::npos) << d.warnings[0];
  EXPECT_NE(d.warnings[0].find("no asymptote detected"), std::string::npos);
  // 8 NCL and 10 unloading rows against 4 asymptotic states.
  EXPECT_NE(d.warnings[1].find("rows against 4 asymptotic states"), std::string::npos)
      << d.warnings[1];
  std::filesystem::remove(path);
}

TEST(DemStateReader, RejectsInvalidAsbsValuesNamingTheKey) {
  for (const double bad : {std::nan(""), 0.0, -0.3, std::numeric_limits<double>::infinity()}) {
    DemReadOptions options;
    options.asbs_ln_1_plus_e = {0.55, bad};
    std::string why;
    EXPECT_FALSE(options.IsValid(&why)) << bad;
    EXPECT_NE(why.find("asbs_ln_1_plus_e[1]"), std::string::npos) << why;
  }
  DemReadOptions good;
  good.asbs_ln_1_plus_e = {0.55, 0.58};
  std::string why;
  EXPECT_TRUE(good.IsValid(&why)) << why;
}

TEST(DemStateReader, AsbsPointsLieOnTheAsymptoticLineOfEachUsableStage) {
  const std::string path = WriteDemFile();
  DemReadOptions options;
  options.ncl_min_p_kpa = 10.0;
  options.max_line_points = 8;
  // 0.65 lies (0.65 − ln 1.75) / 0.05 ≈ 1.8 in ln p from the asymptote: too far.
  options.asbs_ln_1_plus_e = {0.55, 0.58, 0.65};
  const StateDataset d = ReadStatesDem(path, "dem", options);
  EXPECT_EQ(d.Count(StateKind::kNcl), 8u);
  EXPECT_EQ(d.Count(StateKind::kCsl), 2u);          // psi90 and the triaxial
  EXPECT_EQ(d.Count(StateKind::kCompression), 2u);  // psi30 and psi45 asymptotes
  ASSERT_EQ(d.Count(StateKind::kAsbs), 2u);
  const double targets[] = {0.55, 0.58};
  size_t k = 0;
  for (const AsymptoticStatePoint& point : d.points) {
    if (point.kind != StateKind::kAsbs) continue;
    ASSERT_LT(k, 2u);
    const double target = targets[k++];
    EXPECT_NEAR(std::log1p(point.void_ratio), target, 1e-14);
    // On the line: Δ ln(1+e) = slope · Δ ln p from the asymptote.
    EXPECT_NEAR(std::log1p(point.void_ratio) - std::log1p(kAsymptoteE),
                kSlope * (std::log(point.mean_stress) - std::log(kAsymptoteP)), 1e-14);
    EXPECT_NEAR(point.psi_sigma, 12.0 * kDegree, 1e-15);
    EXPECT_NEAR(point.psi_epsilon, 30.0 * kDegree, 1e-15);
    EXPECT_FALSE(point.HasStretching());
    EXPECT_NE(point.source.find("/stages/004 (psi30)"), std::string::npos) << point.source;
    EXPECT_NE(point.source.find(fmt::format("ln(1+e) = {:g}", target)), std::string::npos)
        << point.source;
  }
  auto warned = [&d](const std::string& a, const std::string& b) {
    for (const std::string& w : d.warnings) {
      if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(warned("psi90", "asymptote_dln1pe_dlnp = 0 is not usable"));
  EXPECT_TRUE(warned("psi45", "no asymptote_dln1pe_dlnp attribute"));
  EXPECT_TRUE(warned("psi30", "ln(1+e) = 0.65 skipped"));
  EXPECT_TRUE(warned("psi30", "extrapolation limit"));
  EXPECT_TRUE(warned("psi60", "no asymptote detected"));
  EXPECT_TRUE(warned("triaxial", "asymptote_dln1pe_dlnp = 0 is not usable"));
  // With the ASBS points the line rows no longer outnumber the states 3:1.
  EXPECT_FALSE(warned("rows against", "asymptotic states"));
  EXPECT_EQ(d.warnings.size(), 5u);
  std::filesystem::remove(path);
}

// An unload–reload cycle from the NCL (paper Fig. 9): loading to 200 kPa,
// unloading (180°) to 50 kPa, reloading (0°) to 500 kPa. The reload rows
// below 200 kPa are unloading points, never NCL rows; those above are NCL.
TEST(DemStateReader, ReloadRowsGoToUnloadingNeverToTheNcl) {
  const std::string path = TempPath("granasym_dem_cycle.h5");
  constexpr double kN = 0.8, kLambda = 0.05, kKappa = 0.01;
  std::vector<double> p, e, psi;
  const auto add = [&](double pi, double ln_v) {
    p.push_back(pi);
    e.push_back(std::expm1(ln_v));
    psi.push_back(0.0);
  };
  for (int i = 0; i <= 20; ++i) {  // rows 0..20: NCL 10 -> 200 kPa
    const double pi = 10.0 * std::pow(20.0, i / 20.0);
    add(pi, kN - kLambda * std::log(pi));
  }
  const double ln_v_max = kN - kLambda * std::log(200.0);
  for (int i = 1; i <= 10; ++i) {  // rows 21..30: unloading to 50 kPa
    const double pi = 200.0 * std::pow(0.25, i / 10.0);
    add(pi, ln_v_max - kKappa * std::log(pi / 200.0));
  }
  for (int i = 1; i <= 20; ++i) {  // rows 31..50: reloading to 500 kPa
    const double pi = 50.0 * std::pow(10.0, i / 20.0);
    add(pi, pi <= 200.0 ? ln_v_max - kKappa * std::log(pi / 200.0) : kN - kLambda * std::log(pi));
  }
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("/series/p_kpa", p, "kPa");
    file.WriteDoubles("/series/e", e, "1");
    file.WriteDoubles("/series/psi_sigma_deg", psi, "deg");
    file.CreateGroup("/stages");
    const auto stage = [&file](int index, const char* name, double psi_e, int64_t first,
                               int64_t last) {
      const std::string g = "/stages/00" + std::to_string(index);
      file.CreateGroup(g);
      file.SetAttribute(g, "name", name);
      file.SetAttribute(g, "type", "strain_path");
      file.SetAttribute(g, "first_row", first);
      file.SetAttribute(g, "last_row", last);
      file.SetAttribute(g, "psi_epsilon_deg", psi_e);
    };
    stage(0, "load", 0.0, 0, 20);
    stage(1, "unload1", 180.0, 21, 30);
    stage(2, "reload1", 0.0, 31, 50);
    file.Commit();
  }
  DemReadOptions options;
  options.ncl_min_p_kpa = 5.0;
  options.max_line_points = 30;
  options.unloading_weight = 0.7;
  const StateDataset d = ReadStatesDem(path, "cycle", options);
  int reload = 0, ncl_above = 0;
  for (const AsymptoticStatePoint& point : d.points) {
    const bool in_reload = point.source.find("reload1") != std::string::npos;
    if (point.kind == StateKind::kNcl) {
      // Every NCL point lies on the NCL: none is a reload row below 200 kPa.
      EXPECT_NEAR(std::log1p(point.void_ratio), kN - kLambda * std::log(point.mean_stress), 1e-12)
          << point.source;
      EXPECT_DOUBLE_EQ(point.weight, 1.0);
      ncl_above += in_reload ? 1 : 0;
      if (in_reload) {
        EXPECT_GE(point.mean_stress, 200.0);
      }
    } else {
      ASSERT_EQ(point.kind, StateKind::kUnloading) << point.source;
      EXPECT_DOUBLE_EQ(point.weight, 0.7);
      EXPECT_TRUE(point.IsFittedUnloading());
      EXPECT_FALSE(point.IsFitted());  // not an asymptotic state
      if (in_reload) {
        ++reload;
        EXPECT_LT(point.mean_stress, 200.0);
        EXPECT_NE(point.source.find("reloading below the earlier largest p"), std::string::npos);
        // The branch starts at the reversal, the last unloading row.
        EXPECT_DOUBLE_EQ(point.branch_start_p, p[30]);
        EXPECT_DOUBLE_EQ(point.branch_start_e, e[30]);
      } else {
        EXPECT_DOUBLE_EQ(point.branch_start_p, p[20]);
      }
    }
  }
  EXPECT_GE(reload, 10);
  EXPECT_GE(ncl_above, 5);
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
