// The replicates' ensemble-mean path of a stage (study/ensemble_path.h):
// the common strain axis, the average with its band over replicates of
// different lengths (aligned at the stage starts or ends), the detector on
// the mean path (a mean that holds where the replicates drift; replicates
// that stop at their own detections; an extension path that holds, then
// falls below the floor), which stages stop at their asymptote, and the
// chain of stages whose samples the detector carries on.
#include "study/ensemble_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"

namespace granasym::study {
namespace {
namespace fs = std::filesystem;

// A path of points every `step` of strain up to `length`, with ψ_σ, ln p and
// ln(1+e) functions of the strain, on a strain path of direction ψ_ε.
struct PathFunctions {
  std::function<double(double)> psi_sigma_deg, log_p, log_volume;
};
StagePath MakePath(const PathFunctions& f, double length, double step,
                   double psi_epsilon_deg = 30.0, double offset = 0.0) {
  const AxisymmetricRate unit = AxisymmetricRate::FromAngle(psi_epsilon_deg * kDegree, 1.0);
  StagePath path;
  for (double s = 0; s <= length + 1e-12; s += step) {
    const double strain = s == 0 ? 0.0 : std::min(s + offset, length);
    path.strain.push_back(strain);
    path.psi_sigma_deg.push_back(f.psi_sigma_deg(strain));
    path.log_p.push_back(f.log_p(strain));
    path.log_volume.push_back(f.log_volume(strain));
    path.eps_a.push_back(unit.axial * strain);
    path.eps_r.push_back(unit.radial * strain);
    path.time.push_back(strain / 167.0);
  }
  return path;
}

// A compression path (ψ_ε = 30°) along ln(1+e) = 0.6 − 0.05 ln p, ln p rising
// by 2 per unit strain from 20 kPa, ψ_σ = 20° plus a fluctuation of
// amplitude √2° (standard deviation 1°) and period 0.6 of strain whose phase
// is replicate k's: the three phases 120° apart cancel in the mean. At the
// centre of the window that ends at 1.0 the phases are 0°, 120° and 240°.
PathFunctions Compression(int k) {
  return {[k](double s) {
            const double phase = 2 * kPi * (s - 0.85) / 0.6 + 2 * kPi * k / 3.0;
            return 20.0 + std::sqrt(2.0) * std::sin(phase);
          },
          [](double s) { return std::log(20.0) + 2.0 * s; },
          [](double s) { return 0.6 - 0.05 * (std::log(20.0) + 2.0 * s); }};
}

dem::AsymptoteCriterion CompressionCriterion() {
  dem::AsymptoteCriterion c = dem::AsymptoteCriterion::For(dem::PathKind::kCompression);
  c.sample_strain = 0.002;
  return c;
}

TEST(EnsemblePath, ReplicatesThatDriftAloneHaveAMeanPathThatIsDetected) {
  std::vector<StagePath> paths;
  // The last window (0.3 of strain) ends at 1.0: across it each replicate's
  // fluctuation changes ψ_σ by 2.43 √2 |cos(phase at the centre)| = 1.7-3.4°.
  for (int k = 0; k < 3; ++k) paths.push_back(MakePath(Compression(k), 1.0, 0.002));
  for (const StagePath& path : paths) {
    const MeanPathDetection alone =
        DetectOnMeanPath(AveragePaths({path}, 0.002), CompressionCriterion());
    EXPECT_EQ(alone.result.status, dem::AsymptoteStatus::kDrifting);
    EXPECT_GT(alone.result.psi_change_deg, 1.0);
  }
  const MeanPath mean = AveragePaths(paths, 0.002);
  const MeanPathDetection detection = DetectOnMeanPath(mean, CompressionCriterion());
  EXPECT_EQ(detection.result.status, dem::AsymptoteStatus::kDetected);
  EXPECT_LT(detection.result.psi_change_deg, 1e-6);
  EXPECT_NEAR(detection.result.psi_sigma / kDegree, 20.0, 1e-6);
  EXPECT_NEAR(detection.result.slope_lnv_lnp, -0.05, 1e-9);
  EXPECT_NEAR(detection.result.window_strain, 0.3, 0.003);
  // The band: t(2) × the standard error of three values √2 sin(θ + 2πk/3),
  // whose sample standard deviation is √1.5 whatever θ.
  EXPECT_NEAR(detection.psi_sigma_band_deg, 4.303 * std::sqrt(1.5 / 3.0), 0.01);
  EXPECT_NEAR(detection.log_volume_band, 0.0, 1e-12);
}

TEST(EnsemblePath, ReplicatesOfDifferentLengthsAreAveragedOverTheirCommonRange) {
  auto line = [](double offset) {
    return PathFunctions{[offset](double s) { return 10.0 + offset + 5.0 * s; },
                         [offset](double s) { return 3.0 + offset - s; },
                         [offset](double s) { return 0.5 + 0.01 * offset + 0.1 * s; }};
  };
  // Rows 0.002 apart, one replicate's shifted by 0.001 (interpolated).
  const std::vector<StagePath> paths = {MakePath(line(-1.0), 0.5, 0.002),
                                        MakePath(line(0.0), 0.4, 0.002, 30.0, 0.001),
                                        MakePath(line(1.0), 0.45, 0.002)};
  EXPECT_NEAR(RowSpacing(paths), 0.002, 1e-12);
  const MeanPath mean = AveragePaths(paths, 0.002);
  EXPECT_EQ(mean.paths, 3);
  ASSERT_EQ(mean.mean.strain.size(), 201u);  // 0 to 0.4, the shortest
  EXPECT_NEAR(mean.mean.strain.back(), 0.4, 1e-12);
  for (size_t k = 0; k < mean.mean.strain.size(); k += 50) {
    const double s = mean.mean.strain[k];
    EXPECT_NEAR(mean.mean.psi_sigma_deg[k], 10.0 + 5.0 * s, 1e-9) << s;
    EXPECT_NEAR(mean.mean.log_p[k], 3.0 - s, 1e-9) << s;
    EXPECT_NEAR(mean.mean.log_volume[k], 0.5 + 0.1 * s, 1e-9) << s;
    EXPECT_NEAR(mean.mean.time[k], s / 167.0, 1e-9) << s;
    // Offsets −1, 0, 1: standard deviation 1, t(2) = 4.303.
    EXPECT_NEAR(mean.psi_sigma_band_deg[k], 4.303 / std::sqrt(3.0), 1e-3) << s;
    EXPECT_NEAR(mean.log_volume_band[k], 0.04303 / std::sqrt(3.0), 1e-5) << s;
  }
  EXPECT_TRUE(AveragePaths({paths[0], StagePath{}}, 0.002).mean.strain.empty());

  // Aligned at the stage ends: the mean's strain s is each path's at 0.4 − s
  // before its end, so its last point is every path's end; ε_a, ε_r and time
  // count from its first point.
  const MeanPath ends = AveragePaths(paths, 0.002, PathAlignment::kStageEnds);
  EXPECT_EQ(ends.alignment, PathAlignment::kStageEnds);
  ASSERT_EQ(ends.mean.strain.size(), 201u);
  EXPECT_NEAR(ends.mean.strain.back(), 0.4, 1e-12);
  // Path k ends at 0.5, 0.4 and 0.45: at mean strain s, the paths are at
  // s + 0.1, s and s + 0.05, with offsets −1, 0, 1.
  for (size_t k = 0; k < ends.mean.strain.size(); k += 50) {
    const double s = ends.mean.strain[k];
    EXPECT_NEAR(ends.mean.psi_sigma_deg[k], 10.0 + 5.0 * (s + 0.05), 1e-9) << s;
    EXPECT_NEAR(ends.mean.log_p[k], 3.0 - (s + 0.05), 1e-9) << s;
    EXPECT_NEAR(ends.mean.time[k], s / 167.0, 1e-9) << s;
    EXPECT_NEAR(ends.mean.eps_a[k], AxisymmetricRate::FromAngle(30.0 * kDegree, 1.0).axial * s,
                1e-9)
        << s;
  }
}

// The record of a replicate's detector-carrying stage.
dem::StageRecord ReplicateRecord(const dem::AsymptoteCriterion& criterion,
                                 dem::AsymptoteStatus status) {
  dem::StageRecord record;
  record.name = "psi100";
  record.type = "strain_path";
  dem::AsymptoteRecord a;
  a.path_kind = criterion.kind;
  a.criterion = criterion;
  a.status = status;
  a.coordination = 2.5;
  a.mechanical_coordination = 2.2;
  a.max_relative_overlap = 0.01;
  record.asymptote = a;
  record.validity.flags = {dem::ValidityFlag::kGas};
  return record;
}

// An isochoric path (ψ_ε = 90°) towards the critical state p = 100 kPa,
// ψ_σ = 25°, from 200 kPa and 33°, over a transient that ends at strain
// `transient` (ln(1+e) stays 0.55), stopped where the stage's detector (at
// the output interval, 0.002) first holds, as a stage with `stop.asymptote`.
constexpr double kCriticalLogP = 4.605170185988092;  // ln 100
StagePath StoppedAtItsAsymptote(double transient, const dem::AsymptoteCriterion& criterion) {
  auto gap = [transient](double s) { return std::pow(std::max(0.0, 1.0 - s / transient), 2); };
  const StagePath path =
      MakePath({[gap](double s) { return 25.0 + 8.0 * gap(s); },
                [gap](double s) { return kCriticalLogP + std::log(2.0) * gap(s); },
                [](double) { return 0.55; }},
               2.0, 0.002, 90.0);
  dem::AsymptoteDetector detector(criterion);
  StagePath stopped;
  for (size_t k = 0; k < path.strain.size(); ++k) {
    for (std::vector<double> StagePath::*field :
         {&StagePath::strain, &StagePath::psi_sigma_deg, &StagePath::log_p, &StagePath::log_volume,
          &StagePath::eps_a, &StagePath::eps_r, &StagePath::time}) {
      (stopped.*field).push_back((path.*field)[k]);
    }
    detector.Add({path.strain[k], path.psi_sigma_deg[k] * kDegree, path.log_p[k],
                  path.log_volume[k], path.eps_a[k], path.eps_r[k], path.time[k]});
    if (detector.Evaluate().detected()) break;
  }
  return stopped;
}

TEST(EnsemblePath, ReplicatesThatStopAtTheirOwnAsymptoteAreAlignedAtTheirEnds) {
  dem::AsymptoteCriterion criterion = dem::AsymptoteCriterion::For(dem::PathKind::kIsochoric);
  criterion.sample_strain = 0.002;
  std::vector<ReplicateStage> replicates;
  for (const double transient : {0.2, 0.35, 0.5}) {
    ReplicateStage r{ReplicateRecord(criterion, dem::AsymptoteStatus::kDetected),
                     StoppedAtItsAsymptote(transient, criterion), true};
    r.record.name = "psi90";
    r.record.asymptote->mechanical_coordination = 4.2;  // no gas
    r.record.validity.flags.clear();
    replicates.push_back(r);
  }
  // Each replicate stops where its own window held, past its transient:
  // at different strains, the first before the last has left its transient.
  const double first_end = replicates[0].path.strain.back();
  EXPECT_GT(first_end, 0.2);
  EXPECT_LT(first_end, 0.5);
  EXPECT_GT(replicates[2].path.strain.back() - first_end, 0.2);

  // Each replicate's own state: its last window, which held.
  double log_p = 0, psi_sigma_deg = 0;
  for (const ReplicateStage& r : replicates) {
    const MeanPathDetection alone = DetectOnMeanPath(AveragePaths({r.path}, 0.002), criterion);
    EXPECT_EQ(alone.result.status, dem::AsymptoteStatus::kDetected);
    log_p += std::log(alone.result.mean_stress_kpa) / 3.0;
    psi_sigma_deg += alone.result.psi_sigma / kDegree / 3.0;
  }

  const dem::StageRecord record = EnsembleStageRecord(replicates);
  ASSERT_TRUE(record.asymptote);
  const dem::AsymptoteRecord& a = *record.asymptote;
  EXPECT_EQ(a.status, dem::AsymptoteStatus::kDetected) << record.stop_reason;
  EXPECT_NEAR(a.window_strain, 0.15, 0.003);
  // The mean's last window averages the replicates' last windows: their
  // states, within 1.5 % and 0.2° of the stationary one (as close as their
  // own detectors stop to it).
  EXPECT_NEAR(std::log(a.mean_stress_kpa), log_p, 1e-9);
  EXPECT_NEAR(a.psi_sigma_deg, psi_sigma_deg, 1e-9);
  EXPECT_NEAR(a.mean_stress_kpa, 100.0, 1.5);
  EXPECT_NEAR(a.psi_sigma_deg, 25.0, 0.2);
  EXPECT_NEAR(a.void_ratio, std::expm1(0.55), 1e-12);
  EXPECT_NEAR(a.psi_epsilon_deg, 90.0, 1e-6);
  EXPECT_NE(record.stop_reason.find("aligned at the stage ends"), std::string::npos)
      << record.stop_reason;
  // Over the common range from the starts, the mean ends where two
  // replicates are still in their transients: p still falls.
  for (ReplicateStage& r : replicates) r.stops_at_asymptote = false;
  const dem::StageRecord starts = EnsembleStageRecord(replicates);
  EXPECT_EQ(starts.asymptote->status, dem::AsymptoteStatus::kDrifting) << starts.stop_reason;
  EXPECT_GT(starts.asymptote->mean_stress_kpa, 110.0);
  EXPECT_NE(starts.stop_reason.find("aligned at the stage starts"), std::string::npos);
}

// An extension path (ψ_ε = 100°) from 50 kPa: ψ_σ stationary at 40° with
// replicate fluctuations, ln p falling steadily, below the floor of 0.5 kPa
// from a strain of 0.92 on, to 0.12 kPa at 1.2.
PathFunctions Extension(int k) {
  return {[k](double s) { return 40.0 + 0.5 * std::sin(2 * kPi * s / 0.4 + 2 * kPi * k / 3.0); },
          [](double s) { return std::log(50.0) - 5.0 * s; },
          [](double s) { return 0.55 + 0.2 * s; }};
}

TEST(EnsemblePath, AnExtensionMeanPathKeepsItsLastWindowAboveTheFloor) {
  const dem::AsymptoteCriterion criterion = dem::AsymptoteCriterion::For(dem::PathKind::kExtension);
  std::vector<ReplicateStage> replicates;
  for (int k = 0; k < 3; ++k) {
    replicates.push_back({ReplicateRecord(criterion, dem::AsymptoteStatus::kGas),
                          MakePath(Extension(k), 1.2, 0.002, 100.0)});
  }
  const dem::StageRecord record = EnsembleStageRecord(replicates);
  ASSERT_TRUE(record.asymptote);
  const dem::AsymptoteRecord& a = *record.asymptote;
  EXPECT_EQ(a.status, dem::AsymptoteStatus::kDetected) << record.stop_reason;
  EXPECT_TRUE(a.before_end);
  EXPECT_GE(a.p_min_kpa, criterion.floor_kpa);
  EXPECT_LT(a.p_min_kpa, 0.6);  // the last window that held ends near the floor
  EXPECT_NEAR(a.psi_sigma_deg, 40.0, 1e-6);
  EXPECT_DOUBLE_EQ(a.criterion.sample_strain, 0.002);  // the output interval
  EXPECT_NEAR(a.mechanical_coordination, 2.2, 1e-12);
  EXPECT_EQ(record.validity.flags, std::vector<dem::ValidityFlag>{dem::ValidityFlag::kGas});
  EXPECT_NE(record.stop_reason.find("ensemble mean of 3 replicates"), std::string::npos);
  EXPECT_NE(record.stop_reason.find("aligned at the stage starts"), std::string::npos);
  // As a replicate's record says it (dem::RecordStage).
  EXPECT_NE(record.stop_reason.find("last held over p"), std::string::npos);
  EXPECT_NE(record.stop_reason.find("then left the valid range p >= 0.5 kPa (p 0.1239 kPa at the "
                                    "end)"),
            std::string::npos)
      << record.stop_reason;

  // A path that is below the floor before a window fills: no state, and a
  // gas where every replicate was one.
  for (ReplicateStage& r : replicates) {
    r.path = MakePath({Extension(0).psi_sigma_deg, [](double s) { return std::log(0.6) - 5.0 * s; },
                       Extension(0).log_volume},
                      0.5, 0.002, 100.0);
  }
  EXPECT_EQ(EnsembleStageRecord(replicates).asymptote->status, dem::AsymptoteStatus::kGas);
  replicates[0].record.asymptote->status = dem::AsymptoteStatus::kDrifting;
  EXPECT_EQ(EnsembleStageRecord(replicates).asymptote->status, dem::AsymptoteStatus::kGas)
      << "its last window lies below the floor";
}

TEST(EnsemblePath, TheStrainOfARunsRowsIsTheNormOfTheirStrainIncrements) {
  namespace r = dem::record;
  TimeSeries series({{r::kColumnMeanStress, "kPa", ""},
                     {r::kColumnVoidRatio, "1", ""},
                     {r::kColumnPsiSigma, "deg", ""},
                     {r::kColumnAxialStrain, "1", ""},
                     {r::kColumnRadialStrain, "1", ""},
                     {r::kColumnTime, "s", ""}});
  // Two rows before the stage, then ψ_ε = 0° (Δε_a = Δε_r) and 90°.
  series.AddRow({1, 0.8, 0, 0.5, 0.5, 1.0});
  series.AddRow({0, 0.8, 0, 0.5, 0.5, 1.5});
  series.AddRow({10, 0.7, 1, 0.51, 0.51, 2.0});
  series.AddRow({20, 0.6, 2, 0.53, 0.49, 3.0});
  const StagePath path = ReadStagePath(series, 1, 3);
  ASSERT_EQ(path.strain.size(), 3u);
  EXPECT_EQ(path.strain[0], 0.0);
  EXPECT_NEAR(path.strain[1], std::sqrt(3.0) * 0.01, 1e-12);
  EXPECT_NEAR(path.strain[2], std::sqrt(3.0) * 0.01 + std::sqrt(0.02 * 0.02 + 2 * 0.02 * 0.02),
              1e-12);
  EXPECT_TRUE(std::isnan(path.log_p[0]));  // p = 0: the detector restarts
  EXPECT_NEAR(path.log_p[2], std::log(20.0), 1e-12);
  EXPECT_NEAR(path.log_volume[1], std::log1p(0.7), 1e-12);
  EXPECT_NEAR(path.eps_r[2], -0.01, 1e-12);
  EXPECT_NEAR(path.time[2], 1.5, 1e-12);
}

// Stages of a result: an isotropic chain (two stages of one path and one
// criterion), then another ψ_ε.
TEST(EnsemblePath, TheDetectorsSamplesStartAtTheFirstStageOfTheirPath) {
  const std::string path = (fs::temp_directory_path() / "granasym_ensemble_chain.h5").string();
  std::vector<dem::StageRecord> stages(3);
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.CreateGroup(dem::record::kStages);
  for (size_t k = 0; k < stages.size(); ++k) {
    stages[k] = ReplicateRecord(CompressionCriterion(), dem::AsymptoteStatus::kDrifting);
    stages[k].asymptote_criterion = CompressionCriterion().Describe();
    stages[k].first_row = static_cast<int64_t>(10 * k);
    const std::string group = dem::StageGroup(k);
    dem::WriteStageRecord(file, group, stages[k], nullptr, 1);
    file.SetAttribute(group, dem::record::kStagePsiEpsilonDeg, k < 2 ? 0.0 : 30.0);
    file.SetAttribute(group, dem::record::kStageStretchingRate, 167.0);
    file.SetAttribute(group, dem::record::kStageRateRule, "constant");
  }
  file.Commit();
  const Hdf5File read = Hdf5File::OpenRead(path);
  EXPECT_EQ(DetectionFirstRow(read, stages, 0), 0);
  EXPECT_EQ(DetectionFirstRow(read, stages, 1), 0);
  EXPECT_EQ(DetectionFirstRow(read, stages, 2), 20);
  stages[1].asymptote_criterion += " (another criterion)";
  EXPECT_EQ(DetectionFirstRow(read, stages, 1), 10);
  fs::remove(path);
}

// Whether a stage stops at its asymptote: its scene's stop, or without one
// recorded, its stop reason.
TEST(EnsemblePath, AStageStopsAtItsAsymptoteWhereItsSceneSaysSo) {
  namespace r = dem::record;
  const std::string path = (fs::temp_directory_path() / "granasym_ensemble_stop.h5").string();
  std::vector<dem::StageRecord> stages(2);
  stages[0].name = "p20";
  stages[0].stop_reason = "mean stress reached";
  stages[1].name = "psi90";
  stages[1].stop_reason = "strain norm reached";  // the scene decides, not how it ended
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.CreateGroup(r::kProvenance);
  file.WriteString(std::string(r::kProvenance) + "/" + r::kSceneCanonical,
                   "stage[0].name = \"p20\"\nstage[0].stop.asymptote = false\n"
                   "stage[0].stop.mean_stress_kpa = 20\nstage[1].name = \"psi90\"\n"
                   "stage[1].stop.asymptote = true\nstage[1].stop.strain_norm = 0.8\n");
  file.Commit();
  const Hdf5File read = Hdf5File::OpenRead(path);
  EXPECT_FALSE(StopsAtAsymptote(read, stages, 0));
  EXPECT_TRUE(StopsAtAsymptote(read, stages, 1));
  // Without the scene: the stage that stopped at its detection.
  const std::string bare = (fs::temp_directory_path() / "granasym_ensemble_bare.h5").string();
  Hdf5File without = Hdf5File::CreateAtomic(bare);
  without.CreateGroup(r::kStages);
  without.Commit();
  stages[1].stop_reason = "asymptotic state detected (isochoric: p 136.7 kPa, ...)";
  const Hdf5File read_bare = Hdf5File::OpenRead(bare);
  EXPECT_FALSE(StopsAtAsymptote(read_bare, stages, 0));
  EXPECT_TRUE(StopsAtAsymptote(read_bare, stages, 1));
  fs::remove(path);
  fs::remove(bare);
}

}  // namespace
}  // namespace granasym::study
