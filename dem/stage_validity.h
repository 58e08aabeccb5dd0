// Validity of the DEM states of a stage (SPEC §8.3, paper Sec. 3 and
// Fig. 8): the limits in one place, the state measured over output rows,
// and the per-stage record of what the rows showed.
//
// The limits:
//  - relative overlap u_N/(r_i + r_j): above 2 % the paper's limit of
//    accuracy is passed (a warning), above 10 % results are unreliable
//    (Fig. 8), at 25 % spheres interpenetrate so deeply that the linear law
//    no longer describes a contact (a quarter of the sum of radii: the centre
//    of the smaller sphere approaches the surface of a sphere of ratio 3:1)
//    and the run fails;
//  - inertial number I(d_max) above 1e-2: rate-affected (a warning; the
//    paper's ‖D‖ = 167 1/s gives I(d_max = 1 mm) = 1e-2 at p ≈ 1.5 MPa, so it
//    is set on most of the paper's own states: it says that the state must
//    be checked for rate independence, SPEC §8.2);
//  - a gas (or liquefied) state: mechanical coordination Z_m below 3, or
//    p below 0.5 kPa. A rigid frictional packing needs Z_m ≥ 4 (isostatic
//    limit d + 1 in 3D for μ → ∞); dynamic, flowing packings with μ = 0.5
//    stay a little below it (counted over all contacts), so 3 leaves room for the scatter of small
//    samples while still catching packings that have lost their load-bearing network (measured on
//    3000 spheres: Z_m ≈ 2–2.6 when the sample liquefies on an extension path, 3.4 on the critical
//    state at 30 kPa, 3.8 on the NCL at 200 kPa). The floor on p lies below the paper's smallest
//    state (OC samples unloaded to 1 kPa, Fig. 18);
//  - void ratio e ≤ 0: the cell is smaller than the solid volume; the run
//    fails;
//  - a mean-stress target that the stage moves away from for 0.3 of
//    accumulated strain (from its closest approach, counted once the sample
//    is not a gas) cannot be reached; the run fails.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "common/time_series.h"

namespace granasym::dem {

enum class ValidityFlag { kOverlapAbove2Pct, kOverlapAbove10Pct, kRateAffected, kGas };

}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::ValidityFlag> {
  static constexpr EnumEntry<dem::ValidityFlag> kEntries[] = {
      {dem::ValidityFlag::kOverlapAbove2Pct, "overlap_above_2pct",
       "warning: a relative overlap above the paper's 2 % limit of accuracy"},
      {dem::ValidityFlag::kOverlapAbove10Pct, "overlap_above_10pct",
       "a relative overlap above 10 %: results unreliable (paper Fig. 8)"},
      {dem::ValidityFlag::kRateAffected, "rate_affected",
       "I(d_max) above 1e-2 at the stage end or the asymptote"},
      {dem::ValidityFlag::kGas, "gas",
       "a gas or liquefied state at the stage end or the asymptote"},
  };
};

namespace granasym::dem {

// The limits of SPEC §8.3 (see the file comment for each).
struct ValidityLimits {
  double overlap_warning = 0.02;
  double overlap_unreliable = 0.10;
  double overlap_failure = 0.25;
  double inertial_number = 1e-2;             // of d_max
  double gas_mechanical_coordination = 3.0;  // Z_m below: a gas
  double gas_mean_stress_kpa = 0.5;          // p below: a gas
  double unreachable_strain = 0.3;           // accumulated strain away from a p target
};
inline constexpr ValidityLimits kValidityLimits{};

// A gas: no load-bearing network (Z_m) or no stress (p, kPa).
bool IsGas(double mean_stress_kpa, double mechanical_coordination,
           const ValidityLimits& limits = kValidityLimits);

// The state over output rows [first, last] of the series: means, and the
// largest relative overlap.
struct RowState {
  double mean_stress_kpa = 0;
  double void_ratio = 0;
  double coordination = 0;
  double mechanical_coordination = 0;
  double inertial_number_dmin = 0;
  double inertial_number_dmax = 0;
  double max_relative_overlap = 0;
  static RowState Mean(const TimeSeries& series, int64_t first, int64_t last);
};

// What the rows of one stage showed.
struct StageValidity {
  double max_relative_overlap = 0;         // over the stage's rows
  double max_inertial_number_dmax = 0;     // over its rows that are not a gas
  double min_mechanical_coordination = 0;  // over its rows
  double final_mean_stress_kpa = 0;        // of its last row
  std::vector<ValidityFlag> flags;

  bool Has(ValidityFlag flag) const;
  std::string FlagNames() const;  // "overlap_above_2pct, rate_affected"; "none"
  std::string OneLine() const;    // the numbers and the flags, for log lines
  // From the stage's rows [first_row, last_row]; rate_affected and gas are
  // judged on `state` (the asymptote's window or the last row).
  static StageValidity FromRows(const TimeSeries& series, int64_t first_row, int64_t last_row,
                                const RowState& state,
                                const ValidityLimits& limits = kValidityLimits);
};

}  // namespace granasym::dem
