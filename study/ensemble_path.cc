#include "study/ensemble_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "common/statistics.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"
#include "dem/stage_end.h"
#include "dem/stage_validity.h"
#include "study/state_table.h"

namespace granasym::study {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The fields of a path that are averaged, with the band kept for some;
// those that count from the path's first row count from the mean path's.
struct Field {
  std::vector<double> StagePath::*values;
  std::vector<double> MeanPath::*band;  // nullptr: no band
  bool from_first;
};
constexpr Field kFields[] = {
    {&StagePath::psi_sigma_deg, &MeanPath::psi_sigma_band_deg, false},
    {&StagePath::log_p, &MeanPath::log_p_band, false},
    {&StagePath::log_volume, &MeanPath::log_volume_band, false},
    {&StagePath::eps_a, nullptr, true},
    {&StagePath::eps_r, nullptr, true},
    {&StagePath::time, nullptr, true},
};

constexpr char kAsymptoteDetectedReason[] = "asymptotic state detected";  // dem::AsymptoteStop

// The value of `key` in a canonical scene ("key = value" lines); empty when
// it has none.
std::string CanonicalValue(const std::string& canonical, const std::string& key) {
  std::istringstream lines(canonical);
  const std::string prefix = key + " = ";
  for (std::string line; std::getline(lines, line);) {
    if (line.compare(0, prefix.size(), prefix) == 0) return line.substr(prefix.size());
  }
  return {};
}

// Whether two stage groups of a result hold the same attribute (both
// without it, or with equal values).
bool SameAttribute(const Hdf5File& file, const std::string& a, const std::string& b,
                   const char* name, bool text) {
  const bool has_a = file.HasAttribute(a, name), has_b = file.HasAttribute(b, name);
  if (has_a != has_b || !has_a) return has_a == has_b;
  return text ? file.ReadStringAttribute(a, name) == file.ReadStringAttribute(b, name)
              : file.ReadDoubleAttribute(a, name) == file.ReadDoubleAttribute(b, name);
}

// Stage `index` continues the path of the stage before it with the same
// criterion (dem::Stage::ContinuesDetection, from the records: only
// strain-path stages, which record ψ_ε, continue one).
bool ContinuesPrevious(const Hdf5File& file, const std::vector<dem::StageRecord>& stages,
                       size_t index) {
  const dem::StageRecord &previous = stages[index - 1], &stage = stages[index];
  if (!previous.asymptote || !stage.asymptote || previous.type != stage.type ||
      previous.asymptote_criterion != stage.asymptote_criterion) {
    return false;
  }
  namespace r = dem::record;
  const std::string a = dem::StageGroup(index - 1), b = dem::StageGroup(index);
  if (!file.HasAttribute(b, r::kStagePsiEpsilonDeg)) return false;
  for (const char* name : {r::kStagePsiEpsilonDeg, r::kStageStretchingRate,
                           r::kStageRateInertialNumber, r::kStageRateMinMeanStressKpa}) {
    if (!SameAttribute(file, a, b, name, false)) return false;
  }
  return SameAttribute(file, a, b, r::kStageRateRule, true) &&
         SameAttribute(file, a, b, r::kStageRateDiameter, true);
}

// The state at the end of a mean path without a window (the DEM run's
// stage end): its last point (NaN when it has none), ψ_ε the replicates' mean.
void SetEndState(const StagePath& path, const std::vector<ReplicateStage>& replicates,
                 dem::AsymptoteRecord* a) {
  const bool any = !path.strain.empty();
  a->mean_stress_kpa = any ? std::exp(path.log_p.back()) : kNaN;
  a->void_ratio = any ? std::expm1(path.log_volume.back()) : kNaN;
  a->psi_sigma_deg = any ? path.psi_sigma_deg.back() : kNaN;
  a->q_over_p = StressRatio(a->psi_sigma_deg * kDegree);
  std::vector<double> psi_epsilon;
  for (const ReplicateStage& r : replicates) {
    psi_epsilon.push_back(r.record.asymptote->psi_epsilon_deg);
  }
  a->psi_epsilon_deg = Mean(psi_epsilon);
}

// The replicates' states over their own windows: coordination and inertial
// numbers averaged, the largest overlap.
void SetRowMeasures(const std::vector<ReplicateStage>& replicates, dem::AsymptoteRecord* a) {
  using R = dem::AsymptoteRecord;
  for (double R::*member : {&R::coordination, &R::mechanical_coordination, &R::inertial_number_dmin,
                            &R::inertial_number_dmax, &R::max_relative_overlap}) {
    std::vector<double> values;
    for (const ReplicateStage& r : replicates) values.push_back((*r.record.asymptote).*member);
    a->*member = member == &R::max_relative_overlap
                     ? *std::max_element(values.begin(), values.end())
                     : Mean(values);
  }
}

// The status of the mean path, vetoed as dem::RecordStage vetoes a run's
// (SPEC §8.3): unreliable overlaps make it invalid; a window that held on a
// gas (other than an extension window, whose floor is its criterion's) is
// none; without one it is a gas below the floor or where every replicate
// was a gas (or liquefied).
dem::AsymptoteStatus MeanPathStatus(const std::vector<ReplicateStage>& replicates,
                                    const dem::AsymptoteDetector::Result& result,
                                    const dem::AsymptoteRecord& a) {
  if (a.max_relative_overlap > dem::kValidityLimits.overlap_unreliable) {
    return dem::AsymptoteStatus::kInvalid;
  }
  if (result.detected()) {
    const bool gas = a.path_kind != dem::PathKind::kExtension &&
                     dem::IsGas(a.mean_stress_kpa, a.mechanical_coordination);
    return gas ? dem::AsymptoteStatus::kGas : dem::AsymptoteStatus::kDetected;
  }
  bool every_gas = true;
  for (const ReplicateStage& r : replicates) {
    every_gas = every_gas && r.record.asymptote->status == dem::AsymptoteStatus::kGas;
  }
  return every_gas || result.below_floor ? dem::AsymptoteStatus::kGas : result.status;
}

// The stop reason of the mean path: how many replicates, the bands over the
// window, what the detector found.
std::string EnsembleMessage(const std::vector<ReplicateStage>& replicates, const MeanPath& mean,
                            const MeanPathDetection& detection, const dem::AsymptoteRecord& a) {
  const dem::AsymptoteDetector::Result& w = detection.result;
  const double range = mean.mean.strain.empty() ? 0.0 : mean.mean.strain.back();
  const bool at_ends = mean.alignment == PathAlignment::kStageEnds;
  std::string text = fmt::format(
      "ensemble mean of {} replicates, aligned at the stage {}: their common range of {:.3g} of "
      "strain at {:.3g}",
      replicates.size(),
      at_ends ? "ends (the stage stops at its asymptote)" : "starts (a prescribed path)", range,
      a.criterion.sample_strain);
  if (!(w.window_strain > 0)) return text + "; no full window";
  text += fmt::format(
      "; 95 % band over the window: psi_sigma +-{:.3g} deg, ln(1+e) +-{:.3g}; {} (p {:.4g} kPa, "
      "psi_sigma {:.3f} deg over {:.3g} of strain and {:.3g} of ln p)",
      detection.psi_sigma_band_deg, detection.log_volume_band,
      w.detected() ? "the criterion held" : "the last window", a.mean_stress_kpa, a.psi_sigma_deg,
      w.window_strain, w.window_lnp);
  if (detection.held_before_end) {
    // As dem::RecordStage says it of a run's path.
    const double p_end = std::exp(mean.mean.log_p.back());
    text += fmt::format(
        "; the extension asymptote last held over p {:.4g}-{:.4g} kPa up to {}, then {} (p {:.4g} "
        "kPa at the end)",
        w.p_min_kpa, w.p_max_kpa,
        at_ends ? fmt::format("{:.4g} of strain before the stage end", range - w.window_end_strain)
                : fmt::format("stage strain {:.4g}", w.window_end_strain),
        dem::AfterLastHeld(detection.end, p_end, a.criterion.floor_kpa), p_end);
  }
  return text;
}

// The union of the replicates' validity flags, in the flags' order.
std::vector<dem::ValidityFlag> FlagUnion(const std::vector<ReplicateStage>& replicates) {
  std::set<dem::ValidityFlag> flags;
  for (const ReplicateStage& r : replicates) {
    flags.insert(r.record.validity.flags.begin(), r.record.validity.flags.end());
  }
  return {flags.begin(), flags.end()};
}

}  // namespace

StagePath ReadStagePath(const TimeSeries& series, int64_t first_row, int64_t last_row) {
  namespace r = dem::record;
  StagePath path;
  const std::vector<double>& p = series.Values(r::kColumnMeanStress);
  const std::vector<double>& e = series.Values(r::kColumnVoidRatio);
  const std::vector<double>& psi = series.Values(r::kColumnPsiSigma);
  const std::vector<double>& eps_a = series.Values(r::kColumnAxialStrain);
  const std::vector<double>& eps_r = series.Values(r::kColumnRadialStrain);
  const std::vector<double>& time = series.Values(r::kColumnTime);
  const int64_t first = std::max<int64_t>(first_row, 0);
  const int64_t last = std::min<int64_t>(last_row, static_cast<int64_t>(series.rows()) - 1);
  double strain = 0;
  for (int64_t row = first; row <= last; ++row) {
    const size_t k = static_cast<size_t>(row), k0 = static_cast<size_t>(first);
    if (row > first) {
      const double da = eps_a[k] - eps_a[k - 1], dr = eps_r[k] - eps_r[k - 1];
      strain += std::sqrt(da * da + 2.0 * dr * dr);
    }
    path.strain.push_back(strain);
    path.psi_sigma_deg.push_back(psi[k]);
    path.log_p.push_back(p[k] > 0 ? std::log(p[k]) : kNaN);
    path.log_volume.push_back(std::log1p(e[k]));
    path.eps_a.push_back(eps_a[k] - eps_a[k0]);
    path.eps_r.push_back(eps_r[k] - eps_r[k0]);
    path.time.push_back(time[k] - time[k0]);
  }
  return path;
}

int64_t DetectionFirstRow(const Hdf5File& file, const std::vector<dem::StageRecord>& stages,
                          size_t index) {
  size_t k = index;
  while (k > 0 && ContinuesPrevious(file, stages, k)) --k;
  return stages[k].first_row;
}

bool StopsAtAsymptote(const Hdf5File& file, const std::vector<dem::StageRecord>& stages,
                      size_t index) {
  namespace r = dem::record;
  const std::string scene = std::string(r::kProvenance) + "/" + r::kSceneCanonical;
  if (file.Exists(scene)) {
    const std::string canonical = file.ReadString(scene);
    const std::string prefix = fmt::format("stage[{}].", index);
    const std::string stop = CanonicalValue(canonical, prefix + "stop.asymptote");
    // The scene's stage `index` is the record's (a run records its scene's stages).
    if (!stop.empty() &&
        CanonicalValue(canonical, prefix + "name") == fmt::format("\"{}\"", stages[index].name)) {
      return stop == "true";
    }
  }
  return stages[index].stop_reason.rfind(kAsymptoteDetectedReason, 0) == 0;
}

MeanPath AveragePaths(const std::vector<StagePath>& paths, double step, PathAlignment alignment) {
  MeanPath out;
  out.paths = static_cast<int>(paths.size());
  out.alignment = alignment;
  double range = std::numeric_limits<double>::infinity();
  for (const StagePath& path : paths) {
    if (path.strain.empty()) return out;
    range = std::min(range, path.strain.back());
  }
  if (paths.empty() || !(step > 0)) return out;
  const size_t points = static_cast<size_t>(std::floor(range / step * (1 + 1e-12))) + 1;
  const double span = static_cast<double>(points - 1) * step;
  // Path j's strain at the mean path's strain s.
  auto at = [&](size_t j, double s) {
    return alignment == PathAlignment::kStageEnds ? paths[j].strain.back() - (span - s) : s;
  };
  std::vector<double> values(paths.size());
  for (const Field& field : kFields) {
    std::vector<double> first(paths.size(), 0.0);
    for (size_t j = 0; j < paths.size() && field.from_first; ++j) {
      first[j] = Smoothed(paths[j].strain, paths[j].*field.values, at(j, 0.0), 0.0);
    }
    for (size_t k = 0; k < points; ++k) {
      const double strain = static_cast<double>(k) * step;
      for (size_t j = 0; j < paths.size(); ++j) {
        values[j] =
            Smoothed(paths[j].strain, paths[j].*field.values, at(j, strain), 0.0) - first[j];
      }
      const Interval interval = MeanInterval95(values);
      (out.mean.*field.values).push_back(interval.mean);
      if (field.band) (out.*field.band).push_back(interval.half_width);
    }
  }
  for (size_t k = 0; k < points; ++k) out.mean.strain.push_back(static_cast<double>(k) * step);
  return out;
}

double RowSpacing(const std::vector<StagePath>& paths) {
  std::vector<double> steps;
  for (const StagePath& path : paths) {
    for (size_t k = 1; k < path.strain.size(); ++k) {
      if (path.strain[k] > path.strain[k - 1]) steps.push_back(path.strain[k] - path.strain[k - 1]);
    }
  }
  if (steps.empty()) return kNaN;
  const auto middle = steps.begin() + static_cast<long>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

MeanPathDetection DetectOnMeanPath(const MeanPath& path, const dem::AsymptoteCriterion& criterion) {
  const StagePath& m = path.mean;
  dem::AsymptoteDetector detector(criterion);
  for (size_t k = 0; k < m.strain.size(); ++k) {
    detector.Add({m.strain[k], m.psi_sigma_deg[k] * kDegree, m.log_p[k], m.log_volume[k],
                  m.eps_a[k], m.eps_r[k], m.time[k]});
    detector.Track();
  }
  MeanPathDetection detection;
  detection.end = detector.Evaluate();
  detection.held_before_end = !detection.end.detected() && detector.last_held().has_value();
  detection.result = detection.held_before_end ? *detector.last_held() : detection.end;
  const dem::AsymptoteDetector::Result& w = detection.result;
  std::vector<double> psi_band, volume_band;
  for (size_t k = 0; k < m.strain.size() && w.window_strain > 0; ++k) {
    const double before_end = w.window_end_strain - m.strain[k];
    if (before_end < -1e-9 || before_end > w.window_strain * (1 + 1e-9)) continue;
    psi_band.push_back(path.psi_sigma_band_deg[k]);
    volume_band.push_back(path.log_volume_band[k]);
  }
  detection.psi_sigma_band_deg = Mean(psi_band);
  detection.log_volume_band = Mean(volume_band);
  return detection;
}

dem::StageRecord EnsembleStageRecord(const std::vector<ReplicateStage>& replicates) {
  GRANASYM_CHECK(replicates.size() >= 2) << "an ensemble needs two replicates";
  for (const ReplicateStage& r : replicates) {
    GRANASYM_CHECK(r.record.asymptote) << "stage " << r.record.name << " has no detector";
  }
  std::vector<StagePath> paths;
  bool at_ends = true;
  for (const ReplicateStage& r : replicates) {
    paths.push_back(r.path);
    at_ends = at_ends && r.stops_at_asymptote;
  }
  const double step = RowSpacing(paths);
  dem::AsymptoteCriterion criterion = replicates.front().record.asymptote->criterion;
  if (step > 0) criterion.sample_strain = step;
  const MeanPath mean =
      AveragePaths(paths, step, at_ends ? PathAlignment::kStageEnds : PathAlignment::kStageStarts);
  const MeanPathDetection detection = DetectOnMeanPath(mean, criterion);

  dem::AsymptoteRecord a;
  a.path_kind = criterion.kind;
  a.criterion = criterion;
  a.SetWindow(detection.result);
  a.before_end = detection.held_before_end;
  SetRowMeasures(replicates, &a);
  if (!(detection.result.window_strain > 0)) SetEndState(mean.mean, replicates, &a);
  a.status = MeanPathStatus(replicates, detection.result, a);
  a.detected = a.status == dem::AsymptoteStatus::kDetected;

  dem::StageRecord record;
  record.name = replicates.front().record.name;
  record.type = replicates.front().record.type;
  record.last_row = static_cast<int64_t>(mean.mean.strain.size()) - 1;
  record.validity.flags = FlagUnion(replicates);
  record.stop_reason = EnsembleMessage(replicates, mean, detection, a);
  record.asymptote_criterion = criterion.Describe();
  record.asymptote = a;
  return record;
}

}  // namespace granasym::study
