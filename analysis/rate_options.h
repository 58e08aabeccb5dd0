// The options of the rate study (analysis/rate_study.h) and its rule for a
// usable state: the detector statuses that enter means, lines, fits and
// verdicts, and the validity flags that keep a state out; shared by the
// proportional and the drained states (analysis/drained_study.h).
#pragma once

#include <string>
#include <vector>

#include "study/state_table.h"

namespace granasym::analysis {

// The study's table of asymptotic states, which the analyses read.
using study::CsvNumber;
using study::CsvText;
using study::Interval;
using study::MeanInterval95;
using study::ReadStateTable;
using study::StateRow;
using study::TableKind;
using study::TableStatus;

// The published critical-state stress ratio of frictional spheres without
// rolling resistance that the study's quasi-static M is set against (issue 10
// §2); `source` says where the numbers come from and how they were converted.
// No triaxial value at μ ≈ 0.5 was found in a retrievable text, so the band is
// bounded by two shear-zone frictions read as tan φ = τ/σ_n:
//   Latham, Abe & Mora (2005), "Macroscopic friction response of rotational
//   and non-rotational lattice solid gouge models in 2D and 3D";
//   Mair, Frye & Marone (2002), J. Geophys. Res. 107(B10), 2219,
//   doi:10.1029/2001JB000516.
struct LiteratureBand {
  double low, high;
  const char* source;  // one sentence, for captions and the report
};
inline constexpr LiteratureBand kSphereCriticalStateRatio = {
    0.81, 0.95,
    "M = 0.81 from the 3D DEM of rotating spheres of Latham, Abe & Mora (2005, 'Macroscopic "
    "friction response of rotational and non-rotational lattice solid gouge models in 2D and "
    "3D': macroscopic friction 0.38 for contact friction μ_P ≥ 0.3, sheared between plates) to "
    "0.95 from the glass-bead shear zones of Mair, Frye & Marone (2002, J. Geophys. Res. "
    "107(B10) 2219: sliding friction 0.45), each friction read as tan φ and M = 6 sin φ/(3 − "
    "sin φ); read as sin φ they give 0.87 and 1.06, so the band brackets rather than checks a "
    "triaxial value"};

struct RateStudyOptions {
  // Detector statuses of the states that enter means, lines, fits and verdicts.
  std::vector<TableStatus> statuses = {TableStatus::kDetected};
  // ψ_ε = 0° states also when drifting: on the isotropic path the detector's
  // ψ_σ and slope tests are at the noise level of a small sample (the
  // study's own NCL fit takes them for the same reason, state_table.h).
  std::vector<TableStatus> ncl_statuses = {TableStatus::kDetected, TableStatus::kDrifting};
  // Validity flags that exclude a state (a gas or liquefied sample, overlaps
  // that make a result unreliable, SPEC §8.3).
  std::vector<std::string> excluded_flags = {"gas", "overlap_above_10pct"};
  // The quasi-static line is fitted through the states of this many of the
  // smallest I* values (with usable states); at least 2.
  int fit_rates = 3;
  // The mean stress (kPa) at which a line's position is read and compared.
  double reference_p_kpa = 100.0;
  // The published band the quasi-static M is compared with.
  LiteratureBand literature_m = kSphereCriticalStateRatio;
  bool IsValid(std::string* why) const;
};

// Whether the ';'-separated `flags` hold `flag`.
bool HasFlag(const std::string& flags, const std::string& flag);

// Whether a state's status is one of `statuses` and it carries none of the
// options' excluded flags (the part of usability that proportional and
// drained states share).
bool PassesFilters(TableStatus status, const std::string& flags,
                   const std::vector<TableStatus>& statuses, const RateStudyOptions& options);

// A state that liquefied: a gas (status or flag), no asymptotic state.
bool IsLiquefied(TableStatus status, const std::string& flags);

}  // namespace granasym::analysis
