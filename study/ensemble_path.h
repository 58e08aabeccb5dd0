// The replicates' ensemble-mean path of a stage, run through the stage's own
// asymptote detector (issue 34 §3, SPEC §8.4): at 3000 spheres ψ_σ of one
// path fluctuates by about ±1°, so that many single paths end drifting while
// the mean of the replicates is the cleaner state.
//
// The paths are averaged at a common accumulated strain of the stage,
// ∫‖D‖dt (the detector's Sample.strain), taken from the increments of the
// logarithmic strains between output rows, ‖Δε‖ = √(Δε_a² + 2 Δε_r²), exact
// on a proportional path. Every replicate follows the same prescribed strain
// path (strain-path stages; stress-controlled drained stages also advance in
// strain), so strain is the one axis that all replicates share exactly;
// ln p is not monotone along extension paths at the paper's rate (dense
// flows whose p barely moves) nor along isochoric paths.
#pragma once

#include <cstdint>
#include <vector>

#include "dem/asymptote_detector.h"
#include "dem/run_record.h"

namespace granasym {
class Hdf5File;
class TimeSeries;
}  // namespace granasym

namespace granasym::study {

// A stage's path as the detector samples it, one point per output row.
// Strain, time and the strains count from the path's first row.
struct StagePath {
  std::vector<double> strain;                            // accumulated strain ∫‖D‖dt
  std::vector<double> psi_sigma_deg, log_p, log_volume;  // ψ_σ (deg), ln(p/kPa), ln(1+e)
  std::vector<double> eps_a, eps_r, time;                // compression positive; s
};

// Output rows [first_row, last_row] of a run's series as a path; ln p is
// NaN where p <= 0 (the detector restarts there).
StagePath ReadStagePath(const TimeSeries& series, int64_t first_row, int64_t last_row);

// The first output row of the detector's samples of stage `index` of a
// result: its own, or that of the first of the stages before it that
// continue one path with one criterion (dem::Stage::ContinuesDetection:
// the same criterion, type, ψ_ε, stretching rate and rate rule), whose
// samples the detector carried on.
int64_t DetectionFirstRow(const Hdf5File& file, const std::vector<dem::StageRecord>& stages,
                          size_t index);

// The mean of paths on a common strain grid, with the half-width of the
// 95 % interval of the mean over the paths (Student t) at each point.
struct MeanPath {
  StagePath mean;
  std::vector<double> psi_sigma_band_deg, log_p_band, log_volume_band;
  int paths = 0;
};
// The grid runs 0, step, 2 step, ... over the common strain range (up to the
// shortest path's end); each path is interpolated linearly in strain.
MeanPath AveragePaths(const std::vector<StagePath>& paths, double step);
// The paths' output interval: the median strain between their rows (NaN
// when none).
double RowSpacing(const std::vector<StagePath>& paths);

// The detector run along a mean path as in the DEM run: every point added,
// extension windows tracked (the last that held above the floor is kept),
// the last window evaluated; the result reported is the last window, or
// the last that held before it when it does not (dem::RecordStage).
struct MeanPathDetection {
  dem::AsymptoteDetector::Result result;
  bool held_before_end = false;
  // The mean over the window's points of the bands' half-widths (NaN
  // without a window).
  double psi_sigma_band_deg = 0, log_volume_band = 0;
};
MeanPathDetection DetectOnMeanPath(const MeanPath& path, const dem::AsymptoteCriterion& criterion);

// One replicate's record of a detector-carrying stage, and its path.
struct ReplicateStage {
  dem::StageRecord record;
  StagePath path;
};
// The stage record of the replicates' mean path (two replicates or more,
// each with an asymptote record): the criterion of the stage sampled at
// the output interval; status from the detector, vetoed as in the DEM run
// (invalid above 10 % overlap, a gas below the floor or when every
// replicate was one and the mean did not hold); coordination, inertial
// numbers the mean and the overlap the largest of the replicates' states;
// the union of their validity flags; the stop reason "ensemble mean of N
// replicates: ..." with the bands over the window.
dem::StageRecord EnsembleStageRecord(const std::vector<ReplicateStage>& replicates);

}  // namespace granasym::study
