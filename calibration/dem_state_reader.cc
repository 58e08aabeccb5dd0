// DEM result files → asymptotic states, using the DEM's own asymptote detection.
#include "calibration/dem_state_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/run_record_names.h"

namespace granasym::calibration {

namespace record = ::granasym::dem::record;

bool DemReadOptions::IsValid(std::string* why) const {
  if (!(ncl_min_p_kpa >= 0)) {
    *why = fmt::format("ncl_min_p_kpa = {} must be >= 0", ncl_min_p_kpa);
    return false;
  }
  if (max_line_points < 2) {
    *why = fmt::format("max_line_points = {} must be >= 2", max_line_points);
    return false;
  }
  for (size_t k = 0; k < asbs_ln_1_plus_e.size(); ++k) {
    const double v = asbs_ln_1_plus_e[k];
    if (!(std::isfinite(v) && v > 0)) {
      *why = fmt::format(
          "asbs_ln_1_plus_e[{}] = {} must be finite and > 0 (ln(1+e) of a void "
          "ratio e > 0)",
          k, v);
      return false;
    }
  }
  if (!(std::isfinite(asbs_min_abs_slope) && asbs_min_abs_slope > 0)) {
    *why = fmt::format("asbs_min_abs_slope = {} must be finite and > 0", asbs_min_abs_slope);
    return false;
  }
  if (!(std::isfinite(asbs_max_ln_p_extrapolation) && asbs_max_ln_p_extrapolation > 0)) {
    *why = fmt::format("asbs_max_ln_p_extrapolation = {} must be finite and > 0",
                       asbs_max_ln_p_extrapolation);
    return false;
  }
  if (!(std::isfinite(unloading_weight) && unloading_weight >= 0)) {
    *why = fmt::format("unloading_weight = {} must be finite and >= 0 (0: read, not fitted)",
                       unloading_weight);
    return false;
  }
  return ValidReaderSettings(kind_tolerance_deg, psi_sigma_uncertainty_deg, ln_volume_uncertainty,
                             weight, why);
}

namespace {

// Rows [first, last] whose p moves monotonically in `direction` (+1 rising,
// −1 falling) and passes `filter`, thinned to `max_points` evenly spaced in ln p.
std::vector<size_t> LineRows(const std::vector<double>& p, int64_t first, int64_t last,
                             int direction, double min_p, int max_points) {
  std::vector<size_t> candidates;
  double extreme = direction > 0 ? 0.0 : std::numeric_limits<double>::infinity();
  for (int64_t r = first; r <= last && r < static_cast<int64_t>(p.size()); ++r) {
    if (r < 0) continue;
    const double value = p[static_cast<size_t>(r)];
    if (!(value > 0) || value < min_p) continue;
    if (direction > 0 ? value > extreme : value < extreme) {
      candidates.push_back(static_cast<size_t>(r));
      extreme = value;
    }
  }
  if (candidates.size() <= static_cast<size_t>(max_points)) return candidates;
  std::vector<size_t> rows;
  const double lo = std::log(p[candidates.front()]);
  const double hi = std::log(p[candidates.back()]);
  size_t next = 0;
  for (int k = 0; k < max_points; ++k) {
    const double target = lo + (hi - lo) * k / (max_points - 1);
    while (next + 1 < candidates.size() && std::abs(std::log(p[candidates[next + 1]]) - target) <=
                                               std::abs(std::log(p[candidates[next]]) - target)) {
      ++next;
    }
    if (rows.empty() || rows.back() != candidates[next]) rows.push_back(candidates[next]);
  }
  return rows;
}

// ASBS cross-section points on the asymptotic line of a stage whose detected
// asymptote is `asymptote` (see the header); warnings for what is skipped.
void AddAsbsPoints(const Hdf5File& file, const std::string& group, const std::string& where,
                   const AsymptoticStatePoint& asymptote, const DemReadOptions& options,
                   StateDataset* dataset) {
  const char* kSlope = record::kAsymptoteDln1peDlnp;
  if (!file.HasAttribute(group, kSlope)) {
    dataset->warnings.push_back(fmt::format(
        "{}: no {} attribute (slope of the asymptotic line); no ASBS points taken", where, kSlope));
    return;
  }
  const double slope = file.ReadDoubleAttribute(group, kSlope);
  if (!(std::isfinite(slope) && std::abs(slope) >= options.asbs_min_abs_slope)) {
    dataset->warnings.push_back(fmt::format(
        "{}: {} = {:.6g} is not usable (not finite or |slope| < {:g}: e does not change along "
        "the asymptotic line, as on an isochoric path such as psi_epsilon = 90 deg, so it cannot "
        "be followed to another e); no ASBS points taken",
        where, kSlope, slope, options.asbs_min_abs_slope));
    return;
  }
  const double ln_v_a = std::log1p(asymptote.void_ratio);
  const double ln_p_a = std::log(asymptote.mean_stress);
  for (const double target : options.asbs_ln_1_plus_e) {
    const double d_ln_p = (target - ln_v_a) / slope;
    if (!(std::abs(d_ln_p) <= options.asbs_max_ln_p_extrapolation)) {
      dataset->warnings.push_back(fmt::format(
          "{}: ASBS point at ln(1+e) = {:g} skipped: it lies {:.3g} in ln p from the asymptote "
          "(ln(1+e) = {:.6g}, {} = {:.6g}), beyond the extrapolation limit |d ln p| <= {:g}",
          where, target, d_ln_p, ln_v_a, kSlope, slope, options.asbs_max_ln_p_extrapolation));
      continue;
    }
    AsymptoticStatePoint point = asymptote;
    point.kind = StateKind::kAsbs;
    point.mean_stress = std::exp(ln_p_a + d_ln_p);
    point.void_ratio = std::expm1(target);
    point.source = fmt::format("{} asbs ln(1+e) = {:g}", where, target);
    dataset->points.push_back(point);
  }
}

}  // namespace

StateDataset ReadStatesDem(const std::string& path, const std::string& name,
                           const DemReadOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  const Hdf5File file = Hdf5File::OpenRead(path);
  const std::string series = record::kSeries;
  const std::string p_column = series + "/" + record::kColumnMeanStress;
  const std::string e_column = series + "/" + record::kColumnVoidRatio;
  const std::string psi_column = series + "/" + record::kColumnPsiSigma;
  for (const std::string& required :
       {std::string(record::kStages), p_column, e_column, psi_column}) {
    if (!file.Exists(required)) {
      throw InputError(fmt::format("{}: not a granasym DEM result file (no {})", path, required));
    }
  }
  StateDataset dataset;
  dataset.name = name;
  dataset.origin = path;
  // An interrupted run (or one still running) writes partial results under
  // the final name: its stages so far, not the run's states.
  const std::string summary = record::kSummary;
  if (file.HasAttribute(summary, record::kTermination)) {
    const std::string termination = file.ReadStringAttribute(summary, record::kTermination);
    const std::string message = file.HasAttribute(summary, record::kMessage)
                                    ? file.ReadStringAttribute(summary, record::kMessage)
                                    : "";
    if (termination == record::kTerminationInterrupted ||
        termination == record::kTerminationNotRun) {
      throw InputError(fmt::format(
          "{}: a partial result, not calibration data: the run's termination is '{}' ({}); "
          "finish the run (`granasym dem run SCENE --out {} --restart`) and calibrate on its "
          "final result (`granasym export {} --info` tells)",
          path, termination, message, path, path));
    }
    if (termination == record::kTerminationFailed) {
      dataset.warnings.push_back(fmt::format(
          "{}: the run failed ({}): only the stages completed before are used", path, message));
    }
  }
  const std::vector<double> p = file.ReadDoubles(p_column);
  const std::vector<double> e = file.ReadDoubles(e_column);
  const std::vector<double> psi_sigma = file.ReadDoubles(psi_column);

  const double tolerance = options.kind_tolerance_deg * kDegree;
  for (const std::string& stage : file.List(record::kStages)) {
    const std::string group = std::string(record::kStages) + "/" + stage;
    const std::string stage_name = file.ReadStringAttribute(group, record::kStageName);
    const std::string where = fmt::format("{}:{} ({})", path, group, stage_name);
    if (file.HasAttribute(group, record::kStageFailed) &&
        file.ReadIntAttribute(group, record::kStageFailed) != 0) {
      dataset.warnings.push_back(where + ": the run failed in this stage; stage skipped");
      continue;
    }
    const bool ran_detector = file.HasAttribute(group, record::kAsymptoteDetected);
    const bool strain_path = file.HasAttribute(group, record::kStagePsiEpsilonDeg);
    if (!strain_path && !ran_detector) continue;  // e.g. a rest stage
    // A stress-controlled stage (drained triaxial) has the ψ_ε of its
    // asymptote, measured from the strain increments over the window.
    const double psi_epsilon =
        file.ReadDoubleAttribute(
            group, strain_path ? record::kStagePsiEpsilonDeg : record::kAsymptotePsiEpsilonDeg) *
        kDegree;
    AsymptoticStatePoint base;
    base.psi_epsilon = psi_epsilon;
    base.weight = options.weight;
    base.psi_sigma_uncertainty = options.psi_sigma_uncertainty_deg * kDegree;
    base.ln_volume_uncertainty = options.ln_volume_uncertainty;
    if (ran_detector && file.ReadIntAttribute(group, record::kAsymptoteDetected) == 1) {
      AsymptoticStatePoint point = base;
      point.kind = KindFromStretching(psi_epsilon, tolerance);
      point.mean_stress = file.ReadDoubleAttribute(group, record::kAsymptoteMeanStressKpa);
      point.void_ratio = file.ReadDoubleAttribute(group, record::kAsymptoteVoidRatio);
      point.psi_sigma = file.ReadDoubleAttribute(group, record::kAsymptotePsiSigmaDeg) * kDegree;
      point.source = where;
      // The rate at the asymptote and the stage's validity flags, where recorded.
      if (file.HasAttribute(group, record::kAsymptoteInertialNumberDmax)) {
        point.inertial_number_dmin =
            file.ReadDoubleAttribute(group, record::kAsymptoteInertialNumberDmin);
        point.inertial_number_dmax =
            file.ReadDoubleAttribute(group, record::kAsymptoteInertialNumberDmax);
      }
      if (file.HasAttribute(group, record::kValidityFlags)) {
        point.flags = file.ReadStringAttribute(group, record::kValidityFlags);
        std::replace(point.flags.begin(), point.flags.end(), ',', ';');
        point.flags.erase(std::remove(point.flags.begin(), point.flags.end(), ' '),
                          point.flags.end());
      }
      if (point.kind == StateKind::kUnloading) {
        dataset.warnings.push_back(where + ": an asymptote at psi_epsilon = 180 deg is not used");
        continue;
      }
      dataset.points.push_back(point);
      if (!options.asbs_ln_1_plus_e.empty())
        AddAsbsPoints(file, group, where, point, options, &dataset);
      continue;
    }
    if (ran_detector) {
      dataset.warnings.push_back(
          fmt::format("{}: no asymptote detected (stop reason: {}); stage skipped", where,
                      file.HasAttribute(group, record::kStageStopReason)
                          ? file.ReadStringAttribute(group, record::kStageStopReason)
                          : "unknown"));
      continue;
    }
    if (!strain_path) continue;
    const StateKind kind = KindFromStretching(psi_epsilon, tolerance);
    if (kind != StateKind::kNcl && kind != StateKind::kUnloading) continue;
    const int64_t first = file.ReadIntAttribute(group, record::kStageFirstRow);
    const int64_t last = file.ReadIntAttribute(group, record::kStageLastRow);
    const int direction = kind == StateKind::kNcl ? +1 : -1;
    const double min_p = kind == StateKind::kNcl ? options.ncl_min_p_kpa : 0.0;
    const std::vector<size_t> rows =
        LineRows(p, first, last, direction, min_p, options.max_line_points);
    // The largest p before the stage: rows of a ψ_ε = 0 stage below it are
    // reloading (an unload–reload cycle), never NCL rows.
    double p_max_before = 0.0;
    for (int64_t r = 0; r < first && r < static_cast<int64_t>(p.size()); ++r) {
      if (p[static_cast<size_t>(r)] > p_max_before) p_max_before = p[static_cast<size_t>(r)];
    }
    // The branch starts where the stage does (the row before its first).
    const size_t start_row = static_cast<size_t>(std::max<int64_t>(0, first - 1));
    size_t ncl_rows = 0, reload_rows = 0;
    for (size_t r : rows) {
      AsymptoticStatePoint point = base;
      point.kind = kind;
      point.mean_stress = p[r];
      point.void_ratio = e[r];
      point.psi_sigma = psi_sigma[r] * kDegree;
      point.source = fmt::format("{} row {}", where, r);
      if (kind == StateKind::kNcl && p[r] < p_max_before) {
        point.kind = StateKind::kUnloading;
        point.source += " (reloading below the earlier largest p)";
        ++reload_rows;
      }
      if (point.kind == StateKind::kUnloading) {
        point.weight = options.unloading_weight;
        if (start_row < p.size() && r != start_row) {
          point.branch_start_p = p[start_row];
          point.branch_start_e = e[start_row];
        }
      } else {
        ++ncl_rows;
      }
      dataset.points.push_back(point);
    }
    if (kind == StateKind::kNcl && ncl_rows < 2 && reload_rows == 0) {
      dataset.warnings.push_back(
          fmt::format("{}: fewer than 2 rows with p >= {} kPa; no NCL points taken", where,
                      options.ncl_min_p_kpa));
    }
  }
  // NCL rows of a file's own loading outweigh its asymptotes quickly; say so.
  size_t line_rows = 0;
  for (const AsymptoticStatePoint& point : dataset.points) {
    line_rows += point.kind == StateKind::kNcl || point.kind == StateKind::kUnloading;
  }
  const size_t asymptotes = dataset.points.size() - line_rows;
  if (asymptotes > 0 && line_rows > 3 * asymptotes) {
    dataset.warnings.push_back(fmt::format(
        "{}: {} NCL/unloading rows against {} asymptotic states: the rows dominate the fit "
        "(lower max_line_points or the dataset's weight, or read a study's state table, "
        "which holds each state once)",
        path, line_rows, asymptotes));
  }
  if (dataset.points.empty()) {
    std::string reasons;
    for (const std::string& w : dataset.warnings) reasons += "; " + w;
    throw InputError(
        fmt::format("{}: no asymptotic states found (dataset '{}'){}", path, name, reasons));
  }
  dataset.Validate();
  return dataset;
}

}  // namespace granasym::calibration
