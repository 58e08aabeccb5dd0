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
//
// Where the replicates are aligned on that axis depends on how the stage
// ends. A stage that stops when its own detector holds (`stop.asymptote =
// true`: isochoric ψ_ε = 90°, drained triaxial stages) ends each replicate
// at its own strain, the end of its first stationary window; aligned at the
// stage starts, the common range would end at the first replicate's stop,
// while the others are still in their transient. Such stages are aligned at
// their ENDS: the axis is the strain remaining to the stage end, the common
// range is counted back from the end (down to the shortest replicate), and
// the mean path's last window averages the replicates' stationary states.
// Every other stage follows a prescribed path (compression to a target p,
// extension to a strain norm or the floor, the NCL), on which the same
// strain from the stage start is the same point of the path: those are
// aligned at their STARTS.
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

// Whether stage `index` of a result stops when its own detector holds: its
// `stop.asymptote` in the canonical scene of the result's provenance; where
// that is not recorded, whether its stop reason says that the asymptotic
// state was detected.
bool StopsAtAsymptote(const Hdf5File& file, const std::vector<dem::StageRecord>& stages,
                      size_t index);

// Where paths are aligned on the common strain axis (see above).
enum class PathAlignment {
  kStageStarts,  // at the same strain from the stage start (prescribed paths)
  kStageEnds,    // at the same strain before the stage end (stops at the asymptote)
};

// The mean of paths on a common strain grid, with the half-width of the
// 95 % interval of the mean over the paths (Student t) at each point.
struct MeanPath {
  StagePath mean;
  std::vector<double> psi_sigma_band_deg, log_p_band, log_volume_band;
  int paths = 0;
  PathAlignment alignment = PathAlignment::kStageStarts;
};
// The mean path's strain runs 0, step, 2 step, ... over the common range,
// the shortest path's length. At the stage starts, its point at strain s is
// each path's at s; at the stage ends, each path's at the same strain before
// its end (the last point: every path's end). Each path is interpolated
// linearly in strain; ε_a, ε_r and time count from the mean path's first
// point, as a path's from its first row.
MeanPath AveragePaths(const std::vector<StagePath>& paths, double step,
                      PathAlignment alignment = PathAlignment::kStageStarts);
// The paths' output interval: the median strain between their rows (NaN
// when none).
double RowSpacing(const std::vector<StagePath>& paths);

// The detector run along a mean path as in the DEM run: every point added,
// extension windows tracked (the last that held above the floor is kept),
// the last window evaluated; the result reported is the last window, or
// the last that held before it when it does not (dem::RecordStage).
struct MeanPathDetection {
  dem::AsymptoteDetector::Result result;
  dem::AsymptoteDetector::Result end;  // the last window (result, unless held_before_end)
  bool held_before_end = false;
  // The mean over the window's points of the bands' half-widths (NaN
  // without a window).
  double psi_sigma_band_deg = 0, log_volume_band = 0;
};
MeanPathDetection DetectOnMeanPath(const MeanPath& path, const dem::AsymptoteCriterion& criterion);

// One replicate's record of a detector-carrying stage, its path, and
// whether the stage stops at its asymptote (StopsAtAsymptote).
struct ReplicateStage {
  dem::StageRecord record;
  StagePath path;
  bool stops_at_asymptote = false;
};
// The stage record of the replicates' mean path (two replicates or more,
// each with an asymptote record): aligned at the stage ends where every
// replicate's stage stops at its asymptote, else at the stage starts; the
// criterion of the stage sampled at the output interval; status from the
// detector, vetoed as in the DEM run (dem::RecordStage: invalid above 10 %
// overlap; an extension state that held above the floor before the end
// keeps its detection and says where the path left the valid range; else a
// gas below the floor, or when every replicate was one and the mean did not
// hold); coordination, inertial numbers the mean and the overlap the
// largest of the replicates' states; the union of their validity flags; the
// stop reason "ensemble mean of N replicates: ..." with the alignment and
// the bands over the window.
dem::StageRecord EnsembleStageRecord(const std::vector<ReplicateStage>& replicates);

}  // namespace granasym::study
