// Calibration runs, summaries, HDF5 records and plot data.
#include "calibration/calibration_report.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "calibration/csv_state_reader.h"
#include "calibration/dem_state_reader.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"

namespace granasym::calibration {

ModelParameters ChooseParameters(ModelKind kind, const std::vector<ParameterChoice>& choices,
                                 const StartingValues& start) {
  ModelParameters parameters = ModelParameters::Defaults(kind);
  std::vector<ParameterSpec>& specs = parameters.mutable_specs();
  auto from_data = [&specs](int index, const Estimate& e) {
    if (e.from_data) {
      specs[index].value = std::min(std::max(e.value, specs[index].lower), specs[index].upper);
    } else if (index == kKappaStar) {
      specs[index].value = e.value;
    }
  };
  from_data(kCriticalFrictionAngle, start.critical_friction_angle_deg);
  from_data(kLambdaStar, start.lambda_star);
  from_data(kKappaStar, start.kappa_star);
  from_data(kNIntercept, start.n_intercept);
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

CalibrationRun RunCalibration(const CalibrationConfig& config) {
  CalibrationRun run;
  run.config = config;
  std::vector<StateDataset> datasets;
  for (const DatasetConfig& d : config.datasets) {
    datasets.push_back(d.is_dem ? ReadStatesDem(d.path, d.name, d.dem)
                                : ReadStatesCsv(d.path, d.name, d.csv));
  }
  run.starting_values = EstimateStartingValues(datasets);
  ModelParameters parameters =
      ChooseParameters(config.model, config.parameters, run.starting_values);
  run.problem = std::make_unique<CalibrationProblem>(std::move(datasets), std::move(parameters),
                                                     config.predictor);
  if (config.method != FitMethod::kNlopt) {
    run.fits.push_back(CeresFitter(config.ceres).Fit(*run.problem));
  }
  if (config.method != FitMethod::kCeres) {
    run.fits.push_back(NloptFitter(config.nlopt).Fit(*run.problem));
  }
  if (run.fits.size() == 2) {
    const FitResult& a = run.fits[0];
    const FitResult& b = run.fits[1];
    double worst = 0;
    for (size_t k = 0; k < a.free_indices.size() && k < a.standard_errors.size(); ++k) {
      const int i = a.free_indices[k];
      if (std::isfinite(a.standard_errors[k]) && a.standard_errors[k] > 0) {
        worst = std::max(worst, std::abs(a.values[i] - b.values[i]) / a.standard_errors[k]);
      }
    }
    run.agreement_in_standard_errors = worst;
  }
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
  s += fmt::format("  {:<14} {:>12} {:>12} {:>26}  {}\n", "parameter", "value", "std. error",
                   "95 % interval", "units");
  for (size_t i = 0; i < parameters.specs().size(); ++i) {
    const ParameterSpec& spec = parameters.specs()[i];
    int k = -1;
    for (size_t j = 0; j < fit.free_indices.size(); ++j) {
      if (fit.free_indices[j] == static_cast<int>(i)) k = static_cast<int>(j);
    }
    if (k < 0 || fit.standard_errors.empty()) {
      s += fmt::format("  {:<14} {:>12.6g} {:>12} {:>26}  {}\n", spec.name, fit.values[i],
                       k < 0 ? "fixed" : "-", "", spec.units);
    } else {
      s += fmt::format("  {:<14} {:>12.6g} {:>12.3g}   [{:>10.6g}, {:>10.6g}]  {}\n", spec.name,
                       fit.values[i], fit.standard_errors[k], fit.lower_95[k], fit.upper_95[k],
                       spec.units);
    }
  }
  if (fit.correlation.rows() > 1) {
    s += "  correlation matrix (free parameters):\n";
    for (int r = 0; r < fit.correlation.rows(); ++r) {
      s += fmt::format("    {:<14}", parameters.specs()[fit.free_indices[r]].name);
      for (int c = 0; c < fit.correlation.cols(); ++c)
        s += fmt::format(" {:>7.3f}", fit.correlation(r, c));
      s += "\n";
    }
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
  std::string s =
      fmt::format("  {:<12} {:>10} {:>8} {:>9} {:>9} {:>10} {:>11}  {}\n", "kind", "p_kpa", "e",
                  "psi_eps", "psi_sig", "d_psi_deg", "d_ln(1+e)", "source");
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

std::string SummaryText(const CalibrationRun& run) {
  const CalibrationProblem& problem = *run.problem;
  std::string s =
      fmt::format("granasym calibration: {}\nmodel: {} (asymptotes: {})\n", run.config.origin,
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
  s += run.starting_values.Report() + "\n";
  for (const FitResult& fit : run.fits) s += "\n" + FitText(run, fit);
  if (run.fits.size() == 2) {
    s += fmt::format("\nceres vs nlopt: largest parameter difference {:.3g} standard errors\n",
                     run.agreement_in_standard_errors);
  }
  if (!run.fits.empty()) {
    s += "\nresiduals per point (" + run.fits.front().summary.fitter + "):\n" +
         PointsText(run, run.fits.front());
    s += "\nobjective history (" + run.fits.front().summary.fitter + ", best cost so far):\n";
    const std::vector<HistoryPoint>& h = run.fits.front().history;
    const size_t step = std::max<size_t>(1, h.size() / 20);
    for (size_t i = 0; i < h.size(); i += step) {
      s += fmt::format("  evaluation {:>7}  cost {:.8g}  {}\n", h[i].evaluation, h[i].cost,
                       h[i].stage);
    }
  }
  return s;
}

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
  file.SetAttribute("/calibration", "starting_values", run.starting_values.Report());
  if (run.fits.size() == 2) {
    file.SetAttribute("/calibration", "ceres_nlopt_largest_difference_in_standard_errors",
                      run.agreement_in_standard_errors);
  }
  std::string names, units;
  for (const ParameterSpec& spec : parameters.specs()) {
    names += (names.empty() ? "" : ",") + spec.name;
    units += (units.empty() ? "" : ",") + spec.units;
  }
  file.SetAttribute("/calibration", "parameter_names", names);
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
  file.WriteDoubles("/data/p_kpa", p, "kPa");
  file.WriteDoubles("/data/e", e, "1");
  file.WriteDoubles("/data/psi_sigma_deg", psi_s, "deg");
  file.WriteDoubles("/data/psi_epsilon_deg", psi_e, "deg");
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

  for (const FitResult& fit : run.fits) {
    std::string group = "/fits/" + fit.summary.fitter;
    for (char& c : group) c = (c == ':' || c == '+') ? '_' : c;
    file.CreateGroup(group);
    file.SetAttribute(group, "fitter", fit.summary.fitter);
    file.SetAttribute(group, "termination", ToString(fit.summary.termination));
    file.SetAttribute(group, "message", fit.summary.message);
    file.SetAttribute(group, "report", fit.summary.Report());
    file.SetAttribute(group, "iterations", int64_t{fit.summary.iterations});
    file.SetAttribute(group, "evaluations", int64_t{fit.summary.evaluations});
    file.SetAttribute(group, "initial_cost", fit.summary.initial_cost);
    file.SetAttribute(group, "final_cost", fit.summary.final_cost);
    file.SetAttribute(group, "wall_s", fit.summary.wall_seconds);
    file.SetAttribute(group, "residual_variance", fit.residual_variance);
    file.SetAttribute(group, "degrees_of_freedom", int64_t{fit.degrees_of_freedom});
    file.SetAttribute(group, "condition_number", fit.condition_number);
    std::string warnings;
    for (const std::string& w : fit.warnings) warnings += w + "\n";
    file.SetAttribute(group, "warnings", warnings);
    file.WriteDoubles(group + "/values", fit.values, units);
    std::vector<int64_t> free_index(fit.free_indices.begin(), fit.free_indices.end());
    file.WriteInts(group + "/free_index", free_index, "1");
    file.WriteDoubles(group + "/standard_errors", fit.standard_errors);
    file.WriteDoubles(group + "/lower_95", fit.lower_95);
    file.WriteDoubles(group + "/upper_95", fit.upper_95);
    const size_t n = fit.free_indices.size();
    std::vector<double> cov, cor;
    for (size_t r = 0; r < n; ++r) {
      for (size_t c = 0; c < n; ++c) {
        cov.push_back(fit.covariance.size() ? fit.covariance(r, c) : std::nan(""));
        cor.push_back(fit.correlation.size() ? fit.correlation(r, c) : std::nan(""));
      }
    }
    if (n > 0) {
      file.WriteMatrix(group + "/covariance", cov, n, n, "parameter units squared");
      file.WriteMatrix(group + "/correlation", cor, n, n, "1");
    }
    std::vector<double> hist_eval, hist_cost;
    for (const HistoryPoint& h : fit.history) {
      hist_eval.push_back(static_cast<double>(h.evaluation));
      hist_cost.push_back(h.cost);
    }
    file.WriteDoubles(group + "/history/evaluation", hist_eval, "1");
    file.WriteDoubles(group + "/history/cost", hist_cost, "1");
    std::vector<double> d_psi, d_v, m_psi, m_v, ln_ocr;
    for (const PointResidual& r : fit.residuals) {
      d_psi.push_back(r.psi_sigma_residual_deg);
      d_v.push_back(r.ln_volume_residual);
      m_psi.push_back(r.psi_sigma_model / kDegree);
      m_v.push_back(r.ln_volume_model);
      ln_ocr.push_back(r.ln_ocr_model);
    }
    file.WriteDoubles(group + "/residuals/psi_sigma_deg", d_psi, "deg");
    file.WriteDoubles(group + "/residuals/ln_1_plus_e", d_v, "1");
    file.WriteDoubles(group + "/model/psi_sigma_deg", m_psi, "deg");
    file.WriteDoubles(group + "/model/ln_1_plus_e", m_v, "1");
    file.WriteDoubles(group + "/model/ln_ocr", ln_ocr, "1");
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
      file.WriteDoubles(name, values);
      file.SetAttribute(name, "program", e.program);
      file.SetAttribute(name, "order", order);
    }
  }
  file.WriteString("/summary", SummaryText(run));
  file.Commit();
}

void WritePlotData(const CalibrationRun& run, const FitResult& fit, const std::string& folder) {
  std::filesystem::create_directories(folder);
  const CalibrationProblem& problem = *run.problem;
  const double n = fit.values[kNIntercept], lambda = fit.values[kLambdaStar];
  // Data with the model's values and the ASBS normalisation by the fitted p_e*.
  std::vector<std::vector<double>> columns(11);
  for (const PointResidual& r : fit.residuals) {
    const AsymptoticStatePoint& point = problem.datasets()[r.dataset].points[r.point];
    const double ln_v = std::log1p(point.void_ratio);
    const double pe = EquivalentPressure(point.void_ratio, n, lambda);
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
           {"kind", "dataset", "p_kpa", "ln_p", "ln_1_plus_e", "psi_sigma_deg", "psi_epsilon_deg",
            "model_psi_sigma_deg", "model_ln_1_plus_e", "p_over_pe", "q_over_pe"},
           columns);

  std::vector<Prediction> curve;
  std::string why;
  if (!problem.predictor().Curve(fit.values, 400, &curve, &why)) {
    throw RuntimeError("cannot evaluate the fitted model's asymptotes: " + why);
  }
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
           {"psi_sigma_deg", "psi_epsilon_deg", "ocr", "ln_ocr", "p_over_pe", "q_over_pe"}, c);

  // Model lines in ln(1+e)-ln p, one gnuplot block per distinct ψ_ε of the
  // data (NCL first), spanning the data's pressure range.
  double p_min = std::numeric_limits<double>::infinity(), p_max = 0;
  std::set<double> directions = {0.0};
  for (const StateDataset& d : problem.datasets()) {
    for (const AsymptoticStatePoint& point : d.points) {
      p_min = std::min(p_min, point.mean_stress);
      p_max = std::max(p_max, point.mean_stress);
      if (point.HasStretching()) directions.insert(point.psi_epsilon);
    }
  }
  std::vector<Prediction> by_stretching, by_stress;
  const std::vector<double> list(directions.begin(), directions.end());
  if (!problem.predictor().Predict(fit.values, list, {}, &by_stretching, &by_stress, &why)) {
    throw RuntimeError("cannot evaluate the fitted model's asymptotes: " + why);
  }
  std::ofstream out(folder + "/model_lines.dat");
  out << "# model asymptotic lines ln(1+e) = N - lambda* ln(p OCR(psi_epsilon)); one block per "
         "psi_epsilon\n# columns (comma-separated): psi_epsilon_deg, ln_p, ln_1_plus_e, "
         "psi_sigma_deg\n";
  for (size_t k = 0; k < list.size(); ++k) {
    for (int i = 0; i <= 20; ++i) {
      const double ln_p =
          std::log(p_min / 2) + (std::log(p_max * 2) - std::log(p_min / 2)) * i / 20;
      out << fmt::format("{:.6g},{:.8g},{:.8g},{:.6g}\n", list[k] / kDegree, ln_p,
                         n - lambda * (ln_p + by_stretching[k].ln_ocr),
                         by_stretching[k].psi_sigma / kDegree);
    }
    out << "\n\n";
  }
  if (!out) throw RuntimeError("cannot write " + folder + "/model_lines.dat");
}

}  // namespace granasym::calibration
