// The overall outcome of a calibration, one of five statuses, decided from
// the kept fit's termination, its parameters at a bound and the fitted
// model's admissibility (calibration_report.h: DecideFitStatus). Precedence,
// worst first:
//   failed > no_convergence > converged_inadmissible > at_bound > converged
// so a fit that did not converge says so even when it also ended at a bound.
//
// It is written, with a one-sentence reason, as the first lines of the
// summary, on standard output, in the HDF5 record (/calibration attributes
// `status`, `reason`) and in a small TOML file (`study calibrate`:
// DIR/calibration/<model>/fit_status.toml) that the report reads:
//   status = "at_bound"
//   reason = "..."
// `granasym calibrate` and `granasym study calibrate` exit with ExitStatus of
// the status (of the worst model for `study calibrate`): 0 only when every
// model converged.
#pragma once

#include <string>

#include "common/enum_names.h"

namespace granasym::calibration {

enum class FitStatus { kConverged, kConvergedInadmissible, kAtBound, kNoConvergence, kFailed };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::FitStatus> {
  using S = calibration::FitStatus;
  static constexpr EnumEntry<S> kEntries[] = {
      {S::kConverged, "converged",
       "converged, every fitted parameter inside its bounds, the fitted model admissible"},
      {S::kConvergedInadmissible, "converged_inadmissible",
       "converged, but the fitted model fails an admissibility check of its own (kappa* < "
       "lambda*, OCR >= 1 on compression asymptotes, ASBS closed and inside p/p_e* <= 1)"},
      {S::kAtBound, "at_bound",
       "converged with a fitted parameter at a bound: the optimum may lie outside the bounds"},
      {S::kNoConvergence, "no_convergence",
       "the fit stopped before a convergence criterion was met: its parameters are where it "
       "stopped"},
      {S::kFailed, "failed", "no fit: the fitter failed, or the data could not be fitted"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

using granasym::FromString;
using granasym::ToString;

// Larger is worse (the precedence of the file comment).
int Severity(FitStatus status);
FitStatus Worst(FitStatus a, FitStatus b);

// The exit status of `granasym calibrate` and `granasym study calibrate`
// (docs/guide/exit-statuses.md): converged 0, failed 3 (a failed fit, as for
// every command), at_bound 5, converged_inadmissible 6, no_convergence 7.
int ExitStatus(FitStatus status);

struct FitOutcome {
  FitStatus status = FitStatus::kFailed;
  std::string reason;  // one sentence, no line break
};

// The file name of `study calibrate`'s record of the outcome, in each
// DIR/calibration/<model>/.
inline constexpr char kFitStatusFile[] = "fit_status.toml";
// `status = "..."` and `reason = "..."`, exactly these two keys.
std::string FitStatusToml(const FitOutcome& outcome);
// Reads such a file; InputError naming the file and key when malformed.
FitOutcome ReadFitStatusToml(const std::string& path);

}  // namespace granasym::calibration
