// Whole DEM paths: reading, resampling on strain and the model along them.
#include "calibration/path_dataset.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "constitutive/element_driver.h"
#include "dem/run_record_names.h"

namespace granasym::calibration {

namespace record = ::granasym::dem::record;

double PathSample::PsiSigma() const {
  return AxisymmetricStress{axial_stress, radial_stress}.psi();
}

void PathDataset::Validate() const {
  const std::string where = fmt::format("path dataset '{}' ({})", name, source);
  if (samples.size() < 3) {
    throw InputError(fmt::format("{}: {} samples; a path needs at least 3", where, samples.size()));
  }
  if (control == PathControl::kAuto || kind == PathKind::kAuto) {
    throw InputError(where + ": control and kind must be resolved (not auto) once read");
  }
  for (size_t k = 0; k < samples.size(); ++k) {
    const PathSample& s = samples[k];
    if (!(std::isfinite(s.axial_stress) && std::isfinite(s.radial_stress) && s.MeanStress() > 0 &&
          std::isfinite(s.void_ratio) && s.void_ratio > 0 && std::isfinite(s.axial_strain) &&
          std::isfinite(s.radial_strain))) {
      throw InputError(fmt::format(
          "{}: sample {}: sigma_a = {}, sigma_r = {} kPa, e = {}, eps_a = {}, eps_r = {}: "
          "stresses and strains must be finite, p > 0 and e > 0",
          where, k, s.axial_stress, s.radial_stress, s.void_ratio, s.axial_strain,
          s.radial_strain));
    }
    if (k > 0 && !(s.strain_path > samples[k - 1].strain_path)) {
      throw InputError(fmt::format(
          "{}: sample {}: the strain path s = {} does not grow (previous {}); a path must "
          "strain between its samples",
          where, k, s.strain_path, samples[k - 1].strain_path));
    }
  }
  if (!(weight >= 0)) {
    throw InputError(
        fmt::format("{}: weight = {} must be >= 0 (0: drawn, not fitted)", where, weight));
  }
  if (!(ln_p_uncertainty > 0 && psi_sigma_uncertainty > 0 && ln_volume_uncertainty > 0)) {
    throw InputError(fmt::format(
        "{}: ln_p_uncertainty = {}, psi_sigma_uncertainty_deg = {}, ln_1_plus_e_uncertainty "
        "= {}: each must be > 0",
        where, ln_p_uncertainty, psi_sigma_uncertainty / kDegree, ln_volume_uncertainty));
  }
}

PathControl DetectControl(const std::vector<PathSample>& samples) {
  double r_lo = samples.front().radial_stress, r_hi = r_lo, r_sum = 0;
  double a_lo = samples.front().axial_stress, a_hi = a_lo, a_sum = 0;
  for (const PathSample& s : samples) {
    r_lo = std::min(r_lo, s.radial_stress);
    r_hi = std::max(r_hi, s.radial_stress);
    a_lo = std::min(a_lo, s.axial_stress);
    a_hi = std::max(a_hi, s.axial_stress);
    r_sum += s.radial_stress;
    a_sum += s.axial_stress;
  }
  const double n = static_cast<double>(samples.size());
  const bool radial_held = r_hi - r_lo < 0.02 * std::abs(r_sum / n);
  const bool axial_moves = a_hi - a_lo > 0.10 * std::abs(a_sum / n);
  return radial_held && axial_moves ? PathControl::kDrained : PathControl::kStrain;
}

PathKind DetectKind(const std::vector<PathSample>& samples, PathControl control) {
  if (control == PathControl::kDrained) return PathKind::kDrained;
  double max_dv = 0, max_ds = 0;
  const PathSample& first = samples.front();
  for (const PathSample& s : samples) {
    const double dv =
        (s.axial_strain - first.axial_strain) + 2 * (s.radial_strain - first.radial_strain);
    const double ds =
        2.0 * ((s.axial_strain - first.axial_strain) - (s.radial_strain - first.radial_strain)) /
        3.0;
    max_dv = std::max(max_dv, std::abs(dv));
    max_ds = std::max(max_ds, std::abs(ds));
  }
  if (max_dv < 0.05 * max_ds) return PathKind::kIsochoric;
  if (max_ds < 0.05 * max_dv) return PathKind::kUnloadReload;
  return PathKind::kGeneral;
}

std::vector<PathSample> ResampleOnStrain(const std::vector<PathSample>& raw, int points,
                                         const std::vector<size_t>& keep) {
  GRANASYM_CHECK(raw.size() >= 2 && points >= 2) << "ResampleOnStrain: too few rows or points";
  const double s0 = raw.front().strain_path, s1 = raw.back().strain_path;
  std::vector<double> targets;
  for (int k = 0; k < points; ++k) targets.push_back(s0 + (s1 - s0) * k / (points - 1));
  for (size_t r : keep) {
    if (r < raw.size()) targets.push_back(raw[r].strain_path);
  }
  std::sort(targets.begin(), targets.end());
  // Values closer than 1e-9 of the whole path are one sample.
  std::vector<double> distinct;
  for (double t : targets) {
    if (distinct.empty() || t - distinct.back() > 1e-9 * std::max(s1 - s0, 1e-300)) {
      distinct.push_back(t);
    }
  }
  std::vector<PathSample> out;
  size_t i = 0;
  for (double t : distinct) {
    while (i + 2 < raw.size() && raw[i + 1].strain_path < t) ++i;
    const PathSample& a = raw[i];
    const PathSample& b = raw[std::min(i + 1, raw.size() - 1)];
    const double span = b.strain_path - a.strain_path;
    const double w = span > 0 ? std::clamp((t - a.strain_path) / span, 0.0, 1.0) : 0.0;
    const auto mix = [w](double x, double y) { return x + w * (y - x); };
    PathSample s;
    s.strain_path = t;
    s.axial_strain = mix(a.axial_strain, b.axial_strain);
    s.radial_strain = mix(a.radial_strain, b.radial_strain);
    s.axial_stress = mix(a.axial_stress, b.axial_stress);
    s.radial_stress = mix(a.radial_stress, b.radial_stress);
    // e through ln(1+e), linear in the strain like the volume.
    s.void_ratio = std::expm1(mix(std::log1p(a.void_ratio), std::log1p(b.void_ratio)));
    out.push_back(s);
  }
  return out;
}

bool PathReadOptions::IsValid(std::string* why) const {
  if (stages.empty()) {
    *why =
        "stages is empty: name the stages the path runs through (e.g. stages = [\"unload\", "
        "\"reload\"])";
    return false;
  }
  if (points < 3 || points > 10000) {
    *why = fmt::format("points = {} must be in [3, 10000]", points);
    return false;
  }
  if (!(weight >= 0)) {
    *why = fmt::format("weight = {} must be >= 0 (0: drawn, not fitted)", weight);
    return false;
  }
  if (!(ln_p_uncertainty > 0)) {
    *why = fmt::format("ln_p_uncertainty = {} must be > 0", ln_p_uncertainty);
    return false;
  }
  if (!(psi_sigma_uncertainty_deg > 0)) {
    *why = fmt::format("psi_sigma_uncertainty_deg = {} must be > 0", psi_sigma_uncertainty_deg);
    return false;
  }
  if (!(ln_volume_uncertainty > 0)) {
    *why = fmt::format("ln_1_plus_e_uncertainty = {} must be > 0", ln_volume_uncertainty);
    return false;
  }
  return true;
}

PathDataset ReadPathDem(const std::string& path, const std::string& name,
                        const PathReadOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) {
    throw InputError(fmt::format("path dataset '{}' ({}): {}", name, path, why));
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  const std::string series = record::kSeries;
  const std::vector<std::string> columns = {record::kColumnAxialStrain, record::kColumnRadialStrain,
                                            record::kColumnAxialStress, record::kColumnRadialStress,
                                            record::kColumnVoidRatio};
  for (const std::string& column : columns) {
    if (!file.Exists(series + "/" + column)) {
      throw InputError(fmt::format(
          "{}: no {}/{} column: not a granasym DEM result with strains and stresses (path "
          "dataset '{}')",
          path, series, column, name));
    }
  }
  if (!file.Exists(record::kStages)) {
    throw InputError(
        fmt::format("{}: not a granasym DEM result file (no {})", path, record::kStages));
  }
  // The stages by name, in file order.
  std::vector<std::string> groups, names;
  for (const std::string& stage : file.List(record::kStages)) {
    const std::string group = std::string(record::kStages) + "/" + stage;
    groups.push_back(group);
    names.push_back(file.ReadStringAttribute(group, record::kStageName));
  }
  std::vector<size_t> chosen;
  for (const std::string& wanted : options.stages) {
    const auto it = std::find(names.begin(), names.end(), wanted);
    if (it == names.end()) {
      std::string have;
      for (const std::string& n : names) have += (have.empty() ? "" : ", ") + n;
      throw InputError(fmt::format("{}: path dataset '{}': no stage named '{}' (stages: {})", path,
                                   name, wanted, have));
    }
    chosen.push_back(static_cast<size_t>(it - names.begin()));
  }
  for (size_t k = 1; k < chosen.size(); ++k) {
    if (chosen[k] != chosen[k - 1] + 1) {
      throw InputError(fmt::format(
          "{}: path dataset '{}': stages '{}' and '{}' are not consecutive in the file (a path "
          "runs through consecutive stages, in file order)",
          path, name, options.stages[k - 1], options.stages[k]));
    }
  }
  for (size_t c : chosen) {
    if (file.HasAttribute(groups[c], record::kStageFailed) &&
        file.ReadIntAttribute(groups[c], record::kStageFailed) != 0) {
      throw InputError(
          fmt::format("{}: path dataset '{}': the run failed in stage '{}'", path, name, names[c]));
    }
  }
  const std::vector<double> eps_a = file.ReadDoubles(series + "/" + record::kColumnAxialStrain);
  const std::vector<double> eps_r = file.ReadDoubles(series + "/" + record::kColumnRadialStrain);
  const std::vector<double> sig_a = file.ReadDoubles(series + "/" + record::kColumnAxialStress);
  const std::vector<double> sig_r = file.ReadDoubles(series + "/" + record::kColumnRadialStress);
  const std::vector<double> e = file.ReadDoubles(series + "/" + record::kColumnVoidRatio);
  // The first stage starts at the row before its first (the state it starts
  // from) where there is one.
  int64_t first = file.ReadIntAttribute(groups[chosen.front()], record::kStageFirstRow);
  if (first > 0) --first;
  const int64_t last = file.ReadIntAttribute(groups[chosen.back()], record::kStageLastRow);
  if (!(first >= 0 && last < static_cast<int64_t>(e.size()) && last - first >= 2)) {
    throw InputError(fmt::format(
        "{}: path dataset '{}': rows {} to {} of the stages (of {} rows) are not a path of at "
        "least 3 rows",
        path, name, first, last, e.size()));
  }
  std::vector<PathSample> raw;
  std::vector<size_t> keep;
  double s = 0.0;
  for (int64_t r = first; r <= last; ++r) {
    const size_t i = static_cast<size_t>(r);
    if (!raw.empty()) {
      const double da = eps_a[i] - raw.back().axial_strain;
      const double dr = eps_r[i] - raw.back().radial_strain;
      const double ds = std::sqrt(da * da + 2 * dr * dr);
      if (!(ds > 0)) continue;  // a row without strain (output twice)
      s += ds;
    }
    PathSample sample;
    sample.strain_path = s;
    sample.axial_strain = eps_a[i];
    sample.radial_strain = eps_r[i];
    sample.axial_stress = sig_a[i];
    sample.radial_stress = sig_r[i];
    sample.void_ratio = e[i];
    raw.push_back(sample);
  }
  for (size_t c : chosen) {
    const int64_t row = file.ReadIntAttribute(groups[c], record::kStageLastRow);
    // The raw index of the stage's last row (rows without strain dropped).
    size_t index = 0;
    double target_a = eps_a[static_cast<size_t>(row)], target_r = eps_r[static_cast<size_t>(row)];
    for (size_t k = 0; k < raw.size(); ++k) {
      if (raw[k].axial_strain == target_a && raw[k].radial_strain == target_r) index = k;
    }
    keep.push_back(index);
  }
  if (raw.size() < 3) {
    throw InputError(
        fmt::format("{}: path dataset '{}': fewer than 3 rows with strain", path, name));
  }
  PathDataset dataset;
  dataset.name = name;
  dataset.origin = path;
  dataset.source =
      fmt::format("{}:{} ({})", path, groups[chosen.front()], fmt::join(options.stages, ", "));
  dataset.samples = ResampleOnStrain(raw, options.points, keep);
  // A path said to be drained is under drained control unless said otherwise.
  dataset.control = options.control != PathControl::kAuto ? options.control
                    : options.kind == PathKind::kDrained  ? PathControl::kDrained
                                                          : DetectControl(dataset.samples);
  dataset.kind =
      options.kind == PathKind::kAuto ? DetectKind(dataset.samples, dataset.control) : options.kind;
  dataset.weight = options.weight;
  dataset.ln_p_uncertainty = options.ln_p_uncertainty;
  dataset.psi_sigma_uncertainty = options.psi_sigma_uncertainty_deg * kDegree;
  dataset.ln_volume_uncertainty = options.ln_volume_uncertainty;
  dataset.Validate();
  return dataset;
}

namespace {

// The model's start at (σ_a, σ_r, e), moved onto the SBS (OCR = 1) at the
// same stress where the DEM's e lies outside it.
bool StartState(const ConstitutiveModel& model, double axial, double radial, double void_ratio,
                ModelState* state, bool* moved, std::string* why) {
  Vector6 stress = Vector6::Zero();
  stress << -axial, -radial, -radial, 0, 0, 0;
  *state = model.MakeState(stress, void_ratio);
  *moved = false;
  if (model.IsAdmissibleStart(*state, why)) return true;
  const double p = (axial + 2 * radial) / 3.0;
  // Just inside the SBS: OCR 1 within rounding, or, where the stress is not
  // isotropic and OCR 1 lies outside a yield surface (Cam clay), the
  // smallest OCR of these that is inside.
  std::string last;
  for (const double ocr : {1.0 + 1e-9, 1.001, 1.01, 1.03, 1.1, 1.3, 2.0}) {
    const double e = model.VoidRatioForOcr(p, ocr);
    if (!(std::isfinite(e) && e > 0)) break;
    *state = model.MakeState(stress, e);
    *moved = true;
    if (model.IsAdmissibleStart(*state, &last)) return true;
  }
  *why += "; at OCR = 1 to 2 too: " + last;
  return false;
}

}  // namespace

bool PredictPath(const ConstitutiveModel& model, const PathDataset& path,
                 PathPrediction* prediction, std::string* why) {
  const std::vector<PathSample>& samples = path.samples;
  ModelState start;
  if (!StartState(model, samples[0].axial_stress, samples[0].radial_stress, samples[0].void_ratio,
                  &start, &prediction->start_moved, why)) {
    *why =
        fmt::format("path '{}': the DEM's initial state is outside the model: {}", path.name, *why);
    return false;
  }
  std::vector<LoadingStage> stages;
  for (size_t k = 1; k < samples.size(); ++k) {
    const double ds = samples[k].strain_path - samples[k - 1].strain_path;
    LoadingStage stage;
    stage.name = fmt::format("sample {}", k);
    stage.duration = ds;
    stage.output_points = 1;
    const double axial = (samples[k].axial_strain - samples[k - 1].axial_strain) / ds;
    if (path.control == PathControl::kDrained) {
      stage.control[1] = stage.control[2] = ComponentControl::kStressRate;
      const double radial = (samples[k].radial_stress - samples[k - 1].radial_stress) / ds;
      stage.rate = {axial, radial, radial, 0, 0, 0};
    } else {
      const double radial = (samples[k].radial_strain - samples[k - 1].radial_strain) / ds;
      stage.rate = {axial, radial, radial, 0, 0, 0};
    }
    stages.push_back(stage);
  }
  const ElementTest test(model, ElementTestOptions());
  const ElementTestResult result = test.Run(start, stages);
  // history[0] is the start, history[k] the end of stage k − 1.
  const size_t reached = std::min(result.history.size(), samples.size());
  prediction->mean_stress.assign(samples.size(), 0.0);
  prediction->psi_sigma.assign(samples.size(), 0.0);
  prediction->void_ratio.assign(samples.size(), 0.0);
  for (size_t k = 0; k < samples.size(); ++k) {
    const ElementTestRecord& r = result.history[std::min(k, reached - 1)];
    const AxisymmetricStress stress = RecordStress(r);
    prediction->mean_stress[k] = stress.mean();
    prediction->psi_sigma[k] = stress.psi();
    prediction->void_ratio[k] = r.void_ratio;
  }
  prediction->reached = static_cast<int>(reached);
  prediction->message = result.summary.success() ? "" : result.summary.message;
  if (reached < samples.size() && prediction->message.empty()) {
    prediction->message = fmt::format("stopped after {} of {} samples", reached, samples.size());
  }
  return true;
}

bool PredictIsotropicBranch(const ConstitutiveModel& model, double p0, double e0,
                            const std::vector<double>& targets, std::vector<double>* ln_volume,
                            std::string* why) {
  ModelState start;
  bool moved = false;
  if (!StartState(model, p0, p0, e0, &start, &moved, why)) return false;
  std::vector<LoadingStage> stages;
  for (double target : targets) {
    LoadingStage stage = LoadingStage::IsotropicToMeanStress(target, 1.0);
    stage.output_points = 1;
    stages.push_back(stage);
  }
  const ElementTest test(model, ElementTestOptions());
  const ElementTestResult result = test.Run(start, stages);
  if (!result.summary.success() || result.history.size() < targets.size() + 1) {
    *why = "isotropic branch: " + result.summary.message;
    return false;
  }
  ln_volume->clear();
  for (size_t k = 0; k < targets.size(); ++k) {
    ln_volume->push_back(std::log1p(result.history[k + 1].void_ratio));
  }
  return true;
}

}  // namespace granasym::calibration
