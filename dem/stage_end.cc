#include "dem/stage_end.h"

#include <fmt/format.h>

#include <cmath>

#include "common/state_measures.h"
#include "dem/run_record_names.h"
#include "dem/stage_validity.h"

namespace granasym::dem {
namespace {

// The first of the stage's rows [first, last] at or after `time` (the
// window's start); `last` when none.
int64_t FirstRowAfter(const TimeSeries& series, int64_t first, int64_t last, double time) {
  const auto& times = series.Values(record::kColumnTime);
  for (int64_t k = first; k <= last; ++k) {
    if (times[k] >= time) return k;
  }
  return last;
}

// The last of the stage's rows [first, last] at or before `time` (the
// window's end); `first` when none.
int64_t LastRowBefore(const TimeSeries& series, int64_t first, int64_t last, double time) {
  const auto& times = series.Values(record::kColumnTime);
  for (int64_t k = last; k >= first; --k) {
    if (times[k] <= time) return k;
  }
  return first;
}

// An extension state keeps the flags of its rows (coordination, inertial
// number) with their values, but they do not veto it (SPEC §8.3): a path
// towards the origin at the paper's rate is a dense flow whose network is
// thin. Only overlaps beyond the reliable do.
bool VetoedByRows(PathKind kind, double mean_stress_kpa, const RowState& state) {
  if (state.max_relative_overlap > kValidityLimits.overlap_unreliable) return true;
  return kind != PathKind::kExtension && IsGas(mean_stress_kpa, state.mechanical_coordination);
}

}  // namespace

std::optional<std::string> AsymptoteStop(const AsymptoteDetector::Result& result, PathKind kind,
                                         const TimeSeries& series, int64_t detector_first_row,
                                         int64_t stage_first_row) {
  const int64_t last_row = static_cast<int64_t>(series.rows()) - 1;
  bool valid = result.detected() && last_row >= stage_first_row;
  if (valid) {
    const RowState state = RowState::Mean(
        series, FirstRowAfter(series, detector_first_row, last_row, result.window_start_time),
        last_row);
    valid = !VetoedByRows(kind, result.mean_stress_kpa, state);
  }
  if (!valid) return std::nullopt;
  return fmt::format(
      "asymptotic state detected ({}: p {:.4g} kPa, psi_sigma {:.3f} deg over {:.3g} of "
      "strain and {:.3g} of ln p)",
      ToString(kind), result.mean_stress_kpa, result.psi_sigma / kDegree, result.window_strain,
      result.window_lnp);
}

std::string AfterLastHeld(const AsymptoteDetector::Result& end, double p_end_kpa,
                          double floor_kpa) {
  return end.below_floor || !(p_end_kpa >= floor_kpa)
             ? fmt::format("left the valid range p >= {:g} kPa", floor_kpa)
             : std::string("drifted");
}

StageRecord RecordStage(const Stage& stage, const TimeSeries& series, int64_t first_row,
                        const AsymptoteDetector& detector, int64_t detector_first_row,
                        const std::string& reason, bool failed) {
  StageRecord record;
  record.name = stage.name;
  record.type = stage.type();
  record.first_row = first_row;
  record.last_row = static_cast<int64_t>(series.rows()) - 1;
  record.stop_reason = reason;
  record.failed = failed;
  const bool has_rows = record.last_row >= record.first_row;
  const bool detect = stage.detect_asymptote;
  const AsymptoteDetector::Result end_result =
      detect ? detector.Evaluate() : AsymptoteDetector::Result{};
  // An extension stage reports the last window that held above the floor,
  // even when its path went on below it (SPEC §8.4).
  const bool held_before = detect && !end_result.detected() && detector.last_held().has_value();
  const AsymptoteDetector::Result& result = held_before ? *detector.last_held() : end_result;
  // The state: the window's rows when a full window exists, else the last row.
  const bool window = detect && result.window_strain > 0;
  RowState state;
  if (has_rows) {
    const int64_t state_row = window ? FirstRowAfter(series, detector_first_row, record.last_row,
                                                     result.window_start_time)
                                     : record.last_row;
    const int64_t state_last =
        held_before ? LastRowBefore(series, state_row, record.last_row, result.window_end_time)
                    : record.last_row;
    state = RowState::Mean(series, state_row, state_last);
    record.validity = StageValidity::FromRows(series, record.first_row, record.last_row, state);
  }
  if (!detect) return record;
  AsymptoteRecord a;
  a.path_kind = stage.asymptote.kind;
  a.criterion = stage.asymptote;
  a.SetWindow(result);
  if (!window && has_rows) {
    a.mean_stress_kpa = series.Last(record::kColumnMeanStress);
    a.void_ratio = series.Last(record::kColumnVoidRatio);
    a.psi_sigma_deg = series.Last(record::kColumnPsiSigma);
    a.psi_epsilon_deg = series.Last(record::kColumnPsiEpsilon);
    a.q_over_p = StressRatio(a.psi_sigma_deg * kDegree);
  }
  a.before_end = held_before;
  a.coordination = state.coordination;
  a.mechanical_coordination = state.mechanical_coordination;
  a.inertial_number_dmin = state.inertial_number_dmin;
  a.inertial_number_dmax = state.inertial_number_dmax;
  a.max_relative_overlap = state.max_relative_overlap;
  const ValidityLimits& limits = kValidityLimits;
  if (failed || !has_rows || state.max_relative_overlap > limits.overlap_unreliable) {
    a.status = AsymptoteStatus::kInvalid;
  } else if (result.detected() && !VetoedByRows(a.path_kind, state.mean_stress_kpa, state)) {
    a.status = AsymptoteStatus::kDetected;
  } else if (IsGas(state.mean_stress_kpa, state.mechanical_coordination, limits) ||
             result.below_floor) {
    a.status = AsymptoteStatus::kGas;
  } else {
    a.status = result.status;
  }
  a.detected = a.status == AsymptoteStatus::kDetected;
  if (result.detected() && !a.detected) {
    record.stop_reason += fmt::format("; not an asymptote: status {} ({})", ToString(a.status),
                                      EnumDescription(a.status));
  }
  if (held_before && a.detected) {
    const double p_end = series.Last(record::kColumnMeanStress);
    record.stop_reason += fmt::format(
        "; the extension asymptote last held over p {:.4g}-{:.4g} kPa up to stage strain {:.4g}, "
        "then {} (p {:.4g} kPa at the end)",
        result.p_min_kpa, result.p_max_kpa, result.window_end_strain,
        AfterLastHeld(end_result, p_end, stage.asymptote.floor_kpa), p_end);
  }
  record.asymptote = a;
  record.asymptote_criterion = stage.asymptote.Describe();
  return record;
}

std::vector<std::string> StageEndLines(const StageRecord& record, int64_t index, int64_t steps) {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("stage {} '{}' {} after {} steps: {}", index + 1, record.name,
                              record.failed ? "failed" : "done", steps, record.stop_reason));
  lines.push_back(fmt::format("  validity: {}", record.validity.OneLine()));
  if (record.asymptote) {
    const AsymptoteRecord& a = *record.asymptote;
    lines.push_back(fmt::format(
        "  asymptote ({}): {}; p {:.4g} kPa, e {:.4f}, psi_sigma {:.2f} deg, psi_epsilon {:.2f} "
        "deg over a window of {:.3g} strain and {:.3g} of ln p",
        ToString(a.path_kind), ToString(a.status), a.mean_stress_kpa, a.void_ratio, a.psi_sigma_deg,
        a.psi_epsilon_deg, a.window_strain, a.window_lnp));
  }
  return lines;
}

}  // namespace granasym::dem
