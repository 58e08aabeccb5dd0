// Running a calibration file and reporting it: the fitted parameters with
// standard errors, 95 % intervals and correlations, residuals per dataset and
// per point, warnings, objective history, the parameters in the orders of
// Mašín's UMAT and PLAXIS; an HDF5 record, a readable summary and CSV/DAT
// files for the figures (plots/calibration_*.gp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "calibration/calibration_config.h"
#include "calibration/calibration_problem.h"
#include "calibration/fit_result.h"
#include "calibration/fit_status.h"
#include "calibration/pareto.h"
#include "calibration/profile_likelihood.h"
#include "calibration/starting_values.h"

namespace granasym::calibration {

// What became of each parameter.
enum class ParameterStatus { kFitted, kFixed, kAtBound, kUndetermined };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::ParameterStatus> {
  using S = calibration::ParameterStatus;
  static constexpr EnumEntry<S> kEntries[] = {
      {S::kFitted, "fitted", "fitted within its bounds"},
      {S::kFixed, "fixed", "fixed by the calibration file (free = false)"},
      {S::kAtBound, "at_bound", "fitted, but ended at a bound of the fit"},
      {S::kUndetermined, "undetermined",
       "the data do not determine it: fixed at its start value and the fit repeated"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// One admissibility or structural-misfit warning: a stable code for
// machines (e.g. "csl_ocr_mismatch") and a sentence for people.
// `inadmissible`: the fitted model fails a check of its own (see
// CheckAdmissibility), which makes the fit converged_inadmissible; the
// others compare the data with the model (a misfit, not an inadmissible model).
struct Finding {
  std::string code;
  std::string message;
  bool inadmissible = false;
  std::string Line() const { return code + ": " + message; }
};

// The DEM's rate at the fitted states (issue 36 §2): how many there are,
// how many carry an inertial number and the range of it, and how many are
// flagged rate_affected (I(d_max) above the DEM's limit, dem/stage_validity.h).
struct RateOfData {
  int states = 0;                                                   // fitted states (IsFitted)
  int with_rate = 0;                                                // of them with I(d_max)
  int rate_affected = 0;                                            // of them flagged rate_affected
  double dmin_low = 0, dmin_high = 0, dmax_low = 0, dmax_high = 0;  // over with_rate
  // Whether most fitted states are rate_affected (more than half).
  bool MostlyRateAffected() const { return 2 * rate_affected > states; }
  // "inertial numbers of the 12 fitted states: I(d_max) 0.021 to 0.11, ...".
  std::string Text() const;
  // The warning (code rate_affected) when MostlyRateAffected, else empty.
  std::string Warning() const;
};
RateOfData DescribeRate(const std::vector<StateDataset>& datasets);

struct CalibrationRun {
  CalibrationConfig config;
  StartingValues starting_values;
  std::unique_ptr<CalibrationProblem> problem;
  std::vector<FitResult> fits;  // one per fitter, in the order run
  // The fit whose parameters are reported (KeptFit): of the converged fits
  // the one of lowest cost, else of the fits that did not fail, else the
  // first; −1 without a fit.
  int kept = -1;
  // method = both: the largest |θ_ceres − θ_nlopt| / standard error (Ceres);
  // NaN with the reason in `agreement_not_compared` when a side did not
  // converge or Ceres gives no standard error.
  double agreement_in_standard_errors = 0.0;
  std::string agreement_not_compared;
  // Per parameter (model_parameters.h order), of the kept fit.
  std::vector<ParameterStatus> status;
  // Parameters fixed because the data do not determine them, each with why.
  std::vector<std::string> undetermined;
  // Parameters fixed as undetermined that their profile at the reported fit
  // showed determined after all: freed and refitted (or, where the refit
  // did not lower the cost, kept fixed), each with why.
  std::vector<std::string> freed;
  // The Ceres fits of the search for undetermined parameters besides the
  // reported fit (the last probe, of the final problem, is that fit itself).
  int probe_fits = 0;
  long probe_evaluations = 0;
  double probe_seconds = 0.0;
  // Admissibility checks and the diagnosis of structural misfit (kept fit).
  std::vector<Finding> findings;
  std::vector<std::string> diagnosis;  // per-kind residual lines (always)
  // The overall status and its reason (DecideFitStatus).
  FitOutcome outcome;
  // The rate of the fitted data (summary line; a rate_affected warning).
  RateOfData rate;
  // Of the kept fit when it succeeded and the config asks for them: the
  // profile likelihood of every free and every undetermined parameter, and
  // the Pareto front of the default residual groups (empty otherwise).
  ProfileSet profiles;
  // Refits from a profile's point of least cost (ProfileAndRefit); where the
  // first was kept, the kept fit is the last kept refit.
  std::vector<ProfileRestart> restarts;
  ParetoFront pareto;

  // The kept fit; nullptr without one.
  const FitResult* kept_fit() const;
};

// The index of the fit to keep among `fits` (see CalibrationRun::kept).
int KeptFitIndex(const std::vector<FitResult>& fits);

// The overall status of a run (fit_status.h) from the kept fit: failed when
// there is none or it failed; no_convergence when it stopped before
// converging; converged_inadmissible when a finding is `inadmissible`;
// at_bound when a fitted parameter ended at a bound; else converged. The
// reason names the fitter and what decided it (the first parameter at a
// bound, the first inadmissibility) in one sentence.
FitOutcome DecideFitStatus(const CalibrationRun& run);

// The largest |θ_a − θ_b| over the free parameters in standard errors of
// `a` (the Ceres fit; those FitResult::Reported), or NaN with `*why_not`
// saying why the two fits cannot be compared: a fit did not converge (its
// values are then only where it stopped; each such fit is named), or no
// parameter of `a` has a reported standard error.
double FitAgreementInStandardErrors(const FitResult& a, const FitResult& b, std::string* why_not);

// The parameters for `kind` with the user's choices applied; parameters
// without a value start from the data where an estimate exists.
// The sand's start comes from the clay-type estimates and `datasets` (the CSL's e/e_i).
ModelParameters ChooseParameters(ModelKind kind, const std::vector<ParameterChoice>& choices,
                                 const StartingValues& starting_values,
                                 const std::vector<StateDataset>& datasets = {});

// Reads the datasets, estimates starting values, builds the problem and runs
// the fitters, then (config.profiles, config.pareto) the profile likelihoods
// and the Pareto front of the kept fit. Throws InputError for bad data (naming file/line/column).
// With fix_undetermined (default), a Ceres fit finds the free parameter the
// data determine least — in the near-null space of the scaled Jacobian, or
// with a 95 % interval covering its whole bound range (the widest relative to
// that range) — fixes it at its start value, says so in `undetermined`, and
// repeats (at most five parameters) before the configured fitters run.
CalibrationRun RunCalibration(const CalibrationConfig& config);

// The admissibility checks on a fit (warnings, never errors; * marks the
// checks of the fitted model itself, Finding::inadmissible):
//   invalid_model*          the fitted parameters make no model;
//   kappa_not_below_lambda  κ* ≥ λ* (clay models; fitted*, or the data's own
//                           unloading slope against its NCL slope);
//   ocr_below_one           OCR < 0.99 along the model's compression asymptotes*
//                           (0 ≤ ψ_ε ≤ 90°), or NCL/compression states above
//                           the fitted NCL by more than twice their uncertainty;
//   asbs_outside            the model's ASBS cross-section not closed (a stress
//                           direction without an asymptote)* or beyond
//                           p/p_e* = 1.01*, or states beyond it (p/p_e* > 1 by more
//                           than twice their uncertainty);
//   csl_ocr_mismatch        the data's OCR at the critical state (the study
//                           table's own, else, for the clay models, against
//                           the data's straight NCL fit)
//                           differs from the model's by more than 25 %;
//   structural_misfit       per kind, a mean ln(1+e) or ψ_σ residual larger
//                           than twice the states' mean uncertainty.
// `diagnosis` gets one line per kind with the mean residuals and their signs.
std::vector<Finding> CheckAdmissibility(const CalibrationRun& run, const FitResult& fit,
                                        std::vector<std::string>* diagnosis);

// parameters.csv: parameter,value,std_error,ci95_low,ci95_high,status,
// profile_low,profile_high,profile,units; the standard error and interval empty
// where not FitResult::Reported; profile_low/high the profile's 95 %
// interval (empty where it does not cross the threshold), profile
// "determined" or "flat" (empty when not profiled) and units ParameterSpec::units.
std::string ParametersCsv(const CalibrationRun& run, const FitResult& fit);
// warnings.txt: one "code: message" per line (findings, the rate_affected
// warning, fit warnings of the kept fit, dataset warnings, undetermined
// parameters, profile_flat per flat profile and the profiles' and the Pareto
// sweep's own warnings); empty when none.
std::string WarningsText(const CalibrationRun& run);
// model.toml: the [model] block of the fit and an example element test
// (isotropic compression, then isochoric shear) so that `granasym model run`
// runs it as it stands.
std::string ModelToml(const CalibrationRun& run, const FitResult& fit);

// The readable summary; its second and third lines are the status and its
// reason ("status: at_bound", "reason: ...").
std::string SummaryText(const CalibrationRun& run);
void WriteCalibrationHdf5(const CalibrationRun& run, const std::string& path);
// states.csv, model_curve.csv, model_lines.dat in `folder` (created), and
// profiles.csv (ProfilesCsv) and pareto.csv (ParetoCsv) when computed, for
// plots/calibration_profiles.gp and plots/calibration_pareto.gp. The
// sand model has no analytic ASBS: its model_curve.csv holds the states at
// the data's ψ_ε (and 0°, 90°) at the geometric-mean p of the data, and its
// model_lines.dat the integrated paths (not straight lines) at each ψ_ε.
void WritePlotData(const CalibrationRun& run, const FitResult& fit, const std::string& folder);

}  // namespace granasym::calibration
