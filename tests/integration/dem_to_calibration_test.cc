// A DEM run written by the DEM and read by the calibration reader: the two
// sides share the run record's names (dem/run_record_names.h), and this test
// makes a renamed group, attribute or column fail here, never for a user.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "calibration/dem_state_reader.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "dem/scene.h"
#include "dem/simulation.h"

namespace granasym {
namespace {

std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "granasym_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// About 200 spheres: compressed isotropically past 50 kPa (NCL rows), then
// sheared isochorically with the detector on (loose tolerances: the sample
// is small).
const char* kScene = R"(
[sample.generate]
count = 200
cell_size_mm = 3.4
seed = 4
[numerics]
time_step_s = 1.2e-7
threads = 1
[output]
interval_strain = 0.004
[[stage]]
name = "ncl"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
[stage.stop]
mean_stress_kpa = 400.0
[[stage]]
name = "shear"
psi_epsilon_deg = 90.0
stretching_rate = 167.0
[stage.asymptote]
window_strain = 0.1
sample_strain = 0.005
psi_tolerance_deg = 20.0
lnp_tolerance = 1.0
[stage.stop]
asymptote = true
strain_norm = 0.6
)";

TEST(DemToCalibration, TheCalibrationReaderReadsWhatTheDemWrites) {
  const dem::Scene scene = dem::Scene::Parse(kScene, "dem_to_calibration.toml", "");
  dem::RunOptions options;
  options.output_path = TempPath("dem_to_calibration.h5");
  const dem::RunSummary summary = dem::RunScene(scene, options);
  ASSERT_EQ(summary.termination, dem::Termination::kCompleted) << summary.message;

  const Hdf5File file = Hdf5File::OpenRead(options.output_path);
  const TimeSeries series = TimeSeries::Read(file, dem::record::kSeries);
  const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
  ASSERT_EQ(stages.size(), 2u);
  ASSERT_TRUE(stages[1].asymptote.has_value());
  ASSERT_TRUE(stages[1].asymptote->detected) << stages[1].stop_reason;

  calibration::DemReadOptions read;
  const calibration::StateDataset dataset =
      calibration::ReadStatesDem(options.output_path, "dem", read);
  // Every NCL point is a row of the first stage with p >= 50 kPa; the
  // critical state is the detected asymptote of the second.
  const auto& p = series.Values(dem::record::kColumnMeanStress);
  const auto& e = series.Values(dem::record::kColumnVoidRatio);
  std::set<std::pair<double, double>> ncl_rows;
  for (int64_t r = stages[0].first_row; r <= stages[0].last_row; ++r) {
    if (p[r] >= read.ncl_min_p_kpa) ncl_rows.insert({p[r], e[r]});
  }
  int ncl = 0, csl = 0;
  for (const calibration::AsymptoticStatePoint& point : dataset.points) {
    if (point.kind == calibration::StateKind::kNcl) {
      ++ncl;
      EXPECT_EQ(ncl_rows.count({point.mean_stress, point.void_ratio}), 1u) << point.source;
      EXPECT_EQ(point.psi_epsilon, 0.0);
    } else if (point.kind == calibration::StateKind::kCsl) {
      ++csl;
      EXPECT_EQ(point.mean_stress, stages[1].asymptote->mean_stress_kpa);
      EXPECT_EQ(point.void_ratio, stages[1].asymptote->void_ratio);
      EXPECT_NEAR(point.psi_sigma / kDegree, stages[1].asymptote->psi_sigma_deg, 1e-12);
      EXPECT_NEAR(point.psi_epsilon / kDegree, 90.0, 1e-12);
    } else {
      ADD_FAILURE() << "unexpected state " << point.source;
    }
  }
  EXPECT_GE(ncl, 3);
  EXPECT_EQ(csl, 1);
}

}  // namespace
}  // namespace granasym
