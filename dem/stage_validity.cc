#include "dem/stage_validity.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "dem/run_record_names.h"

namespace granasym::dem {

bool IsGas(double mean_stress_kpa, double mechanical_coordination, const ValidityLimits& limits) {
  return !(mean_stress_kpa >= limits.gas_mean_stress_kpa) ||
         !(mechanical_coordination >= limits.gas_mechanical_coordination);
}

RowState RowState::Mean(const TimeSeries& series, int64_t first, int64_t last) {
  GRANASYM_CHECK(first >= 0 && first <= last && last < static_cast<int64_t>(series.rows()))
      << "rows " << first << " .. " << last << " of " << series.rows();
  using namespace record;
  const auto& p = series.Values(kColumnMeanStress);
  const auto& e = series.Values(kColumnVoidRatio);
  const auto& z = series.Values(kColumnCoordination);
  const auto& zm = series.Values(kColumnMechanicalCoordination);
  const auto& i_min = series.Values(kColumnInertialNumberDmin);
  const auto& i_max = series.Values(kColumnInertialNumberDmax);
  const auto& overlap = series.Values(kColumnOverlapMax);
  RowState state;
  const double n = static_cast<double>(last - first + 1);
  for (int64_t k = first; k <= last; ++k) {
    state.mean_stress_kpa += p[k] / n;
    state.void_ratio += e[k] / n;
    state.coordination += z[k] / n;
    state.mechanical_coordination += zm[k] / n;
    state.inertial_number_dmin += i_min[k] / n;
    state.inertial_number_dmax += i_max[k] / n;
    state.max_relative_overlap = std::max(state.max_relative_overlap, overlap[k]);
  }
  return state;
}

bool StageValidity::Has(ValidityFlag flag) const {
  return std::find(flags.begin(), flags.end(), flag) != flags.end();
}

std::string StageValidity::FlagNames() const {
  if (flags.empty()) return "none";
  std::string names;
  for (ValidityFlag flag : flags)
    names += (names.empty() ? "" : ", ") + std::string(ToString(flag));
  return names;
}

std::string StageValidity::OneLine() const {
  return fmt::format(
      "max relative overlap {:.3g}, max I(d_max) {:.3g}, min mechanical coordination {:.3g}, "
      "final p {:.4g} kPa; flags: {}",
      max_relative_overlap, max_inertial_number_dmax, min_mechanical_coordination,
      final_mean_stress_kpa, FlagNames());
}

StageValidity StageValidity::FromRows(const TimeSeries& series, int64_t first_row, int64_t last_row,
                                      const RowState& state, const ValidityLimits& limits) {
  GRANASYM_CHECK(first_row >= 0 && first_row <= last_row &&
                 last_row < static_cast<int64_t>(series.rows()))
      << "rows " << first_row << " .. " << last_row << " of " << series.rows();
  using namespace record;
  const auto& p = series.Values(kColumnMeanStress);
  const auto& zm = series.Values(kColumnMechanicalCoordination);
  const auto& i_max = series.Values(kColumnInertialNumberDmax);
  const auto& overlap = series.Values(kColumnOverlapMax);
  StageValidity v;
  v.min_mechanical_coordination = zm[first_row];
  for (int64_t k = first_row; k <= last_row; ++k) {
    v.max_relative_overlap = std::max(v.max_relative_overlap, overlap[k]);
    v.min_mechanical_coordination = std::min(v.min_mechanical_coordination, zm[k]);
    if (!IsGas(p[k], zm[k], limits)) {
      v.max_inertial_number_dmax = std::max(v.max_inertial_number_dmax, i_max[k]);
    }
  }
  v.final_mean_stress_kpa = p[last_row];
  if (v.max_relative_overlap > limits.overlap_warning) {
    v.flags.push_back(ValidityFlag::kOverlapAbove2Pct);
  }
  if (v.max_relative_overlap > limits.overlap_unreliable) {
    v.flags.push_back(ValidityFlag::kOverlapAbove10Pct);
  }
  if (!(state.inertial_number_dmax <= limits.inertial_number)) {
    v.flags.push_back(ValidityFlag::kRateAffected);
  }
  if (IsGas(state.mean_stress_kpa, state.mechanical_coordination, limits)) {
    v.flags.push_back(ValidityFlag::kGas);
  }
  return v;
}

}  // namespace granasym::dem
