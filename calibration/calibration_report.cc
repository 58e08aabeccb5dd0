// Calibration runs, summaries, HDF5 records and plot data.
#include "calibration/calibration_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <set>
#include <sstream>

#include "calibration/csv_state_reader.h"
#include "calibration/dem_state_reader.h"
#include "calibration/identifiability.h"
#include "calibration/path_report.h"
#include "calibration/study_state_reader.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/quantity_names.h"
#include "common/state_measures.h"
#include "common/statistics.h"
#include "common/text_file.h"
#include "constitutive/constitutive_model.h"

namespace granasym::calibration {

namespace {

// Starting values of the sand from the clay-type estimates (SPEC §6.3): at the
// geometric-mean p_ref of the NCL states, Bauer's e_i = e_i0 exp(−(3p/h_s)^n)
// has d ln(1+e)/d ln p = −n x e/(1+e), x = (3p/h_s)^n; with n at its start
// value this gives x, h_s and e_i0 from λ* and the NCL's e at p_ref; e_c0
// keeps the data's e_c/e_i at the CSL states (else e_c0 = e_i0/1.15), e_d0 =
// 0.6 e_c0; α, β keep their typical values.
void SandStart(const StartingValues& start, const std::vector<StateDataset>& datasets,
               std::vector<ParameterSpec>* specs) {
  auto set = [specs](int index, double value) {
    ParameterSpec& spec = (*specs)[index];
    if (std::isfinite(value)) spec.value = std::min(std::max(value, spec.lower), spec.upper);
  };
  if (start.critical_friction_angle_deg.from_data) {
    set(kSandCriticalFrictionAngle, start.critical_friction_angle_deg.value);
  }
  if (!(start.lambda_star.from_data && start.n_intercept.from_data)) return;
  double sum = 0, csl_ratio = 0;
  int count = 0, csl = 0;
  for (const StateDataset& d : datasets) {
    for (const AsymptoticStatePoint& point : d.points) {
      if (point.kind == StateKind::kNcl) {
        sum += std::log(point.mean_stress);
        ++count;
      }
    }
  }
  if (count == 0) return;
  const double lambda = start.lambda_star.value, n_line = start.n_intercept.value;
  const double p_ref = std::exp(sum / count);
  const double e_ref = std::expm1(n_line - lambda * std::log(p_ref));
  const double n = (*specs)[kSandExponent].value;
  const double x = lambda * (1 + e_ref) / (e_ref * n);
  set(kSandGranularHardness, 3.0 * p_ref / std::pow(x, 1.0 / n));
  const double e_i0 = e_ref * std::exp(x);
  set(kSandLoosestVoidRatio, e_i0);
  for (const StateDataset& d : datasets) {
    for (const AsymptoticStatePoint& point : d.points) {
      if (point.kind != StateKind::kCsl) continue;
      const double e_i = std::expm1(n_line - lambda * std::log(point.mean_stress));
      csl_ratio += point.void_ratio / e_i;
      ++csl;
    }
  }
  const double ratio = csl > 0 ? std::min(csl_ratio / csl, 0.98) : 1.0 / 1.15;
  set(kSandCriticalVoidRatio, e_i0 * ratio);
  set(kSandDensestVoidRatio, 0.6 * e_i0 * ratio);
}

// The estimate of the clay models' starting values for `role`; nullptr for
// the roles of the sand (SandStart) and typical values.
const Estimate* EstimateFor(const StartingValues& start, ParameterStart role) {
  switch (role) {
    case ParameterStart::kCslStressRatio:
      return &start.critical_friction_angle_deg;
    case ParameterStart::kNclSlope:
      return &start.lambda_star;
    case ParameterStart::kUnloadingSlope:
      return &start.kappa_star;
    case ParameterStart::kNclIntercept:
      return &start.n_intercept;
    case ParameterStart::kTypical:
    case ParameterStart::kBauerNcl:
    case ParameterStart::kCslVoidRatio:
    case ParameterStart::kDensestFraction:
      return nullptr;
  }
  return nullptr;
}

}  // namespace

ModelParameters ChooseParameters(ModelKind kind, const std::vector<ParameterChoice>& choices,
                                 const StartingValues& start,
                                 const std::vector<StateDataset>& datasets) {
  ModelParameters parameters = ModelParameters::Defaults(kind);
  std::vector<ParameterSpec>& specs = parameters.mutable_specs();
  const std::vector<FittedParameter>& fitted = parameters.traits().parameters;
  if (parameters.traits().linear_ncl) {
    // Each parameter from its estimate, clamped into its bounds; κ* takes
    // its assumed value (λ*/5 of the data) too.
    for (size_t i = 0; i < fitted.size(); ++i) {
      const Estimate* e = EstimateFor(start, fitted[i].start);
      if (e == nullptr) continue;
      if (e->from_data) {
        specs[i].value = std::min(std::max(e->value, specs[i].lower), specs[i].upper);
      } else if (fitted[i].start == ParameterStart::kUnloadingSlope) {
        specs[i].value = e->value;
      }
    }
  } else {
    // Bauer's law: the starts come from the clay-type estimates together.
    SandStart(start, datasets, &specs);
  }
  for (const ParameterChoice& choice : choices) {
    const int index = parameters.Index(choice.name);
    GRANASYM_CHECK(index >= 0) << choice.name;
    ParameterSpec& spec = specs[index];
    spec.free = choice.free;
    if (choice.has_lower) spec.lower = choice.lower;
    if (choice.has_upper) spec.upper = choice.upper;
    if (choice.has_value) spec.value = choice.value;
    if (spec.free) spec.value = std::min(std::max(spec.value, spec.lower), spec.upper);
  }
  return parameters;
}

namespace {

StateDataset ReadDataset(const DatasetConfig& d) {
  if (d.is_study) return ReadStatesStudy(d.path, d.name, d.study);
  if (!d.is_dem) return ReadStatesCsv(d.path, d.name, d.csv);
  StateDataset merged;
  for (const std::string& path : d.paths) {
    StateDataset one = ReadStatesDem(path, d.name, d.dem);
    if (merged.points.empty() && merged.warnings.empty()) {
      merged = std::move(one);
      continue;
    }
    merged.origin += ", " + one.origin;
    merged.points.insert(merged.points.end(), one.points.begin(), one.points.end());
    merged.warnings.insert(merged.warnings.end(), one.warnings.begin(), one.warnings.end());
  }
  return merged;
}

}  // namespace

RateOfData DescribeRate(const std::vector<StateDataset>& datasets) {
  RateOfData rate;
  const double inf = std::numeric_limits<double>::infinity();
  rate.dmin_low = rate.dmax_low = inf;
  rate.dmin_high = rate.dmax_high = -inf;
  for (const StateDataset& d : datasets) {
    for (const AsymptoticStatePoint& point : d.points) {
      if (!point.IsFitted()) continue;
      ++rate.states;
      rate.rate_affected += point.HasFlag("rate_affected") ? 1 : 0;
      if (!std::isfinite(point.inertial_number_dmax)) continue;
      ++rate.with_rate;
      rate.dmax_low = std::min(rate.dmax_low, point.inertial_number_dmax);
      rate.dmax_high = std::max(rate.dmax_high, point.inertial_number_dmax);
      if (std::isfinite(point.inertial_number_dmin)) {
        rate.dmin_low = std::min(rate.dmin_low, point.inertial_number_dmin);
        rate.dmin_high = std::max(rate.dmin_high, point.inertial_number_dmin);
      }
    }
  }
  return rate;
}

std::string RateOfData::Text() const {
  std::string text = fmt::format("rate of the data: {} fitted states", states);
  if (with_rate == 0) return text + ", none with an inertial number (not a DEM study table)";
  text += fmt::format(", {} with an inertial number: I(d_max) {:.3g} to {:.3g}", with_rate,
                      dmax_low, dmax_high);
  if (dmin_low <= dmin_high)
    text += fmt::format(", I(d_min) {:.3g} to {:.3g}", dmin_low, dmin_high);
  return text + fmt::format("; {} of {} flagged rate_affected", rate_affected, states);
}

std::string RateOfData::Warning() const {
  if (!MostlyRateAffected()) return "";
  return fmt::format(
      "{} of the {} fitted states are flagged rate_affected (I(d_max) above the DEM's "
      "quasi-static limit; here I(d_max) {:.3g} to {:.3g}): the parameters describe the DEM at "
      "its rate, not its quasi-static behaviour; fit a quasi-static selection (`granasym study "
      "calibrate --select quasi_static`, docs/guide/calibration.md)",
      rate_affected, states, dmax_low, dmax_high);
}

CalibrationRun RunCalibration(const CalibrationConfig& config) {
  CalibrationRun run;
  run.config = config;
  std::vector<StateDataset> datasets;
  std::vector<PathDataset> paths;
  for (const DatasetConfig& d : config.datasets) {
    if (d.is_path) {
      paths.push_back(ReadPathDem(d.path, d.name, d.path_read));
    } else {
      datasets.push_back(ReadDataset(d));
    }
  }
  if (datasets.empty()) {
    throw InputError(
        "calibration: only path datasets; a calibration needs asymptotic states beside them "
        "(a [[dataset]] with study, dem or csv)");
  }
  run.starting_values = EstimateStartingValues(datasets);
  run.rate = DescribeRate(datasets);
  ModelParameters parameters =
      ChooseParameters(config.model, config.parameters, run.starting_values, datasets);
  std::vector<bool> undetermined(parameters.specs().size(), false);
  if (config.fix_undetermined) {
    // What these data cannot identify whatever the fit (no states in the
    // directions a parameter acts on) is fixed before the first fit.
    for (const auto& [index, need] : Unidentifiable(datasets, parameters, paths)) {
      ParameterSpec& spec = parameters.mutable_specs()[index];
      spec.free = false;
      undetermined[index] = true;
      run.undetermined.push_back(
          fmt::format("{} fixed at its start value {:.6g}: these data cannot identify it ({})",
                      spec.name, spec.value, need));
    }
  }
  run.problem = std::make_unique<CalibrationProblem>(datasets, parameters, config.predictor, paths);
  // The last probe when it is the Ceres fit of the final problem (the loop
  // ended without changing the problem): the fit itself, not rerun.
  std::unique_ptr<FitResult> final_probe;
  // The probes need the fit's standard errors and null directions, which
  // ComputeUncertainty takes from its own central-difference Jacobian at the
  // probe's optimum; with fast_refits their iterations use forward
  // differences to a cost tolerance of 1e-8 (CostRefitOptions), and the
  // reported fit is then run with the exact options.
  const bool fast_probes = config.profiles.fast_refits;
  CeresFitter::Options probe_options = CeresFitter::CostRefitOptions(config.ceres, fast_probes);
  probe_options.compute_uncertainty = true;
  if (config.fix_undetermined) {
    // One parameter per round: fixing one of a correlated pair often
    // determines the other.
    for (int round = 0; round < kMaxUndeterminedRounds; ++round) {
      FitResult probe = CeresFitter(probe_options).Fit(*run.problem);
      ++run.probe_fits;
      run.probe_evaluations += probe.summary.evaluations;
      run.probe_seconds += probe.summary.wall_seconds;
      if (!probe.summary.success() || run.problem->num_free() <= 1) {
        if (!fast_probes) final_probe = std::make_unique<FitResult>(std::move(probe));
        break;
      }
      const std::pair<int, std::string> found = LeastDetermined(*run.problem, probe);
      if (found.first < 0) {
        if (!fast_probes) final_probe = std::make_unique<FitResult>(std::move(probe));
        break;
      }
      {
        const int index = found.first;
        const std::string& why = found.second;
        ParameterSpec& spec = parameters.mutable_specs()[index];
        spec.free = false;
        undetermined[index] = true;
        run.undetermined.push_back(fmt::format(
            "{} fixed at its start value {:.6g}: the data do not determine it ({}; the fit "
            "had reached {:.6g})",
            spec.name, spec.value, why, probe.values[index]));
      }
      run.problem =
          std::make_unique<CalibrationProblem>(datasets, parameters, config.predictor, paths);
    }
  }
  if (config.method != FitMethod::kNlopt) {
    // The Ceres fit is deterministic: the last probe, where it fitted this
    // very problem with these options (exact probes), is it.
    if (final_probe) {
      --run.probe_fits;
      run.probe_evaluations -= final_probe->summary.evaluations;
      run.probe_seconds -= final_probe->summary.wall_seconds;
      run.fits.push_back(std::move(*final_probe));
    } else {
      run.fits.push_back(CeresFitter(config.ceres).Fit(*run.problem));
    }
  }
  if (config.method != FitMethod::kCeres) {
    run.fits.push_back(NloptFitter(config.nlopt).Fit(*run.problem));
  }
  if (run.fits.size() == 2) {
    run.agreement_in_standard_errors =
        FitAgreementInStandardErrors(run.fits[0], run.fits[1], &run.agreement_not_compared);
  }
  run.kept = KeptFitIndex(run.fits);
  if (run.kept_fit() && run.kept_fit()->summary.success() && config.profiles.enabled) {
    ProfileTheKeptFit(config, undetermined, /*compare_fits=*/true, &run);
    FreeRejectedFixedValues(config, datasets, paths, &parameters, &undetermined, &run);
  }
  const std::vector<ParameterSpec>& specs = run.problem->parameters().specs();
  const double tolerance = config.ceres.uncertainty.bound_tolerance;
  const FitResult* kept = run.kept_fit();
  for (size_t i = 0; i < specs.size(); ++i) {
    ParameterStatus status = ParameterStatus::kFitted;
    if (undetermined[i]) {
      status = ParameterStatus::kUndetermined;
    } else if (!specs[i].free) {
      status = ParameterStatus::kFixed;
    } else if (kept && !kept->values.empty() && AtBound(specs[i], kept->values[i], tolerance)) {
      status = ParameterStatus::kAtBound;
    }
    run.status.push_back(status);
  }
  if (kept && kept->summary.success()) {
    run.findings = CheckAdmissibility(run, *kept, &run.diagnosis);
    if (config.pareto.enabled) {
      run.pareto = ComputeParetoFront(*run.problem, *kept, ChooseResidualGroups(*run.problem),
                                      config.ceres, config.pareto);
    }
  }
  run.outcome = DecideFitStatus(run);
  return run;
}

namespace {

std::string FitText(const CalibrationRun& run, const FitResult& fit) {
  const CalibrationProblem& problem = *run.problem;
  const ModelParameters& parameters = problem.parameters();
  std::string s = fit.summary.Report() + "\n";
  s += fmt::format(
      "  residual variance s^2 = {:.4g} ({} degrees of freedom), condition number "
      "{:.3g}\n",
      fit.residual_variance, fit.degrees_of_freedom, fit.condition_number);
  s += fmt::format("  {:<14} {:>12} {:>14} {:>26}  {}\n", "parameter", "value", "std. error",
                   "95 % interval", "units");
  for (size_t i = 0; i < parameters.specs().size(); ++i) {
    const ParameterSpec& spec = parameters.specs()[i];
    int k = -1;
    for (size_t j = 0; j < fit.free_indices.size(); ++j) {
      if (fit.free_indices[j] == static_cast<int>(i)) k = static_cast<int>(j);
    }
    if (k >= 0 && fit.Reported(static_cast<size_t>(k))) {
      s += fmt::format("  {:<14} {:>12.6g} {:>14.3g}   [{:>10.6g}, {:>10.6g}]  {}\n", spec.name,
                       fit.values[i], fit.standard_errors[k], fit.lower_95[k], fit.upper_95[k],
                       spec.units);
      continue;
    }
    // Fixed, or no standard error that means something: at a bound, or in a
    // near-null direction of the Jacobian (or no uncertainty computed).
    const bool at_bound = k >= 0 && static_cast<size_t>(k) < fit.at_bound.size() && fit.at_bound[k];
    s += fmt::format("  {:<14} {:>12.6g} {:>14} {:>26}  {}\n", spec.name, fit.values[i],
                     k < 0      ? "fixed"
                     : at_bound ? "at bound"
                                : "not determined",
                     "", spec.units);
  }
  if (!fit.null_directions.empty()) {
    // (JᵀJ)⁻¹ does not exist: correlations would describe the pseudo-inverse.
    s += fmt::format(
        "  correlations not reported: the Jacobian is rank-deficient (rank {} of {}); the data "
        "do not determine these directions (relative changes of the parameters):\n",
        static_cast<int>(fit.free_indices.size() - fit.null_directions.size()),
        fit.free_indices.size());
    for (const NullDirection& null : fit.null_directions) {
      s += fmt::format("    {} (singular value ratio {:.3g})\n",
                       null.Text(parameters, fit.free_indices), null.singular_ratio);
    }
  } else if (fit.correlation.rows() > 1) {
    s += "  correlation matrix (free parameters; (J^T J)^-1 normalised):\n";
    s += fmt::format("    {:<14}", "");
    for (int c = 0; c < fit.correlation.cols(); ++c) {
      s += fmt::format(" {:>7.7}", parameters.specs()[fit.free_indices[c]].name);
    }
    s += "\n";
    std::string strong;
    for (int r = 0; r < fit.correlation.rows(); ++r) {
      s += fmt::format("    {:<14}", parameters.specs()[fit.free_indices[r]].name);
      for (int c = 0; c < fit.correlation.cols(); ++c) {
        s += fmt::format(" {:>7.3f}", fit.correlation(r, c));
        if (c > r && std::abs(fit.correlation(r, c)) > 0.95) {
          strong +=
              fmt::format("{}{} and {} ({:.3f})", strong.empty() ? "" : ", ",
                          parameters.specs()[fit.free_indices[r]].name,
                          parameters.specs()[fit.free_indices[c]].name, fit.correlation(r, c));
        }
      }
      s += "\n";
    }
    if (!strong.empty()) s += "  strongly correlated (|rho| > 0.95): " + strong + "\n";
  }
  for (const std::string& w : fit.warnings) s += "  WARNING: " + w + "\n";
  // Residuals per dataset.
  s += "  residuals per dataset (model - data): RMS and largest |.|\n";
  for (size_t d = 0; d < problem.datasets().size(); ++d) {
    double ss_psi = 0, ss_v = 0, max_psi = 0, max_v = 0;
    int n_psi = 0, n_v = 0;
    for (const PointResidual& r : fit.residuals) {
      if (r.dataset != static_cast<int>(d)) continue;
      if (std::isfinite(r.psi_sigma_residual_deg)) {
        ss_psi += r.psi_sigma_residual_deg * r.psi_sigma_residual_deg;
        max_psi = std::max(max_psi, std::abs(r.psi_sigma_residual_deg));
        ++n_psi;
      }
      if (std::isfinite(r.ln_volume_residual)) {
        ss_v += r.ln_volume_residual * r.ln_volume_residual;
        max_v = std::max(max_v, std::abs(r.ln_volume_residual));
        ++n_v;
      }
    }
    s += fmt::format(
        "    {:<16} d_psi_sigma {:.4g} deg (max {:.4g}, {} pts); d_ln(1+e) {:.4g} "
        "(max {:.4g}, {} pts)\n",
        problem.datasets()[d].name, n_psi ? std::sqrt(ss_psi / n_psi) : 0.0, max_psi, n_psi,
        n_v ? std::sqrt(ss_v / n_v) : 0.0, max_v, n_v);
  }
  s += "  exported parameters:\n";
  for (const ExportedParameters& e : ExportOrders(parameters.kind(), fit.values)) {
    s += "    " + e.program + ":";
    for (size_t k = 0; k < e.values.size(); ++k) {
      s += fmt::format(" {}={}={:.6g}", k + 1, e.values[k].first, e.values[k].second);
    }
    s += "\n";
  }
  return s;
}

std::string PointsText(const CalibrationRun& run, const FitResult& fit) {
  std::string s = fmt::format("  {:<12} {:>10} {:>8} {:>9} {:>9} {:>10} {:>11}  {}\n", "kind",
                              quantity::kMeanStress, quantity::kVoidRatio, "psi_eps", "psi_sig",
                              "d_psi_deg", "d_ln(1+e)", "source");
  for (const PointResidual& r : fit.residuals) {
    const AsymptoticStatePoint& p = run.problem->datasets()[r.dataset].points[r.point];
    s += fmt::format("  {:<12} {:>10.4g} {:>8.4f} {:>9.3f} {:>9.3f} {:>10.4f} {:>11.3e}  {}{}\n",
                     ToString(p.kind), p.mean_stress, p.void_ratio, p.psi_epsilon / kDegree,
                     p.psi_sigma / kDegree, r.psi_sigma_residual_deg, r.ln_volume_residual,
                     p.source, r.clamped ? " (outside the model's range)" : "");
  }
  return s;
}

}  // namespace

double FitAgreementInStandardErrors(const FitResult& a, const FitResult& b, std::string* why_not) {
  why_not->clear();
  std::vector<std::string> not_converged;
  for (const FitResult* fit : {&a, &b}) {
    if (fit->summary.termination != FitTermination::kConverged) {
      not_converged.push_back(fmt::format(
          "{} did not converge ({}{})", fit->summary.fitter, ToString(fit->summary.termination),
          fit->summary.message.empty() ? "" : ": " + fit->summary.message));
    }
  }
  if (!not_converged.empty()) {
    *why_not = not_converged.front() +
               (not_converged.size() > 1 ? " and " + not_converged.back() : std::string()) +
               ", so there is no pair of optima to compare";
    return std::numeric_limits<double>::quiet_NaN();
  }
  double worst = 0;
  bool compared = false;
  for (size_t k = 0; k < a.free_indices.size() && k < a.standard_errors.size(); ++k) {
    const int i = a.free_indices[k];
    if (a.Reported(k) && a.standard_errors[k] > 0) {
      worst = std::max(worst, std::abs(a.values[i] - b.values[i]) / a.standard_errors[k]);
      compared = true;
    }
  }
  if (!compared) {
    *why_not = fmt::format(
        "{} reports no standard error of any free parameter (each is undetermined or at a bound)",
        a.summary.fitter);
    return std::numeric_limits<double>::quiet_NaN();
  }
  return worst;
}

const FitResult* CalibrationRun::kept_fit() const {
  return kept >= 0 && kept < static_cast<int>(fits.size()) ? &fits[kept] : nullptr;
}

int KeptFitIndex(const std::vector<FitResult>& fits) {
  int kept = -1;
  // Rank: converged before not converged before failed; then the lower cost.
  const auto rank = [](const FitResult& fit) {
    return fit.summary.termination == FitTermination::kConverged ? 0
           : fit.summary.termination == FitTermination::kFailure ? 2
                                                                 : 1;
  };
  for (size_t k = 0; k < fits.size(); ++k) {
    if (kept < 0) {
      kept = static_cast<int>(k);
      continue;
    }
    const FitResult& a = fits[k];
    const FitResult& b = fits[kept];
    if (rank(a) < rank(b) ||
        (rank(a) == rank(b) && rank(a) < 2 && a.summary.final_cost < b.summary.final_cost)) {
      kept = static_cast<int>(k);
    }
  }
  return kept;
}

FitOutcome DecideFitStatus(const CalibrationRun& run) {
  const FitResult* fit = run.kept_fit();
  if (!fit) return {FitStatus::kFailed, "no fit ran"};
  const FitSummary& summary = fit->summary;
  if (summary.termination == FitTermination::kFailure) {
    return {FitStatus::kFailed,
            fmt::format("the {} fit failed: {}.", summary.fitter,
                        summary.message.empty() ? "no reason given" : summary.message)};
  }
  if (summary.termination == FitTermination::kNoConvergence) {
    return {FitStatus::kNoConvergence,
            fmt::format("the {} fit stopped after {} iterations ({} evaluations) before a "
                        "convergence criterion was met{}, so its parameters are only where it "
                        "stopped.",
                        summary.fitter, summary.iterations, summary.evaluations,
                        summary.message.empty() ? "" : " (" + summary.message + ")")};
  }
  std::vector<const Finding*> inadmissible;
  for (const Finding& f : run.findings) {
    if (f.inadmissible) inadmissible.push_back(&f);
  }
  if (!inadmissible.empty()) {
    return {FitStatus::kConvergedInadmissible,
            fmt::format("the {} fit converged, but the fitted model is inadmissible: {} ({}){}.",
                        summary.fitter, inadmissible.front()->message, inadmissible.front()->code,
                        inadmissible.size() > 1
                            ? fmt::format(", and {} more such warnings", inadmissible.size() - 1)
                            : "")};
  }
  const std::vector<ParameterSpec>& specs = run.problem->parameters().specs();
  std::vector<std::string> at_bound;
  for (size_t i = 0; i < specs.size() && i < run.status.size(); ++i) {
    if (run.status[i] != ParameterStatus::kAtBound) continue;
    const double v = fit->values[i];
    const bool lower = std::abs(v - specs[i].lower) <= std::abs(specs[i].upper - v);
    at_bound.push_back(fmt::format("{} = {:.6g} at its {} bound {:.6g}", specs[i].name, v,
                                   lower ? "lower" : "upper",
                                   lower ? specs[i].lower : specs[i].upper));
  }
  if (!at_bound.empty()) {
    std::string list;
    for (size_t k = 0; k < at_bound.size(); ++k) {
      list += (k == 0 ? "" : k + 1 == at_bound.size() ? " and " : ", ") + at_bound[k];
    }
    return {FitStatus::kAtBound,
            fmt::format("the {} fit converged with {}: the optimum may lie beyond the bounds, and "
                        "the standard errors of parameters at a bound are not reported.",
                        summary.fitter, list)};
  }
  return {FitStatus::kConverged,
          fmt::format("the {} fit converged after {} iterations with every fitted parameter "
                      "inside its bounds and the fitted model admissible{}.",
                      summary.fitter, summary.iterations,
                      run.findings.empty() ? ""
                                           : fmt::format(" ({} misfit warnings: see the summary)",
                                                         run.findings.size()))};
}

std::string SummaryText(const CalibrationRun& run) {
  const CalibrationProblem& problem = *run.problem;
  std::string s =
      fmt::format("granasym calibration: {}\nstatus: {}\nreason: {}\nmodel: {} (asymptotes: {})\n",
                  run.config.origin, ToString(run.outcome.status), run.outcome.reason,
                  ToString(problem.parameters().kind()), ToString(run.config.predictor.method));
  s += fmt::format(
      "residuals: {} (psi_sigma in deg / sigma_psi, ln(1+e) / sigma_v, times "
      "sqrt(weight)); free parameters: {}\n",
      problem.num_residuals(), problem.num_free());
  s += "datasets:\n";
  for (const StateDataset& d : problem.datasets()) {
    s += fmt::format("  {} ({}): {} states:", d.name, d.origin, d.points.size());
    for (StateKind k : {StateKind::kNcl, StateKind::kCsl, StateKind::kCompression,
                        StateKind::kExtension, StateKind::kAsbs, StateKind::kUnloading}) {
      if (d.Count(k) > 0) s += fmt::format(" {} {}", d.Count(k), ToString(k));
    }
    s += "\n";
    for (const std::string& w : d.warnings) s += "    WARNING: " + w + "\n";
  }
  for (const PathDataset& path : problem.paths()) {
    s += fmt::format("  {} ({}): a whole path, {} samples, {} residuals (group 'path')\n",
                     path.name, path.source, path.samples.size(), path.NumResiduals());
  }
  s += run.rate.Text() + "\n";
  if (run.rate.MostlyRateAffected()) s += "WARNING rate_affected: " + run.rate.Warning() + "\n";
  s += run.starting_values.Report() + "\n";
  for (const std::string& u : run.undetermined) s += "UNDETERMINED: " + u + "\n";
  for (const std::string& f : run.freed) s += "FREED: " + f + "\n";
  if (run.probe_fits > 0) {
    s += fmt::format(
        "undetermined search: {} Ceres fit{} before the reported one ({} evaluations, {:.2f} "
        "s)\n",
        run.probe_fits, run.probe_fits == 1 ? "" : "s", run.probe_evaluations, run.probe_seconds);
  }
  for (const FitResult& fit : run.fits) s += "\n" + FitText(run, fit);
  if (!run.restarts.empty()) {
    s += "\nrefits from the profiles (a profile reached a lower cost than the fit):\n";
    for (const ProfileRestart& restart : run.restarts) s += "  " + restart.Text() + "\n";
    if (run.restarts.front().kept) {
      s += "  the fit above is the last refit; the profiles below are of it\n";
    }
  }
  if (!run.status.empty()) {
    s += "\nparameter status:";
    const std::vector<ParameterSpec>& specs = problem.parameters().specs();
    for (size_t i = 0; i < specs.size() && i < run.status.size(); ++i) {
      s += fmt::format(" {} {};", specs[i].name, ToString(run.status[i]));
    }
    s += "\n";
  }
  const FitResult* kept = run.kept_fit();
  if (kept && !kept->values.empty()) {
    const std::string paths = PathSummaryText(problem, kept->values);
    if (!paths.empty()) s += "\nwhole paths (" + kept->summary.fitter + "):\n" + paths;
  }
  if (!run.diagnosis.empty() || !run.findings.empty()) {
    s += "\nadmissibility and structural misfit (" +
         (kept ? kept->summary.fitter : std::string("-")) + "):\n";
    for (const std::string& line : run.diagnosis) s += "  " + line + "\n";
    for (const Finding& f : run.findings) {
      s += std::string(f.inadmissible ? "  INADMISSIBLE " : "  WARNING ") + f.Line() + "\n";
    }
    if (run.findings.empty()) s += "  no warnings\n";
  }
  if (run.fits.size() == 2) {
    if (run.agreement_not_compared.empty()) {
      s += fmt::format("\n{} vs {}: largest parameter difference {:.3g} standard errors\n",
                       run.fits[0].summary.fitter, run.fits[1].summary.fitter,
                       run.agreement_in_standard_errors);
    } else {
      s += fmt::format("\n{} vs {}: not compared: {}\n", run.fits[0].summary.fitter,
                       run.fits[1].summary.fitter, run.agreement_not_compared);
    }
    if (kept) s += "kept: the " + kept->summary.fitter + " fit\n";
  }
  if (!run.profiles.empty()) s += "\n" + ProfilesText(run.profiles);
  if (run.pareto.computed() || !run.pareto.not_computed.empty()) {
    s += "\n" + ParetoText(run.pareto, problem.parameters());
  }
  if (kept) {
    s += "\nresiduals per point (" + kept->summary.fitter + "):\n" + PointsText(run, *kept);
    s += "\nobjective history (" + kept->summary.fitter + ", best cost so far):\n";
    const std::vector<HistoryPoint>& h = kept->history;
    const size_t step = std::max<size_t>(1, h.size() / 20);
    for (size_t i = 0; i < h.size(); i += step) {
      s += fmt::format("  evaluation {:>7}  cost {:.8g}  {}\n", h[i].evaluation, h[i].cost,
                       h[i].stage);
    }
  }
  return s;
}

namespace {

// /fits/<fitter>: a fit's summary, values, uncertainties, history, residuals
// and export orders (`units`: the parameters' units, comma-separated).
void WriteFitHdf5(const FitResult& fit, const ModelParameters& parameters, const std::string& units,
                  Hdf5File* file) {
  std::string group = "/fits/" + fit.summary.fitter;
  for (char& c : group) c = (c == ':' || c == '+') ? '_' : c;
  file->CreateGroup(group);
  file->SetAttribute(group, "fitter", fit.summary.fitter);
  file->SetAttribute(group, "termination", ToString(fit.summary.termination));
  file->SetAttribute(group, "message", fit.summary.message);
  file->SetAttribute(group, "report", fit.summary.Report());
  file->SetAttribute(group, "iterations", int64_t{fit.summary.iterations});
  file->SetAttribute(group, "evaluations", int64_t{fit.summary.evaluations});
  file->SetAttribute(group, "initial_cost", fit.summary.initial_cost);
  file->SetAttribute(group, "final_cost", fit.summary.final_cost);
  file->SetAttribute(group, "wall_s", fit.summary.wall_seconds);
  file->SetAttribute(group, "residual_variance", fit.residual_variance);
  file->SetAttribute(group, "degrees_of_freedom", int64_t{fit.degrees_of_freedom});
  file->SetAttribute(group, "condition_number", fit.condition_number);
  std::string warnings;
  for (const std::string& w : fit.warnings) warnings += w + "\n";
  file->SetAttribute(group, "warnings", warnings);
  file->WriteDoubles(group + "/values", fit.values, units);
  std::vector<int64_t> free_index(fit.free_indices.begin(), fit.free_indices.end());
  file->WriteInts(group + "/free_index", free_index, "1");
  file->WriteDoubles(group + "/standard_errors", fit.standard_errors);
  file->WriteDoubles(group + "/lower_95", fit.lower_95);
  file->WriteDoubles(group + "/upper_95", fit.upper_95);
  const size_t n = fit.free_indices.size();
  std::vector<double> cov, cor;
  for (size_t r = 0; r < n; ++r) {
    for (size_t c = 0; c < n; ++c) {
      cov.push_back(fit.covariance.size() ? fit.covariance(r, c) : std::nan(""));
      cor.push_back(fit.correlation.size() ? fit.correlation(r, c) : std::nan(""));
    }
  }
  if (n > 0) {
    file->WriteMatrix(group + "/covariance", cov, n, n, "parameter units squared");
    file->WriteMatrix(group + "/correlation", cor, n, n, "1");
  }
  std::vector<double> hist_eval, hist_cost;
  for (const HistoryPoint& h : fit.history) {
    hist_eval.push_back(static_cast<double>(h.evaluation));
    hist_cost.push_back(h.cost);
  }
  file->WriteDoubles(group + "/history/evaluation", hist_eval, "1");
  file->WriteDoubles(group + "/history/cost", hist_cost, "1");
  std::vector<double> d_psi, d_v, m_psi, m_v, ln_ocr;
  for (const PointResidual& r : fit.residuals) {
    d_psi.push_back(r.psi_sigma_residual_deg);
    d_v.push_back(r.ln_volume_residual);
    m_psi.push_back(r.psi_sigma_model / kDegree);
    m_v.push_back(r.ln_volume_model);
    ln_ocr.push_back(r.ln_ocr_model);
  }
  file->WriteDoubles(group + "/residuals/" + quantity::kPsiSigma, d_psi, "deg");
  file->WriteDoubles(group + "/residuals/" + quantity::kLnVolume, d_v, "1");
  file->WriteDoubles(group + "/model/" + quantity::kPsiSigma, m_psi, "deg");
  file->WriteDoubles(group + "/model/" + quantity::kLnVolume, m_v, "1");
  file->WriteDoubles(group + "/model/ln_ocr", ln_ocr, "1");
  for (const ExportedParameters& e : ExportOrders(parameters.kind(), fit.values)) {
    std::string order;
    std::vector<double> values;
    for (const auto& v : e.values) {
      order += (order.empty() ? "" : ",") + v.first;
      values.push_back(v.second);
    }
    const std::string name =
        group + (e.program.rfind("UMAT", 0) == 0 || e.program.rfind("Modified", 0) == 0
                     ? "/export_umat"
                     : "/export_plaxis");
    file->WriteDoubles(name, values);
    file->SetAttribute(name, "program", e.program);
    file->SetAttribute(name, "order", order);
  }
}

}  // namespace

void WriteCalibrationHdf5(const CalibrationRun& run, const std::string& path) {
  const CalibrationProblem& problem = *run.problem;
  const ModelParameters& parameters = problem.parameters();
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.CreateGroup("/calibration");
  file.SetAttribute("/calibration", "config", run.config.origin);
  file.SetAttribute("/calibration", "model", ToString(parameters.kind()));
  file.SetAttribute("/calibration", "asymptotes", ToString(run.config.predictor.method));
  file.SetAttribute("/calibration", "method", ToString(run.config.method));
  file.SetAttribute("/calibration", "residuals", int64_t{problem.num_residuals()});
  file.SetAttribute("/calibration", "status", ToString(run.outcome.status));
  file.SetAttribute("/calibration", "reason", run.outcome.reason);
  if (run.kept_fit()) file.SetAttribute("/calibration", "kept_fit", run.kept_fit()->summary.fitter);
  file.SetAttribute("/calibration", "starting_values", run.starting_values.Report());
  if (run.fits.size() == 2) {
    if (run.agreement_not_compared.empty()) {
      file.SetAttribute("/calibration", "ceres_nlopt_largest_difference_in_standard_errors",
                        run.agreement_in_standard_errors);
    } else {
      file.SetAttribute("/calibration", "ceres_nlopt_not_compared", run.agreement_not_compared);
    }
  }
  std::string names, symbols, units;
  for (const ParameterSpec& spec : parameters.specs()) {
    names += (names.empty() ? "" : ",") + spec.name;
    symbols += (symbols.empty() ? "" : ",") + spec.symbol;
    units += (units.empty() ? "" : ",") + spec.units;
  }
  file.SetAttribute("/calibration", "parameter_names", names);
  file.SetAttribute("/calibration", "parameter_symbols", symbols);
  file.SetAttribute("/calibration", "parameter_units", units);
  std::vector<int64_t> free_flags;
  std::vector<double> start, lower, upper;
  for (const ParameterSpec& spec : parameters.specs()) {
    free_flags.push_back(spec.free ? 1 : 0);
    start.push_back(spec.value);
    lower.push_back(spec.lower);
    upper.push_back(spec.upper);
  }
  file.WriteInts("/calibration/free", free_flags, "1");
  file.WriteDoubles("/calibration/start", start, units);
  file.WriteDoubles("/calibration/lower_bound", lower, units);
  file.WriteDoubles("/calibration/upper_bound", upper, units);

  // Data, with the dataset index of each point.
  std::vector<double> p, e, psi_s, psi_e, weight;
  std::vector<int64_t> dataset_index, kind;
  std::string sources;
  for (size_t d = 0; d < problem.datasets().size(); ++d) {
    for (const AsymptoticStatePoint& point : problem.datasets()[d].points) {
      p.push_back(point.mean_stress);
      e.push_back(point.void_ratio);
      psi_s.push_back(point.psi_sigma / kDegree);
      psi_e.push_back(point.psi_epsilon / kDegree);
      weight.push_back(point.weight);
      dataset_index.push_back(static_cast<int64_t>(d));
      kind.push_back(static_cast<int64_t>(point.kind));
      sources += point.source + "\n";
    }
  }
  const std::string data = "/data/";
  file.WriteDoubles(data + quantity::kMeanStress, p, "kPa");
  file.WriteDoubles(data + quantity::kVoidRatio, e, "1");
  file.WriteDoubles(data + quantity::kPsiSigma, psi_s, "deg");
  file.WriteDoubles(data + quantity::kPsiEpsilon, psi_e, "deg");
  file.WriteDoubles("/data/weight", weight, "1");
  file.WriteInts("/data/dataset", dataset_index, "1");
  file.WriteInts("/data/kind", kind, "1");
  file.SetAttribute("/data/kind", "codes",
                    "0 ncl, 1 csl, 2 compression, 3 extension, 4 asbs, 5 unloading");
  file.WriteString("/data/sources", sources);
  std::string dataset_names;
  for (const StateDataset& d : problem.datasets())
    dataset_names += d.name + " (" + d.origin + ")\n";
  file.WriteString("/data/datasets", dataset_names);

  for (const FitResult& fit : run.fits) WriteFitHdf5(fit, parameters, units, &file);
  file.WriteString("/summary", SummaryText(run));
  file.Commit();
}

namespace {

// states.csv: the data with the model's values and the ASBS normalisation by
// the fitted p_e*.
void WriteStatesCsv(const CalibrationProblem& problem, const FitResult& fit,
                    const ConstitutiveModel& model, const std::string& folder) {
  std::vector<std::vector<double>> columns(11);
  for (const PointResidual& r : fit.residuals) {
    const AsymptoticStatePoint& point = problem.datasets()[r.dataset].points[r.point];
    const double ln_v = std::log1p(point.void_ratio);
    const double pe = model.EquivalentPressure(point.void_ratio);
    const double q = 3.0 / std::sqrt(2.0) * std::tan(point.psi_sigma) * point.mean_stress;
    columns[0].push_back(static_cast<double>(point.kind));
    columns[1].push_back(r.dataset);
    columns[2].push_back(point.mean_stress);
    columns[3].push_back(std::log(point.mean_stress));
    columns[4].push_back(ln_v);
    columns[5].push_back(point.psi_sigma / kDegree);
    columns[6].push_back(point.psi_epsilon / kDegree);
    columns[7].push_back(r.psi_sigma_model / kDegree);
    columns[8].push_back(r.ln_volume_model);
    columns[9].push_back(point.mean_stress / pe);
    columns[10].push_back(q / pe);
  }
  WriteCsv(folder + "/states.csv",
           {"kind", "dataset", quantity::kMeanStress, "ln_p", quantity::kLnVolume,
            quantity::kPsiSigma, quantity::kPsiEpsilon, std::string("model_") + quantity::kPsiSigma,
            std::string("model_") + quantity::kLnVolume, "p_over_pe", "q_over_pe"},
           columns);
}

// model_curve.csv: the model's asymptotes, one row per stress direction.
void WriteModelCurve(const std::vector<Prediction>& curve, const std::string& folder) {
  std::vector<std::vector<double>> c(6);
  for (const Prediction& pr : curve) {
    const double eta = 3.0 * std::tan(pr.psi_sigma) / std::sqrt(2.0);
    c[0].push_back(pr.psi_sigma / kDegree);
    c[1].push_back(pr.psi_epsilon / kDegree);
    c[2].push_back(std::exp(pr.ln_ocr));
    c[3].push_back(pr.ln_ocr);
    c[4].push_back(std::exp(-pr.ln_ocr));
    c[5].push_back(eta * std::exp(-pr.ln_ocr));
  }
  WriteCsv(folder + "/model_curve.csv",
           {quantity::kPsiSigma, quantity::kPsiEpsilon, quantity::kOverconsolidation, "ln_ocr",
            "p_over_pe", "q_over_pe"},
           c);
}

// What the model lines span: the data's pressures and stretching directions.
struct PlotRange {
  double p_min = std::numeric_limits<double>::infinity(), p_max = 0, ln_p_sum = 0;
  int count = 0;
  std::set<double> directions = {0.0};  // ψ_ε (rad) of the data, and 0°

  explicit PlotRange(const CalibrationProblem& problem) {
    for (const StateDataset& d : problem.datasets()) {
      for (const AsymptoticStatePoint& point : d.points) {
        p_min = std::min(p_min, point.mean_stress);
        p_max = std::max(p_max, point.mean_stress);
        ln_p_sum += std::log(point.mean_stress);
        ++count;
        if (point.HasStretching()) directions.insert(point.psi_epsilon);
      }
    }
  }
  // The i-th of 21 values of ln p from p_min/2 to 2 p_max.
  double LnP(int i) const {
    return std::log(p_min / 2) + (std::log(p_max * 2) - std::log(p_min / 2)) * i / 20;
  }
};

// The comment line of model_lines.dat that names its columns.
std::string ModelLinesColumns() {
  return fmt::format("# columns (comma-separated): {}, ln_p, {}, {}\n", quantity::kPsiEpsilon,
                     quantity::kLnVolume, quantity::kPsiSigma);
}

// A model with a linear NCL: its asymptotes by stress direction and its lines
// in ln(1+e)-ln p, one gnuplot block per distinct ψ_ε of the data (NCL
// first), spanning the data's pressure range.
void WriteStraightModelLines(const CalibrationProblem& problem, const FitResult& fit,
                             const PlotRange& range, const std::string& folder) {
  std::string why;
  const std::vector<double> list(range.directions.begin(), range.directions.end());
  const double n = fit.values[kNIntercept], lambda = fit.values[kLambdaStar];
  std::vector<Prediction> curve;
  if (!problem.predictor().Curve(fit.values, 400, &curve, &why)) {
    throw RuntimeError("cannot evaluate the fitted model's asymptotes: " + why);
  }
  WriteModelCurve(curve, folder);
  std::vector<Prediction> by_stretching, by_stress;
  if (!problem.predictor().Predict(fit.values, list, {}, &by_stretching, &by_stress, &why)) {
    throw RuntimeError("cannot evaluate the fitted model's asymptotes: " + why);
  }
  std::ostringstream out;
  out << "# model asymptotic lines ln(1+e) = N - lambda* ln(p OCR(psi_epsilon)); one block per "
         "psi_epsilon\n"
      << ModelLinesColumns();
  for (size_t k = 0; k < list.size(); ++k) {
    for (int i = 0; i <= 20; ++i) {
      const double ln_p = range.LnP(i);
      out << fmt::format("{:.6g},{:.8g},{:.8g},{:.6g}\n", list[k] / kDegree, ln_p,
                         n - lambda * (ln_p + by_stretching[k].ln_ocr),
                         by_stretching[k].psi_sigma / kDegree);
    }
    out << "\n\n";
  }
  WriteTextFileAtomically(folder + "/model_lines.dat", out.str());
}

// A model without a linear NCL (the sand): its states at the data's ψ_ε (and
// 0°, 90°) at the geometric-mean p, and its integrated paths at each ψ_ε.
void WriteCurvedModelLines(const CalibrationProblem& problem, const FitResult& fit,
                           const PlotRange& range, const std::string& folder) {
  std::string why;
  const std::vector<double> list(range.directions.begin(), range.directions.end());
  std::set<double> curve_directions = range.directions;
  curve_directions.insert(0.5 * kPi);
  const double p_mid = std::exp(range.ln_p_sum / std::max(1, range.count));
  std::vector<double> psi_list(curve_directions.begin(), curve_directions.end());
  std::vector<StatePrediction> states;
  if (!problem.predictor().PredictAtPressures(
          fit.values, psi_list, std::vector<double>(psi_list.size(), p_mid), &states, &why)) {
    throw RuntimeError("cannot evaluate the fitted sand model's states: " + why);
  }
  std::vector<Prediction> curve;
  for (size_t k = 0; k < psi_list.size(); ++k) {
    Prediction pr;
    pr.psi_epsilon = psi_list[k];
    pr.psi_sigma = states[k].psi_sigma;
    pr.ln_ocr = states[k].ln_ocr;
    curve.push_back(pr);
  }
  std::sort(curve.begin(), curve.end(),
            [](const Prediction& a, const Prediction& b) { return a.psi_sigma < b.psi_sigma; });
  WriteModelCurve(curve, folder);
  std::ostringstream out;
  out << fmt::format(
             "# sand model: states along proportional stretching at each psi_epsilon "
             "(integrated, not straight lines); model_curve.csv holds them at p = {:.6g} kPa\n",
             p_mid)
      << ModelLinesColumns();
  for (double psi : list) {
    std::vector<double> pressures;
    for (int i = 0; i <= 20; ++i) pressures.push_back(std::exp(range.LnP(i)));
    if (!problem.predictor().PredictAtPressures(
            fit.values, std::vector<double>(pressures.size(), psi), pressures, &states, &why)) {
      throw RuntimeError("cannot evaluate the fitted sand model's paths: " + why);
    }
    for (size_t i = 0; i < pressures.size(); ++i) {
      out << fmt::format("{:.6g},{:.8g},{:.8g},{:.6g}\n", psi / kDegree, std::log(pressures[i]),
                         states[i].ln_volume, states[i].psi_sigma / kDegree);
    }
    out << "\n\n";
  }
  WriteTextFileAtomically(folder + "/model_lines.dat", out.str());
}

}  // namespace

void WritePlotData(const CalibrationRun& run, const FitResult& fit, const std::string& folder) {
  std::filesystem::create_directories(folder);
  const CalibrationProblem& problem = *run.problem;
  std::string why;
  const std::unique_ptr<ConstitutiveModel> model =
      MakeModel(problem.parameters().kind(), fit.values, &why);
  if (!model) throw RuntimeError("cannot make the fitted model: " + why);
  WriteStatesCsv(problem, fit, *model, folder);
  const PlotRange range(problem);
  if (problem.parameters().traits().linear_ncl) {
    WriteStraightModelLines(problem, fit, range, folder);
  } else {
    WriteCurvedModelLines(problem, fit, range, folder);
  }
  // Profiles and the front of an earlier run do not stay behind.
  for (const char* stale :
       {"profiles.csv", "profile_parameters.csv", "pareto.csv", "profiles.png", "pareto.png"}) {
    std::filesystem::remove(folder + "/" + stale);
  }
  if (!run.profiles.empty()) {
    WriteTextFileAtomically(folder + "/profiles.csv", ProfilesCsv(run.profiles));
    WriteTextFileAtomically(folder + "/profile_parameters.csv", ProfileParametersCsv(run.profiles));
  }
  if (run.pareto.computed()) {
    WriteTextFileAtomically(folder + "/pareto.csv", ParetoCsv(run.pareto, problem.parameters()));
  }
  WritePathPlotData(problem, fit.values, folder);
}

namespace {

// The model's ASBS counts as beyond p/p_e* = 1 (OCR < 1) past this fraction:
// the hypoplastic clay's surface itself bulges by ~1e-3 near the isotropic
// axis (London clay: OCR 0.9997 at psi_epsilon = 11 deg).
constexpr double kAsbsTolerance = 0.01;

// κ* < λ* (models with a linear NCL): fitted, and the data's own slopes.
void CheckSlopes(const CalibrationRun& run, const std::vector<double>& v,
                 std::vector<Finding>* findings) {
  if (!(v[kKappaStar] < v[kLambdaStar])) {
    findings->push_back({"kappa_not_below_lambda",
                         fmt::format("kappa* = {:.4g} >= lambda* = {:.4g}: unloading would be "
                                     "as steep as the NCL",
                                     v[kKappaStar], v[kLambdaStar]),
                         /*inadmissible=*/true});
  }
  const StartingValues& sv = run.starting_values;
  if (sv.kappa_star.from_data && sv.lambda_star.from_data &&
      !(sv.kappa_star.value < sv.lambda_star.value)) {
    findings->push_back(
        {"kappa_not_below_lambda",
         fmt::format("the data's unloading slope kappa* = {:.4g} is not below their NCL slope "
                     "lambda* = {:.4g} (no model with kappa* < lambda* fits both)",
                     sv.kappa_star.value, sv.lambda_star.value)});
  }
}

// The model's own ASBS (models with a linear NCL): OCR >= 1 on compression
// asymptotes, closed, inside p/p_e* <= 1.
void CheckModelAsbs(const CalibrationProblem& problem, const std::vector<double>& v,
                    std::vector<Finding>* findings) {
  std::string why;
  std::vector<Prediction> curve;
  if (!problem.predictor().Curve(v, 200, &curve, &why)) {
    findings->push_back(
        {"asbs_outside", "the model's ASBS cross-section is not closed: " + why, true});
    return;
  }
  double worst_ocr = std::numeric_limits<double>::infinity(), worst_psi = 0;
  double widest = 0, widest_psi = 0;
  int missing = 0;
  for (const Prediction& pr : curve) {
    if (!std::isfinite(pr.ln_ocr) || !std::isfinite(pr.psi_epsilon)) {
      ++missing;
      continue;
    }
    if (pr.psi_epsilon >= -1e-9 && pr.psi_epsilon <= 0.5 * kPi + 1e-9 &&
        pr.ln_ocr < std::log(worst_ocr)) {
      worst_ocr = std::exp(pr.ln_ocr);
      worst_psi = pr.psi_epsilon;
    }
    if (std::exp(-pr.ln_ocr) > widest) {
      widest = std::exp(-pr.ln_ocr);
      widest_psi = pr.psi_sigma;
    }
  }
  if (worst_ocr < 1 - kAsbsTolerance) {
    findings->push_back(
        {"ocr_below_one",
         fmt::format("the model's compression asymptote at psi_epsilon = {:.3g} deg has OCR = "
                     "{:.4g} < 1",
                     worst_psi / kDegree, worst_ocr),
         true});
  }
  if (missing > 0) {
    findings->push_back(
        {"asbs_outside",
         fmt::format("the model's ASBS cross-section is not closed: {} of {} stress directions "
                     "have no asymptote",
                     missing, curve.size()),
         true});
  }
  if (widest > 1 + kAsbsTolerance) {
    findings->push_back(
        {"asbs_outside",
         fmt::format("the model's ASBS cross-section reaches p/p_e* = {:.4g} > 1 (at psi_sigma "
                     "= {:.3g} deg)",
                     widest, widest_psi / kDegree),
         true});
  }
}

// ln OCR at the critical state: the model's per CSL state, and the data's own
// (the study table's) where every CSL state has one.
struct CriticalStateOcrs {
  std::vector<double> data, model;
};

// The data against the fitted NCL: ln OCR = ln(p_e*(e)/p), uncertainty in
// ln p from that of ln(1+e) through the NCL slope (λ*, or the sand's local
// slope). Collects the critical states' OCRs on the way.
CriticalStateOcrs CheckStatesAgainstNcl(const CalibrationProblem& problem, const FitResult& fit,
                                        const ConstitutiveModel& model,
                                        std::vector<Finding>* findings) {
  const std::vector<double>& v = fit.values;
  const bool linear_ncl = problem.parameters().traits().linear_ncl;
  int ocr_low = 0, beyond = 0;
  double ocr_low_worst = 1, beyond_worst = 1;
  CriticalStateOcrs csl;
  for (const PointResidual& r : fit.residuals) {
    const AsymptoticStatePoint& point = problem.datasets()[r.dataset].points[r.point];
    if (!point.IsAsymptotic()) continue;
    const double pe = model.EquivalentPressure(point.void_ratio);
    const double ocr = pe / point.mean_stress;
    const double slope = linear_ncl ? v[kLambdaStar] : 0.0;
    double margin = 0;
    if (linear_ncl) {
      margin = std::exp(-2 * point.ln_volume_uncertainty / slope);
    } else {
      // d ln p_e / d ln(1+e) of e_i(p_e) by a difference.
      const double e2 = std::expm1(std::log1p(point.void_ratio) + point.ln_volume_uncertainty);
      const double pe2 = model.EquivalentPressure(e2);
      margin = pe2 > 0 && pe > 0 ? std::min(1.0, std::pow(pe2 / pe, 2.0)) : 1.0;
    }
    const bool below = ocr < margin;
    if (below && (point.kind == StateKind::kNcl || point.kind == StateKind::kCompression)) {
      ++ocr_low;
      ocr_low_worst = std::min(ocr_low_worst, ocr);
    } else if (below) {
      ++beyond;
      beyond_worst = std::min(beyond_worst, ocr);
    }
    if (point.kind == StateKind::kCsl && std::isfinite(r.ln_ocr_model)) {
      csl.model.push_back(r.ln_ocr_model);
      if (std::isfinite(point.source_ocr)) csl.data.push_back(std::log(point.source_ocr));
    }
  }
  if (ocr_low > 0) {
    findings->push_back(
        {"ocr_below_one", fmt::format("{} NCL/compression states lie above the fitted NCL by more "
                                      "than twice their uncertainty (OCR down to {:.4g} < 1)",
                                      ocr_low, ocr_low_worst)});
  }
  if (beyond > 0) {
    findings->push_back(
        {"asbs_outside", fmt::format("{} states lie beyond the fitted model's p/p_e* = 1 by more "
                                     "than twice their uncertainty (p/p_e* up to {:.4g})",
                                     beyond, 1.0 / beyond_worst)});
  }
  return csl;
}

// OCR at the critical state: the data's own (study table) or against the
// data's NCL fit (starting values), against the model's.
void CheckCriticalStateOcr(const CalibrationRun& run, CriticalStateOcrs csl,
                           std::vector<Finding>* findings, std::vector<std::string>* diagnosis) {
  if (csl.model.empty()) return;
  const CalibrationProblem& problem = *run.problem;
  const ModelTraits& traits = problem.parameters().traits();
  std::string against = "the study table's own OCR";
  if (csl.data.size() != csl.model.size()) {
    csl.data.clear();
    const StartingValues& sv = run.starting_values;
    // A straight NCL fit is the reference of the models with a linear NCL
    // only (the sand's e_i is curved in ln(1+e)-ln p).
    if (traits.linear_ncl && sv.lambda_star.from_data && sv.n_intercept.from_data &&
        sv.lambda_star.points >= 2) {
      for (const StateDataset& d : problem.datasets()) {
        for (const AsymptoticStatePoint& point : d.points) {
          if (point.kind != StateKind::kCsl) continue;
          csl.data.push_back((sv.n_intercept.value - std::log1p(point.void_ratio)) /
                                 sv.lambda_star.value -
                             std::log(point.mean_stress));
        }
      }
      against = "the OCR against the data's own NCL fit";
    }
  }
  if (csl.data.empty()) return;
  const double dem = std::exp(Mean(csl.data)), fitted = std::exp(Mean(csl.model));
  diagnosis->push_back(
      fmt::format("critical state: data OCR {:.3g} ({}), model OCR {:.3g}", dem, against, fitted));
  if (std::abs(std::log(dem / fitted)) > std::log(1.25)) {
    const std::string model_ocr =
        std::string(traits.critical_state_ocr).empty()
            ? ""
            : fmt::format(" ({} for {})", traits.critical_state_ocr, traits.title);
    findings->push_back(
        {"csl_ocr_mismatch",
         fmt::format("the data put the CSL at OCR = {:.3g} ({}, mean of {} states), the "
                     "model at OCR = {:.3g}{}: the model cannot place its CSL and NCL as "
                     "the data do",
                     dem, against, csl.data.size(), fitted, model_ocr)});
  }
}

// Structural misfit: per kind, the mean residuals against twice the states'
// mean uncertainty; one diagnosis line per kind.
void DiagnoseStructuralMisfit(const CalibrationProblem& problem, const FitResult& fit,
                              std::vector<Finding>* findings, std::vector<std::string>* diagnosis) {
  for (StateKind k : {StateKind::kNcl, StateKind::kCsl, StateKind::kCompression,
                      StateKind::kExtension, StateKind::kAsbs}) {
    std::vector<double> dv, dpsi, uv, upsi;
    int positive_v = 0, positive_psi = 0;
    for (const PointResidual& r : fit.residuals) {
      const AsymptoticStatePoint& point = problem.datasets()[r.dataset].points[r.point];
      if (point.kind != k || !point.IsFitted()) continue;
      if (std::isfinite(r.ln_volume_residual)) {
        dv.push_back(r.ln_volume_residual);
        uv.push_back(point.ln_volume_uncertainty);
        positive_v += r.ln_volume_residual > 0 ? 1 : 0;
      }
      if (std::isfinite(r.psi_sigma_residual_deg)) {
        dpsi.push_back(r.psi_sigma_residual_deg);
        upsi.push_back(point.psi_sigma_uncertainty / kDegree);
        positive_psi += r.psi_sigma_residual_deg > 0 ? 1 : 0;
      }
    }
    if (dv.empty()) continue;
    const double mv = Mean(dv), mpsi = Mean(dpsi);
    std::string line =
        fmt::format("{}: {} states, mean model - data d_ln(1+e) {:+.4g} ({} of {} positive)",
                    ToString(k), dv.size(), mv, positive_v, dv.size());
    if (!dpsi.empty()) {
      line += fmt::format(", d_psi_sigma {:+.3g} deg ({} of {} positive)", mpsi, positive_psi,
                          dpsi.size());
    }
    diagnosis->push_back(line);
    const bool volume = std::abs(mv) > 2 * Mean(uv);
    const bool stress = !dpsi.empty() && std::abs(mpsi) > 2 * Mean(upsi);
    if (volume || stress) {
      findings->push_back(
          {"structural_misfit",
           fmt::format("{}: the model is systematically {}{}{} (more than twice the states' mean "
                       "uncertainty)",
                       ToString(k),
                       volume ? fmt::format("{} in ln(1+e) by {:.3g}", mv > 0 ? "above" : "below",
                                            std::abs(mv))
                              : "",
                       volume && stress ? " and " : "",
                       stress ? fmt::format("{} in psi_sigma by {:.3g} deg",
                                            mpsi > 0 ? "above" : "below", std::abs(mpsi))
                              : "")});
    }
  }
}

}  // namespace

std::vector<Finding> CheckAdmissibility(const CalibrationRun& run, const FitResult& fit,
                                        std::vector<std::string>* diagnosis) {
  std::vector<Finding> findings;
  const CalibrationProblem& problem = *run.problem;
  std::string why;
  const std::unique_ptr<ConstitutiveModel> model =
      MakeModel(problem.parameters().kind(), fit.values, &why);
  if (!model) {
    findings.push_back(
        {"invalid_model", "the fitted parameters do not make a model: " + why, true});
    return findings;
  }
  if (problem.parameters().traits().linear_ncl) {
    CheckSlopes(run, fit.values, &findings);
    CheckModelAsbs(problem, fit.values, &findings);
  }
  const CriticalStateOcrs csl = CheckStatesAgainstNcl(problem, fit, *model, &findings);
  CheckCriticalStateOcr(run, csl, &findings, diagnosis);
  DiagnoseStructuralMisfit(problem, fit, &findings, diagnosis);
  return findings;
}

std::string ParametersCsv(const CalibrationRun& run, const FitResult& fit) {
  std::string csv =
      "parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile,"
      "units\n";
  const std::vector<ParameterSpec>& specs = run.problem->parameters().specs();
  auto number = [](double x) {
    return std::isfinite(x) ? fmt::format("{:.10g}", x) : std::string();
  };
  for (size_t i = 0; i < specs.size(); ++i) {
    double se = std::nan(""), lo = std::nan(""), hi = std::nan("");
    for (size_t k = 0; k < fit.free_indices.size() && k < fit.standard_errors.size(); ++k) {
      if (fit.free_indices[k] == static_cast<int>(i) && fit.Reported(k)) {
        se = fit.standard_errors[k];
        lo = fit.lower_95[k];
        hi = fit.upper_95[k];
      }
    }
    const ParameterStatus status = i < run.status.size() ? run.status[i] : ParameterStatus::kFitted;
    std::string profile_low, profile_high, profile;
    for (const ParameterProfile& p : run.profiles.profiles) {
      if (p.parameter != static_cast<int>(i)) continue;
      profile_low = number(p.lower);
      profile_high = number(p.upper);
      profile = p.flat() ? "flat" : "determined";
    }
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", specs[i].name, number(fit.values[i]),
                       number(se), number(lo), number(hi), ToString(status), profile_low,
                       profile_high, profile, specs[i].units);
  }
  return csv;
}

std::string WarningsText(const CalibrationRun& run) {
  std::string text;
  auto add = [&text](const std::string& code, std::string message) {
    for (char& c : message) c = c == '\n' ? ' ' : c;
    text += code + ": " + message + "\n";
  };
  for (const Finding& f : run.findings) add(f.code, f.message);
  if (run.rate.MostlyRateAffected()) add("rate_affected", run.rate.Warning());
  for (const std::string& u : run.undetermined) add("undetermined", u);
  for (const std::string& f : run.freed) add("freed", f);
  if (const FitResult* kept = run.kept_fit()) {
    for (const std::string& w : kept->warnings) add("fit", w);
    if (!kept->summary.success()) add("fit_failed", kept->summary.Report());
  }
  for (const StateDataset& d : run.problem->datasets()) {
    for (const std::string& w : d.warnings) add("dataset", d.name + ": " + w);
  }
  for (const ParameterProfile& p : run.profiles.profiles) {
    if (p.flat()) add("profile_flat", p.Text() + " (its profile likelihood, profiles.csv)");
  }
  for (const ProfileRestart& restart : run.restarts) add("profile_refit", restart.Text());
  for (const std::string& w : run.profiles.warnings) {
    const size_t colon = w.find(": ");
    add(w.substr(0, colon), w.substr(colon + 2));
  }
  for (const std::string& w : run.pareto.warnings) add("pareto", w.substr(w.find(": ") + 2));
  return text;
}

std::string ModelToml(const CalibrationRun& run, const FitResult& fit) {
  const ModelKind kind = run.problem->parameters().kind();
  double p_min = std::numeric_limits<double>::infinity(), p_max = 0;
  for (const StateDataset& d : run.problem->datasets()) {
    for (const AsymptoticStatePoint& point : d.points) {
      p_min = std::min(p_min, point.mean_stress);
      p_max = std::max(p_max, point.mean_stress);
    }
  }
  if (!(p_min > 0 && std::isfinite(p_max))) p_min = 100, p_max = 1000;
  std::string s = fmt::format(
      "# granasym calibration of {} ({}); fitted by {}\n# Run it: granasym model run "
      "model.toml --out model_run.h5\n",
      ToString(kind), run.config.origin, fit.summary.fitter);
  s += ModelTomlBlock(kind, fit.values);
  s += fmt::format(
      "\n# An example element test: normally consolidated at the lowest p of the data, isotropic\n"
      "# compression to the highest, then isochoric shear towards the critical state.\n"
      "[initial]\nmean_stress_kpa = {:.6g}\nocr = 1.0\n\n[[stage]]\ntype = \"isotropic\"\n"
      "target_mean_stress_kpa = {:.6g}\n\n[[stage]]\ntype = \"isochoric\"\naxial_rate = 1.0\n"
      "duration_s = 0.2\n",
      p_min, std::max(p_max, 1.5 * p_min));
  return s;
}

}  // namespace granasym::calibration
