#include "analysis/figure_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "analysis/calibration_selections.h"
#include "common/hdf5_file.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"
#include "study/ensemble_path.h"
#include "study/study_folder.h"

namespace granasym::analysis::figures {
using study::CaseRecord;
using study::ReadCaseRecords;
namespace fs = std::filesystem;
namespace {

std::string Clean(std::string s) {
  for (char& c : s) {
    if (c == '\t' || c == '\n') c = ' ';
  }
  return s;
}

std::string Quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

double AttributeOr(const Hdf5File& file, const std::string& group, const char* name,
                   double fallback) {
  return file.HasAttribute(group, name) ? file.ReadDoubleAttribute(group, name) : fallback;
}

Path ReadPath(const TimeSeries& series, int64_t first, int64_t last, int half_rows) {
  Path path;
  if (series.rows() == 0 || last < first) return path;
  first = std::max<int64_t>(first, 0);
  last = std::min<int64_t>(last, static_cast<int64_t>(series.rows()) - 1);
  auto slice = [&](const char* name) {
    const std::vector<double>& v = series.Values(name);
    return std::vector<double>(v.begin() + first, v.begin() + last + 1);
  };
  path.p = slice(dem::record::kColumnMeanStress);
  path.ln_v = slice(dem::record::kColumnLnVolume);
  path.psi_sigma = slice(dem::record::kColumnPsiSigma);
  path.q = slice(dem::record::kColumnDeviator);
  path.i_dmin = slice(dem::record::kColumnInertialNumberDmin);
  path.i_dmax = slice(dem::record::kColumnInertialNumberDmax);
  const std::vector<double> eps_a = slice(dem::record::kColumnAxialStrain),
                            eps_r = slice(dem::record::kColumnRadialStrain);
  path.eps_s.resize(eps_a.size());
  path.eps_a.resize(eps_a.size());
  path.eps_r.resize(eps_a.size());
  for (size_t k = 0; k < eps_a.size(); ++k) {
    path.eps_a[k] = eps_a[k] - eps_a[0];
    path.eps_r[k] = eps_r[k] - eps_r[0];
    path.eps_s[k] = 2.0 * (path.eps_a[k] - path.eps_r[k]) / 3.0;
  }
  path.psi_epsilon = PathPsiEpsilon(eps_a, eps_r, half_rows);
  return path;
}

std::vector<CaseData> LoadCases(const std::string& directory, int half_rows) {
  std::vector<CaseData> cases;
  for (const CaseRecord& record : ReadCaseRecords(directory)) {
    const fs::path folder(record.directory);
    CaseData c;
    c.directory = record.directory;
    c.name = record.name;
    c.replicate = record.replicate;
    c.figures = record.figures;
    c.parent_name = record.parent_name();
    c.parent_stage = record.parent_stage;
    c.finished = record.Done().finished;
    if (c.finished) {
      const Hdf5File file = Hdf5File::OpenRead((folder / "result.h5").string());
      c.stages = dem::ReadStageRecords(file);
      for (size_t k = 0; k < c.stages.size(); ++k) {
        const std::string group = dem::StageGroup(k);
        c.stage_psi_epsilon.push_back(AttributeOr(file, group, dem::record::kStagePsiEpsilonDeg,
                                                  std::numeric_limits<double>::quiet_NaN()));
        c.stage_radial_stress.push_back(AttributeOr(file, group, dem::record::kStageRadialStressKpa,
                                                    std::numeric_limits<double>::quiet_NaN()));
        if (file.HasAttribute(group, dem::record::kStagePsiEpsilonDeg)) {
          c.rate_label = dem::StageRateLabel(file, k);
        }
      }
      c.time_step = dem::ReadSummary(file).time_step;
      if (!c.stages.empty()) {
        c.stops_at_asymptote = study::StopsAtAsymptote(file, c.stages, c.stages.size() - 1);
      }
      c.friction = dem::ReadMaterial(file).friction_angle;
      const TimeSeries series = TimeSeries::Read(file, dem::record::kSeries);
      if (!c.stages.empty()) {
        c.path = ReadPath(series, c.stages.front().first_row, c.stages.back().last_row, half_rows);
      }
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

// The NCL of a replicate and NCL case from DIR/asymptotic_states.h5.
std::map<std::pair<int, std::string>, NclLine> ReadNclFits(const std::string& directory) {
  std::map<std::pair<int, std::string>, NclLine> fits;
  const Hdf5File file = Hdf5File::OpenRead(directory + "/asymptotic_states.h5");
  if (!file.Exists("/ncl_fit/N")) return fits;
  const std::vector<int64_t> replicate = file.ReadInts("/ncl_fit/replicate");
  const std::vector<std::string> names = file.ReadStrings("/ncl_fit/case");
  const std::vector<double> n = file.ReadDoubles("/ncl_fit/N");
  const std::vector<double> lambda = file.ReadDoubles("/ncl_fit/lambda_star");
  for (size_t k = 0; k < replicate.size() && k < names.size() && k < n.size() && k < lambda.size();
       ++k) {
    if (std::isfinite(n[k]) && std::isfinite(lambda[k]) && lambda[k] > 0) {
      fits[{static_cast<int>(replicate[k]), names[k]}] = NclLine{n[k], lambda[k]};
    }
  }
  return fits;
}

std::string StudyNclName(const std::string& directory) {
  return study::StudyNclCase(directory).value_or("ncl");
}

}  // namespace

void ClassifySamples(Context* ctx) {
  std::map<std::pair<double, double>, int> count;
  bool found = false;
  for (const CaseData& c : ctx->cases) {
    if (!c.finished || !(c.time_step > 0)) continue;
    if (c.name == ctx->study_ncl) {
      ctx->main_friction = c.friction;
      ctx->main_time_step = c.time_step;
      found = true;
      break;
    }
    ++count[{c.friction, c.time_step}];
  }
  if (!found) {
    int most = 0;
    for (const auto& [key, n] : count) {
      if (n > most) {
        std::tie(ctx->main_friction, ctx->main_time_step) = key;
        most = n;
      }
    }
  }
  for (CaseData& c : ctx->cases) {
    if (!c.finished) continue;
    const bool same_friction = !(std::isfinite(c.friction) && std::isfinite(ctx->main_friction)) ||
                               std::abs(c.friction - ctx->main_friction) < 1e-9;
    c.sample = !same_friction                             ? Sample::kOtherFriction
               : c.time_step < 0.75 * ctx->main_time_step ? Sample::kFineStep
                                                          : Sample::kMain;
  }
  for (size_t k = 0; k < ctx->cases.size(); ++k) {
    ctx->by_name[{ctx->cases[k].replicate, ctx->cases[k].name}] = k;
  }
}

namespace {}  // namespace

void BlockFile::Add(const std::string& title, const std::vector<std::vector<double>>& rows) {
  std::string block;
  for (size_t k = 0; k < columns_.size(); ++k) block += columns_[k] + "\t";
  block += Clean(title) + "\n";
  int kept = 0;
  for (const std::vector<double>& row : rows) {
    if (row.empty()) {  // a break in the curve (one blank line)
      if (kept > 0) block += "\n";
      continue;
    }
    bool finite = true;
    for (double v : row) finite = finite && std::isfinite(v);
    if (!finite) continue;
    for (size_t k = 0; k < row.size(); ++k) {
      block += fmt::format("{}{:.8g}", k ? "\t" : "", row[k]);
    }
    block += "\n";
    ++kept;
  }
  if (kept == 0) return;
  text_ += (blocks_ ? "\n\n" : "") + block;
  ++blocks_;
  titles_ += (titles_.empty() ? "\"" : " \"") + Clean(title) + "\"";
}

void BlockFile::AddLabelled(const std::string& title, const std::vector<std::vector<double>>& rows,
                            const std::vector<std::string>& labels) {
  std::string block;
  for (size_t k = 0; k < columns_.size(); ++k) block += columns_[k] + "\t";
  block += Clean(title) + "\n";
  int kept = 0;
  for (size_t r = 0; r < rows.size() && r < labels.size(); ++r) {
    bool finite = true;
    for (double v : rows[r]) finite = finite && std::isfinite(v);
    if (!finite || rows[r].empty()) continue;
    for (size_t k = 0; k < rows[r].size(); ++k) {
      block += fmt::format("{}{:.8g}", k ? "\t" : "", rows[r][k]);
    }
    block += "\t" + Clean(labels[r]) + "\n";
    ++kept;
  }
  if (kept == 0) return;
  text_ += (blocks_ ? "\n\n" : "") + block;
  ++blocks_;
  titles_ += (titles_.empty() ? "\"" : " \"") + Clean(title) + "\"";
}

void BlockFile::Write(const std::string& path) const { WriteTextFileAtomically(path, text_); }

std::vector<std::vector<double>> Rows(std::initializer_list<const std::vector<double>*> columns) {
  std::vector<std::vector<double>> rows;
  const size_t n = (*columns.begin())->size();
  for (size_t k = 0; k < n; ++k) {
    std::vector<double> row;
    for (const std::vector<double>* column : columns) row.push_back((*column)[k]);
    rows.push_back(row);
  }
  return rows;
}

std::string Short(double v) {
  if (!std::isfinite(v)) return "?";
  const double a = std::abs(v);
  if (a >= 10) return fmt::format("{:.0f}", v);
  if (a >= 1) return fmt::format("{:.3g}", v);
  return fmt::format("{:.2g}", v);
}

std::string QuotedWords(const std::vector<std::string>& titles) {
  std::string words;
  for (const std::string& title : titles) {
    words += (words.empty() ? "\"" : " \"") + Clean(title) + "\"";
  }
  return words;
}

std::pair<double, double> AxisRange::Padded() const {
  if (log) {
    // At least a decade, so that the axis has a labelled power of ten.
    double a = std::log(lo), b = std::log(hi);
    const double pad = 0.08 * (b - a);
    a -= pad;
    b += pad;
    if (b - a < std::log(10.0)) {
      const double middle = 0.5 * (a + b);
      a = middle - 0.5 * std::log(10.0);
      b = middle + 0.5 * std::log(10.0);
    }
    return {std::exp(a), std::exp(b)};
  }
  const double pad = hi - lo > 1e-12 * std::max(1.0, std::abs(hi)) ? 0.08 * (hi - lo) : 1.0;
  return {lo - pad, hi + pad};
}

std::pair<double, double> AxisRange::Linear(double margin, double min_span) const {
  const double floor = min_span > 0 ? min_span : 1e-3 * std::max(1.0, std::abs(hi));
  const double span = std::max(hi - lo, floor);
  return {lo - margin * span, hi + margin * span};
}

std::pair<double, double> AxisRange::Logarithmic(double margin) const {
  const double a = std::log10(lo), b = std::log10(hi);
  const double span = std::max(b - a, 0.2);
  return {std::pow(10.0, a - margin * span), std::pow(10.0, b + margin * span)};
}

std::vector<std::vector<double>> LineRows(double n, double lambda, double p_lo, double p_hi,
                                          int intervals) {
  std::vector<std::vector<double>> rows;
  for (int k = 0; k <= intervals; ++k) {
    const double ln_p = std::log(p_lo) + (std::log(p_hi) - std::log(p_lo)) * k / intervals;
    rows.push_back({std::exp(ln_p), n - lambda * ln_p});
  }
  return rows;
}

const CaseData* FindCase(const std::vector<CaseData>& cases, int replicate,
                         const std::string& name) {
  for (const CaseData& c : cases) {
    if (c.replicate == replicate && c.name == name) return &c;
  }
  return nullptr;
}

Start StartOf(const std::vector<CaseData>& cases, const CaseData& c) {
  Start start;
  const CaseData* parent = FindCase(cases, c.replicate, c.parent_name);
  if (!parent || !parent->finished || parent->stages.empty()) return start;
  size_t k = parent->stages.size() - 1;
  for (size_t j = 0; j < parent->stages.size(); ++j) {
    if (parent->stages[j].name == c.parent_stage) k = j;
  }
  start.p_kpa = parent->stages[k].validity.final_mean_stress_kpa;
  const double psi = parent->stage_psi_epsilon[k];
  start.kind = std::abs(psi - 180) < 1 ? "OC" : std::abs(psi) < 1 ? "NC" : "";
  return start;
}

double Rounded(double v) {
  if (!(std::abs(v) > 0) || !std::isfinite(v)) return v;
  for (int digits : {1, 2}) {
    const double unit = std::pow(10.0, std::floor(std::log10(std::abs(v))) - (digits - 1));
    const double r = std::round(v / unit) * unit;
    if (digits == 2 || std::abs(r / v - 1) <= 0.05) return r;
  }
  return v;
}

std::string StartLabel(const std::vector<CaseData>& cases, const CaseData& c) {
  const Start start = StartOf(cases, c);
  if (!std::isfinite(start.p_kpa)) {
    return "from " + (c.parent_name.empty() ? "the sample" : c.parent_name);
  }
  return fmt::format("{}{}{} kPa", start.kind, start.kind.empty() ? "" : " ",
                     Short(Rounded(start.p_kpa)));
}

std::string DirectionLabel(const CaseData& c) {
  if (std::isfinite(c.RadialStress())) return fmt::format("σ_r = {} kPa", Short(c.RadialStress()));
  return fmt::format("ψ_ε = {}°", Short(c.NominalPsiEpsilon()));
}

bool UsableState(const StateRow& row) {
  return (row.status == TableStatus::kDetected || row.status == TableStatus::kDrifting) &&
         row.p_kpa > 0 && std::isfinite(row.ln_1_plus_e);
}

std::string StateLabel(const StateRow& row) {
  std::string text = fmt::format(
      "{} (replicate {}), stage {}\\n{}, {}\\np = {:.4g} kPa, e = {:.4f}\\nψ_ε = {:.1f}°, "
      "ψ_σ = {:.2f}°, q/p = {:.3f}",
      row.case_name, row.replicate, row.stage, ToString(row.kind), ToString(row.status), row.p_kpa,
      row.e, row.psi_epsilon_deg, row.psi_sigma_deg, row.q_over_p);
  if (row.inertial_number_dmax > 0) {
    text += fmt::format("\\nI(d_max) = {:.2g}", row.inertial_number_dmax);
  }
  if (!row.flags.empty()) text += "\\nflags: " + row.flags;
  return text;
}

MeanCasePath MeanPathOf(const std::vector<CaseData>& cases, const std::string& name) {
  std::vector<study::StagePath> paths;
  bool at_ends = true;
  for (const CaseData& c : cases) {
    if (c.name != name || !c.finished || c.path.p.size() < 2) continue;
    study::StagePath path;
    double strain = 0;
    for (size_t k = 0; k < c.path.p.size(); ++k) {
      if (k > 0) {
        const double da = c.path.eps_a[k] - c.path.eps_a[k - 1],
                     dr = c.path.eps_r[k] - c.path.eps_r[k - 1];
        strain += std::sqrt(da * da + 2 * dr * dr);
      }
      path.strain.push_back(strain);
      path.psi_sigma_deg.push_back(c.path.psi_sigma[k]);
      path.log_p.push_back(c.path.p[k] > 0 ? std::log(c.path.p[k])
                                           : std::numeric_limits<double>::quiet_NaN());
      path.log_volume.push_back(c.path.ln_v[k]);
      path.eps_a.push_back(c.path.eps_a[k]);
      path.eps_r.push_back(c.path.eps_r[k]);
      path.time.push_back(0);
    }
    at_ends = at_ends && c.stops_at_asymptote;
    paths.push_back(std::move(path));
  }
  MeanCasePath out;
  if (paths.size() < 2) return out;
  const double step = study::RowSpacing(paths);
  if (!(step > 0)) return out;
  const study::MeanPath mean = study::AveragePaths(
      paths, step, at_ends ? study::PathAlignment::kStageEnds : study::PathAlignment::kStageStarts);
  out.paths = mean.paths;
  for (size_t k = 0; k < mean.mean.strain.size(); ++k) {
    out.p.push_back(std::exp(mean.mean.log_p[k]));
    out.ln_v.push_back(mean.mean.log_volume[k]);
    out.psi_sigma.push_back(mean.mean.psi_sigma_deg[k]);
    out.psi_sigma_band.push_back(mean.psi_sigma_band_deg[k]);
    out.ln_v_band.push_back(mean.log_volume_band[k]);
    out.ln_p_band.push_back(mean.log_p_band[k]);
  }
  return out;
}

std::string ModelTitle(const std::string& name) {
  if (name == "hypoplastic_clay") return "hypoplastic clay (Mašín 2005)";
  if (name == "modified_cam_clay") return "Modified Cam clay";
  if (name == "hypoplastic_sand") return "hypoplastic sand (von Wolffersdorff 1996)";
  std::string title = name;
  std::replace(title.begin(), title.end(), '_', ' ');
  return title;
}

Context ReadContext(const std::string& directory, const FigureDataOptions& options) {
  Context ctx;
  ctx.directory = directory;
  ctx.data = (options.out.empty() ? directory : options.out) + "/figures/data";
  ctx.options = options;
  ctx.cases = LoadCases(directory, options.psi_epsilon_half_rows);
  ctx.states = study::WithoutEnsembleRows(study::ReadStateTable(directory));
  ctx.ncl_fits = ReadNclFits(directory);
  ctx.study_ncl = StudyNclName(directory);
  ClassifySamples(&ctx);
  std::vector<std::string> overlaid, absent;
  bool other = false;  // an overlay of the study's other selection
  for (const std::string& name : study::kFigureModels) {
    if (!options.settings.Overlays(name)) continue;
    // The study's default selection (calibration/<model>/), then the other
    // one where calibrated too, titled by its selection
    // (analysis/calibration_selections.h).
    bool any = false;
    const CalibrationSelection first = DefaultSelection(directory);
    for (CalibrationSelection selection :
         {first, first == CalibrationSelection::kAll ? CalibrationSelection::kQuasiStatic
                                                     : CalibrationSelection::kAll}) {
      const std::string folder =
          directory + "/" + SelectionFolder(directory, name, selection) + "/plot_data";
      if (!fs::exists(folder + "/model_curve.csv") || !fs::exists(folder + "/model_lines.dat")) {
        continue;
      }
      ctx.models.push_back(ReadModelOverlay(folder, name));
      if (selection != first) {
        ctx.models.back().title += " (" + SelectionTitle(directory, selection) + ")";
        other = true;
      }
      overlaid.push_back(ctx.models.back().title);
      any = true;
    }
    if (!any) absent.push_back(ModelTitle(name));
  }
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + v[k];
    return s;
  };
  ctx.models_note = overlaid.empty()
                        ? "No calibrated model is overlaid"
                        : "Models overlaid (DIR/calibration/<model>/plot_data" +
                              std::string(other ? ", the other selection's from "
                                                  "DIR/calibration/<selection>/<model>/plot_data"
                                                : "") +
                              "): " + join(overlaid);
  if (!absent.empty())
    ctx.models_note += "; not calibrated in this study, so not shown: " + join(absent);
  ctx.models_note += ".";
  return ctx;
}

namespace {
// A case of `cases`; a joined row ("a+b", the path convergence's) when both
// of the paths it joins are.
bool InCases(const std::set<std::string>& cases, const std::string& name) {
  const size_t plus = name.find('+');
  if (plus == std::string::npos) return cases.count(name) > 0;
  return cases.count(name.substr(0, plus)) > 0 && InCases(cases, name.substr(plus + 1));
}
}  // namespace

std::vector<const StateRow*> Context::Select(const StateSelection& selection) const {
  std::vector<const StateRow*> out;
  for (const StateRow& row : states) {
    if (!UsableState(row) || SampleOf(row) != selection.sample) continue;
    if (row.status == TableStatus::kDrifting && !selection.drifting) continue;
    if (!selection.kinds.empty() && std::find(selection.kinds.begin(), selection.kinds.end(),
                                              row.kind) == selection.kinds.end()) {
      continue;
    }
    if (!selection.cases.empty() && !InCases(selection.cases, row.case_name)) continue;
    if (!options.settings.IncludesCase(row.case_name)) continue;
    out.push_back(&row);
  }
  return out;
}

std::string StateSelection::Describe(const Context& ctx) const {
  std::string sample_text = sample == Sample::kMain ? "the study's own sample"
                            : sample == Sample::kOtherFriction
                                ? "the sample of other contact friction"
                                : "the sample of the finer time step";
  if (sample == Sample::kMain && std::isfinite(ctx.main_friction)) {
    sample_text +=
        fmt::format(" (φ = {} rad, Δt = {:.3g} s)", Short(ctx.main_friction), ctx.main_time_step);
  }
  std::string kinds_text;
  for (TableKind kind : kinds) {
    kinds_text += (kinds_text.empty() ? "" : ", ") + std::string(ToString(kind));
  }
  return "States shown: " + sample_text + (kinds_text.empty() ? "" : "; kinds " + kinds_text) +
         (drifting ? "; detected (filled) and still drifting at the stage end (open)"
                   : "; detected only") +
         "; gas, invalid and unfinished stages left out" +
         (ctx.options.settings.cases.empty() && ctx.options.settings.exclude_cases.empty()
              ? ""
              : "; only the cases the figure settings include") +
         ".";
}

FigureSpec Spec(const std::string& stem, const std::string& figure, const std::string& title,
                const std::string& caption, const std::string& script) {
  FigureSpec spec;
  spec.stem = stem;
  spec.figure = figure;
  spec.title = title;
  spec.caption = caption;
  spec.script = script;
  return spec;
}

FigureSpec NotDrawn(FigureSpec spec, const std::string& why) {
  spec.not_drawn = why;
  spec.caption += " Not drawn: " + why + ".";
  return spec;
}

void Set(FigureSpec* spec, const std::string& name, int value) {
  spec->variables.emplace_back(name, std::to_string(value));
}
void Set(FigureSpec* spec, const std::string& name, const std::string& value) {
  spec->variables.emplace_back(name, Quoted(value));
}
void SetNumber(FigureSpec* spec, const std::string& name, double value) {
  spec->variables.emplace_back(name, fmt::format("{:.6g}", value));
}

}  // namespace granasym::analysis::figures
