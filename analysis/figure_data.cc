#include "analysis/figure_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "analysis/rate_study.h"
#include "common/config.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/statistics.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "study/case_record.h"
#include "study/study_folder.h"

namespace granasym::analysis {
using study::CaseFolders;
using study::CaseRecord;
using study::FigureSet;
using study::ReadCaseRecords;
using study::ReadDone;
using study::ResultMismatch;
using study::TableKind;
using study::TableStatus;
namespace fs = std::filesystem;
namespace {

constexpr double kDegree = M_PI / 180.0;

// ---------------------------------------------------------------- data files

// A data file of blocks: a header (column names, then the legend title) and rows.
class BlockFile {
 public:
  explicit BlockFile(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  // Adds a block; rows with a non-finite value are dropped; an empty block
  // is not written (gnuplot warns about blocks without points).
  void Add(const std::string& title, const std::vector<std::vector<double>>& rows) {
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
  int blocks() const { return blocks_; }
  // The blocks' titles as gnuplot words ("a b" "c"), for legend entries of
  // blocks drawn with `pt variable` (whose own key sample is a dot).
  const std::string& titles() const { return titles_; }
  void Write(const std::string& path) const { WriteTextFileAtomically(path, text_); }

 private:
  static std::string Clean(std::string s) {
    for (char& c : s) {
      if (c == '\t' || c == '\n') c = ' ';
    }
    return s;
  }
  std::vector<std::string> columns_;
  std::string text_, titles_;
  int blocks_ = 0;
};

std::string Quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// A number for a legend: 3 significant digits, no exponent for kPa values.
std::string Short(double v) {
  if (!std::isfinite(v)) return "?";
  const double a = std::abs(v);
  if (a >= 10) return fmt::format("{:.0f}", v);
  if (a >= 1) return fmt::format("{:.3g}", v);
  return fmt::format("{:.2g}", v);
}

// ---------------------------------------------------------------- cases

struct Path {
  std::vector<double> p, ln_v, psi_sigma, psi_epsilon, eps_s, q, i_dmin, i_dmax;
  bool empty() const { return p.empty(); }
};

struct CaseData {
  std::string name, directory, parent_name, parent_stage;
  int replicate = 1;
  FigureSet figures;
  bool finished = false;
  // From the result.
  std::vector<dem::StageRecord> stages;
  std::vector<double> stage_psi_epsilon;  // nominal ψ_ε per stage (NaN: not a strain path)
  std::vector<double> stage_radial_stress;
  double time_step = 0;
  double friction = std::numeric_limits<double>::quiet_NaN();
  Path path;  // the case's own rows
  bool Serves(const std::string& figure) const { return figures.Contains(figure); }
  double NominalPsiEpsilon() const {
    for (double v : stage_psi_epsilon) {
      if (std::isfinite(v)) return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
};

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
  for (size_t k = 0; k < eps_a.size(); ++k) {
    path.eps_s[k] = 2.0 * ((eps_a[k] - eps_a[0]) - (eps_r[k] - eps_r[0])) / 3.0;
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
      }
      c.time_step = dem::ReadSummary(file).time_step;
      const TimeSeries series = TimeSeries::Read(file, dem::record::kSeries);
      if (!c.stages.empty()) {
        c.path = ReadPath(series, c.stages.front().first_row, c.stages.back().last_row, half_rows);
      }
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

const CaseData* FindCase(const std::vector<CaseData>& cases, int replicate,
                         const std::string& name) {
  for (const CaseData& c : cases) {
    if (c.replicate == replicate && c.name == name) return &c;
  }
  return nullptr;
}

// "NC 100 kPa", "OC 20 kPa" (unloaded from the NCL), from the parent stage.
std::string StartLabel(const std::vector<CaseData>& cases, const CaseData& c) {
  const CaseData* parent = FindCase(cases, c.replicate, c.parent_name);
  if (!parent || !parent->finished)
    return "from " + (c.parent_name.empty() ? "the sample" : c.parent_name);
  size_t k = parent->stages.size() - 1;
  for (size_t j = 0; j < parent->stages.size(); ++j) {
    if (parent->stages[j].name == c.parent_stage) k = j;
  }
  // Two significant digits: the stop condition overshoots its target slightly.
  double p = parent->stages[k].validity.final_mean_stress_kpa;
  if (p > 0) {
    const double unit = std::pow(10.0, std::floor(std::log10(p)) - 1);
    p = std::round(p / unit) * unit;
  }
  const double psi = parent->stage_psi_epsilon[k];
  const std::string kind = std::abs(psi - 180) < 1 ? "OC" : std::abs(psi) < 1 ? "NC" : "";
  return fmt::format("{}{}{} kPa", kind, kind.empty() ? "" : " ", Short(p));
}

std::string DirectionLabel(const CaseData& c) {
  for (size_t k = 0; k < c.stages.size(); ++k) {
    if (std::isfinite(c.stage_radial_stress[k])) {
      return fmt::format("σ_r = {} kPa", Short(c.stage_radial_stress[k]));
    }
  }
  return fmt::format("ψ_ε = {}°", Short(c.NominalPsiEpsilon()));
}

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

bool UsableState(const StateRow& row) {
  return (row.status == TableStatus::kDetected || row.status == TableStatus::kDrifting) &&
         row.p_kpa > 0 && std::isfinite(row.ln_1_plus_e);
}

std::string ModelTitle(const std::string& name) {
  if (name == "hypoplastic_clay") return "hypoplastic clay (Mašín 2005)";
  if (name == "modified_cam_clay") return "Modified Cam clay";
  if (name == "hypoplastic_sand") return "hypoplastic sand (von Wolffersdorff 1996)";
  std::string title = name;
  std::replace(title.begin(), title.end(), '_', ' ');
  return title;
}

struct Context {
  std::string directory, data;  // DIR, DIR/figures/data
  FigureDataOptions options;
  std::vector<CaseData> cases;
  std::vector<StateRow> states;
  std::map<std::pair<int, std::string>, NclLine> ncl_fits;
  std::string study_ncl;
  std::vector<ModelOverlay> models;
  std::string models_note;  // which models are overlaid, which absent

  std::string File(const std::string& name) const { return data + "/" + name; }
  // Replicate 1's finished cases that serve `figure`.
  std::vector<const CaseData*> Serving(const std::string& figure) const {
    std::vector<const CaseData*> out;
    for (const CaseData& c : cases) {
      if (c.replicate == 1 && c.finished && !c.path.empty() && c.Serves(figure)) out.push_back(&c);
    }
    return out;
  }
  NclLine StudyNcl(int replicate) const {
    const auto it = ncl_fits.find({replicate, study_ncl});
    return it == ncl_fits.end() ? NclLine{} : it->second;
  }
};

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

// ---------------------------------------------------------------- figures

// Element tests along the paths A, B, C: the finished runs in the
// subfolders of `root` (each with result.csv and done.toml), as one figure.
FigureSpec ModelPaths(const Context& ctx, FigureSpec spec, const fs::path& root,
                      const std::string& data_file) {
  BlockFile file({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  std::vector<fs::path> folders;
  if (fs::exists(root)) {
    for (const auto& entry : fs::directory_iterator(root)) {
      if (fs::exists(entry.path() / "result.csv") && fs::exists(entry.path() / "done.toml")) {
        folders.push_back(entry.path());
      }
    }
  }
  std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
    const CsvTable ta = CsvTable::ReadFile((a / "result.csv").string());
    const CsvTable tb = CsvTable::ReadFile((b / "result.csv").string());
    const double pa = ta.rows.empty() ? 0 : ta.rows[0][ta.Column("psi_epsilon_deg")];
    const double pb = tb.rows.empty() ? 0 : tb.rows[0][tb.Column("psi_epsilon_deg")];
    return pa != pb ? pa < pb : a < b;
  });
  for (const fs::path& folder : folders) {
    const CsvTable table = CsvTable::ReadFile((folder / "result.csv").string());
    if (table.rows.empty()) continue;
    const size_t p = table.Column("p_kpa"),
                 e = table.Column(quantity::kVoidRatio, quantity::former::kVoidRatio),
                 psi = table.Column("psi_sigma_deg"), dir = table.Column("psi_epsilon_deg"),
                 ocr = table.Column("ocr");
    std::vector<std::vector<double>> rows;
    for (const std::vector<double>& r : table.rows)
      rows.push_back({r[p], std::log1p(r[e]), r[psi]});
    const double psi_e = table.rows[0][dir];
    const char* path = psi_e < 89.5 ? "A" : psi_e < 90.5 ? "B" : "C";
    file.Add(fmt::format("{}: ψ_ε = {}°, OCR {}", path, Short(psi_e), Short(table.rows[0][ocr])),
             rows);
  }
  if (file.blocks() == 0) {
    return NotDrawn(spec,
                    "no finished element tests in " + fs::relative(root, ctx.directory).string());
  }
  file.Write(ctx.File(data_file));
  Set(&spec, "n_paths", file.blocks());
  Set(&spec, "paths_file", data_file);
  return spec;
}

FigureSpec Fig05(const Context& ctx) {
  FigureSpec spec =
      Spec("fig05_model_paths", "5", "Asymptotic states of the hypoplastic model for clays",
           "Element tests of the hypoplastic model for clays (Mašín 2005; the programme's "
           "[[model_run]] parameters) along proportional paths: compression (A, 0° < ψ_ε "
           "< 90°), isochoric (B, ψ_ε = 90°) and extension (C, ψ_ε > 90°), each from a "
           "normally and an overconsolidated state; paths of one ψ_ε reach one asymptotic "
           "ψ_σ and a line parallel to the NCL. Data: DIR/models/<name>/result.csv.",
           "model_paths.gp");
  return ModelPaths(ctx, spec, fs::path(ctx.directory) / "models", "fig05_paths.tsv");
}

// Fig. 5 for each calibrated model: its paths A (45°), B (90°), C (120°)
// from OCR 1 and 4 at 100 kPa, written by `granasym study calibrate`.
std::vector<FigureSpec> Fig05Calibrated(const Context& ctx) {
  std::vector<FigureSpec> specs;
  for (const char* model : {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"}) {
    const fs::path root = fs::path(ctx.directory) / "calibration" / model / "paths";
    if (!fs::exists(root)) continue;
    const std::string title = std::string(model) == "hypoplastic_clay"    ? "hypoplastic clay"
                              : std::string(model) == "modified_cam_clay" ? "Modified Cam clay"
                                                                          : "hypoplastic sand";
    FigureSpec spec = Spec(
        std::string("fig05_") + model, "5", "Asymptotic states of the calibrated " + title,
        "Element tests of the " + title +
            " model with the parameters fitted to this study "
            "(DIR/calibration/" +
            model +
            "/model.toml) along the paths A (ψ_ε = 45°), B (90°) "
            "and C (120°) from a normally and an overconsolidated (OCR 4) state at 100 kPa; "
            "A stops at 2000 kPa, C at 1 kPa; a path the model cannot follow (e.g. Cam "
            "clay softening on the dry side) is absent, its test.toml beside the others. Data: "
            "DIR/calibration/" +
            model + "/paths/.",
        "model_paths.gp");
    specs.push_back(ModelPaths(ctx, spec, root, std::string("fig05_") + model + ".tsv"));
  }
  return specs;
}

FigureSpec Fig08(const Context& ctx) {
  FigureSpec spec =
      Spec("fig08_overlaps", "8", "Relative overlaps along the isotropic NCL",
           "Frequency of relative overlaps Δu/(r_i + r_j) among the contacts (a) at the end "
           "of each ψ_ε = 0° stage of the NCL case (replicate 1, /series_histogram), and "
           "(b) the coordination number against p along the same path. The paper takes "
           "2 % as the limit of accuracy and 10 % as unreliable.",
           "overlaps.gp");
  const CaseData* ncl = FindCase(ctx.cases, 1, ctx.study_ncl);
  if (!ncl || !ncl->finished) return NotDrawn(spec, "the NCL case has no result");
  const Hdf5File file = Hdf5File::OpenRead(ncl->directory + "/result.h5");
  const std::string edges_name = std::string(dem::record::kSeriesHistogram) + "/edges";
  if (!file.Exists(edges_name)) return NotDrawn(spec, "the NCL case has no overlap histograms");
  const std::vector<double> edges = file.ReadDoubles(edges_name);
  const std::vector<double> counts = dem::ReadHistogramRows(file);
  const size_t bins = edges.size() - 1;
  BlockFile histograms({"relative_overlap", "fraction", "contacts"});
  for (const dem::StageRecord& stage : ncl->stages) {
    const size_t row = static_cast<size_t>(stage.last_row);
    if ((row + 1) * bins > counts.size()) continue;
    double total = 0;
    for (size_t b = 0; b < bins; ++b) total += counts[row * bins + b];
    if (!(total > 0)) continue;
    std::vector<std::vector<double>> rows;
    for (size_t b = 0; b < bins; ++b) {
      const double centre = edges[b] > 0 ? std::sqrt(edges[b] * edges[b + 1]) : edges[b + 1] / 2;
      rows.push_back({centre, counts[row * bins + b] / total, counts[row * bins + b]});
    }
    histograms.Add(fmt::format("p = {} kPa", Short(stage.validity.final_mean_stress_kpa)), rows);
  }
  if (histograms.blocks() == 0) return NotDrawn(spec, "the NCL histograms are empty");
  histograms.Write(ctx.File("fig08_histograms.tsv"));
  const TimeSeries series = TimeSeries::Read(file, dem::record::kSeries);
  BlockFile contacts({"p_kpa", "coordination", "contacts"});
  const std::vector<double>& p = series.Values(dem::record::kColumnMeanStress);
  const std::vector<double>& z = series.Values(dem::record::kColumnCoordination);
  const std::vector<double>& n = series.Values(dem::record::kColumnContacts);
  std::vector<std::vector<double>> rows;
  for (size_t k = 0; k < p.size(); ++k) {
    if (p[k] > 0) rows.push_back({p[k], z[k], n[k]});
  }
  contacts.Add("ψ_ε = 0°", rows);
  contacts.Write(ctx.File("fig08_contacts.tsv"));
  Set(&spec, "n_histograms", histograms.blocks());
  Set(&spec, "has_contacts", contacts.blocks());
  return spec;
}

void AddLine(BlockFile* file, const std::string& title, const NclLine& line, double p_min,
             double p_max) {
  std::vector<std::vector<double>> rows;
  for (int k = 0; k <= 20; ++k) {
    const double ln_p = std::log(p_min) + (std::log(p_max) - std::log(p_min)) * k / 20;
    rows.push_back({std::exp(ln_p), line.n - line.lambda * ln_p});
  }
  file->Add(title, rows);
}

FigureSpec Fig09(const Context& ctx) {
  FigureSpec spec =
      Spec("fig09_ncl", "9", "Isotropic compression: monotonic and with unload/reload cycles",
           "ln(1+e) against p (log scale) along ψ_ε = 0° (the NCL case) and along the "
           "unload (ψ_ε = 180°)/reload (0°) cycles that start from it (replicate 1); the "
           "line is the NCL fitted through the NCL case's stage-end states (ncl_fit.csv).",
           "ncl.gp");
  BlockFile file({"p_kpa", "ln_1_plus_e"});
  std::vector<const CaseData*> cases = ctx.Serving("9");
  // A case with unloading (ψ_ε = 180°) stages is a cycle; several monotonic
  // NCLs (of other materials) are told apart by their names.
  auto cycles_of = [](const CaseData* c) {
    return std::any_of(c->stage_psi_epsilon.begin(), c->stage_psi_epsilon.end(),
                       [](double psi) { return std::abs(psi - 180) < 1; });
  };
  const long monotonic =
      std::count_if(cases.begin(), cases.end(), [&](const CaseData* c) { return !cycles_of(c); });
  double p_min = 1e300, p_max = 0;
  for (const CaseData* c : cases) {
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; k < c->path.p.size(); ++k) {
      if (!(c->path.p[k] > 0)) continue;
      rows.push_back({c->path.p[k], c->path.ln_v[k]});
      p_min = std::min(p_min, c->path.p[k]);
      p_max = std::max(p_max, c->path.p[k]);
    }
    file.Add(cycles_of(c)    ? "unload (ψ_ε = 180°)/reload (0°) cycles"
             : monotonic > 1 ? "monotonic, ψ_ε = 0° (" + c->name + ")"
                             : "monotonic, ψ_ε = 0°",
             rows);
  }
  if (file.blocks() == 0) return NotDrawn(spec, "no finished case serves Fig. 9");
  const NclLine ncl = ctx.StudyNcl(1);
  const int paths = file.blocks();
  if (ncl.valid()) {
    AddLine(&file, fmt::format("fitted NCL: N = {:.3f}, λ* = {:.4f}", ncl.n, ncl.lambda), ncl,
            p_min, p_max);
  }
  file.Write(ctx.File("fig09_paths.tsv"));
  Set(&spec, "n_paths", paths);
  Set(&spec, "has_fit", file.blocks() - paths);
  return spec;
}

// A figure of path families (Figs. 10, 11, 13-15): ψ_σ–p, ln(1+e)–p,
// ψ_σ–ln(1+e), with the cases' asymptotic states of all replicates marked.
FigureSpec PathFamily(const Context& ctx, const std::string& figure, const std::string& stem,
                      const std::string& title, const std::string& what,
                      const std::vector<std::pair<TableKind, std::string>>& reference_kinds) {
  FigureSpec spec =
      Spec(stem, figure, title,
           what + " Paths of replicate 1 (cases whose `figures` include " + figure +
               "): (a) ψ_σ against p, (b) ln(1+e) against p, (c) ψ_σ against ln(1+e). "
               "Marks: the detector's asymptotic states of these cases, all replicates "
               "(filled: detected; open: still drifting at the stage end; gases and "
               "invalid stages omitted).",
           "paths.gp");
  BlockFile paths({"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "eps_s", "psi_epsilon_deg", "q_kpa"});
  std::vector<const CaseData*> cases = ctx.Serving(figure);
  std::stable_sort(cases.begin(), cases.end(), [](const CaseData* a, const CaseData* b) {
    const double pa = a->NominalPsiEpsilon(), pb = b->NominalPsiEpsilon();
    return std::isfinite(pa) && std::isfinite(pb) && pa != pb ? pa < pb : false;
  });
  std::set<std::string> names;
  // Colour by direction (or σ_r), dash type by start.
  std::vector<std::string> directions, starts;
  std::string colours, dashes;
  auto index_of = [](std::vector<std::string>* list, const std::string& item) {
    auto it = std::find(list->begin(), list->end(), item);
    if (it == list->end()) it = list->insert(list->end(), item);
    return static_cast<int>(it - list->begin()) + 1;
  };
  for (const CaseData* c : cases) {
    names.insert(c->name);
    colours += fmt::format("{} ", index_of(&directions, DirectionLabel(*c)));
    dashes += fmt::format("{} ", index_of(&starts, StartLabel(ctx.cases, *c)));
    paths.Add(DirectionLabel(*c) + ", " + StartLabel(ctx.cases, *c),
              Rows({&c->path.p, &c->path.ln_v, &c->path.psi_sigma, &c->path.eps_s,
                    &c->path.psi_epsilon, &c->path.q}));
  }
  if (paths.blocks() == 0) return NotDrawn(spec, "no finished case serves Fig. " + figure);
  BlockFile marks({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  std::vector<std::vector<double>> detected, drifting;
  for (const StateRow& row : ctx.states) {
    if (!names.count(row.case_name) || !UsableState(row)) continue;
    (row.status == TableStatus::kDetected ? detected : drifting)
        .push_back({row.p_kpa, row.ln_1_plus_e, row.psi_sigma_deg});
  }
  marks.Add("asymptotic states (detected)", detected);
  marks.Add("still drifting at the stage end", drifting);
  for (const auto& [kind, label] : reference_kinds) {
    std::vector<std::vector<double>> rows;
    for (const StateRow& row : ctx.states) {
      if (row.kind == kind && row.status == TableStatus::kDetected) {
        rows.push_back({row.p_kpa, row.ln_1_plus_e, row.psi_sigma_deg});
      }
    }
    marks.Add(label, rows);
    if (!rows.empty()) spec.caption += " Grey marks: " + label + ".";
  }
  paths.Write(ctx.File(stem + "_paths.tsv"));
  marks.Write(ctx.File(stem + "_states.tsv"));
  Set(&spec, "stem", stem);
  Set(&spec, "n_paths", paths.blocks());
  Set(&spec, "path_colours", colours);
  Set(&spec, "path_dashes", dashes);
  Set(&spec, "n_marks", marks.blocks());
  // Open marks are the second block only when there are detected ones.
  Set(&spec, "first_open", detected.empty() ? 0 : 1);
  Set(&spec, "n_own_marks", (detected.empty() ? 0 : 1) + (drifting.empty() ? 0 : 1));
  return spec;
}

FigureSpec Fig12(const Context& ctx) {
  FigureSpec spec =
      Spec("fig12_triaxial_strain", "12", "Drained triaxial tests against shear strain",
           "Constant-σ_r tests from NC and OC states (replicate 1) with the axial rate of "
           "the ψ_ε = 90° tests: (a) ψ_σ and (b) the stretching direction ψ_ε (from the "
           "strain increments over ±2 output rows) against the stage's shear strain "
           "ε_s = 2(ε_a − ε_r)/3.",
           "triaxial_strain.gp");
  BlockFile paths({"eps_s", "psi_sigma_deg", "psi_epsilon_deg"});
  for (const CaseData* c : ctx.Serving("12")) {
    paths.Add(DirectionLabel(*c) + ", " + StartLabel(ctx.cases, *c),
              Rows({&c->path.eps_s, &c->path.psi_sigma, &c->path.psi_epsilon}));
  }
  if (paths.blocks() == 0) return NotDrawn(spec, "no finished case serves Fig. 12");
  paths.Write(ctx.File("fig12_paths.tsv"));
  Set(&spec, "n_paths", paths.blocks());
  return spec;
}

// Nominal ψ_ε of a state: the measured one, rounded to 0.1°.
double NominalOf(const StateRow& row) { return std::round(row.psi_epsilon_deg * 10) / 10; }

bool ConstantDirectionKind(TableKind kind) {
  return kind == TableKind::kNcl || kind == TableKind::kCsl || kind == TableKind::kCompression ||
         kind == TableKind::kExtension;
}

FigureSpec Fig16(const Context& ctx) {
  FigureSpec spec =
      Spec("fig16_asymptotic_states", "16", "Asymptotic states: summary",
           "The asymptotic states of all constant-ψ_ε paths, all replicates (filled: "
           "detected; open: still drifting at the stage end; gases and invalid stages "
           "omitted), with the joined parts of paths of one ψ_ε from different starts "
           "(path_convergence.csv): (a) ψ_σ against p, (b) ln(1+e) against p, (c) ψ_σ "
           "against ln(1+e), (d) ψ_σ against ψ_ε. Lines: the calibrated models' "
           "asymptotic lines in (b) and their ψ_σ(ψ_ε) in (d).",
           "asymptotic_states.gp");
  std::map<double, std::vector<std::vector<double>>> by_direction;
  for (const StateRow& row : ctx.states) {
    if (!ConstantDirectionKind(row.kind) || !UsableState(row)) continue;
    by_direction[NominalOf(row)].push_back({row.p_kpa, row.ln_1_plus_e, row.psi_sigma_deg,
                                            row.psi_epsilon_deg,
                                            row.status == TableStatus::kDetected ? 7.0 : 6.0});
  }
  BlockFile states({"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "psi_epsilon_deg", "point_type"});
  for (const auto& [psi, rows] : by_direction)
    states.Add(fmt::format("ψ_ε = {}°", Short(psi)), rows);
  if (states.blocks() == 0)
    return NotDrawn(spec, "the state table has no usable asymptotic states");
  states.Write(ctx.File("fig16_states.tsv"));
  BlockFile lines({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  BlockFile curves({"psi_epsilon_deg", "psi_sigma_deg"});
  for (const ModelOverlay& model : ctx.models) {
    std::vector<std::vector<double>> rows;
    for (const ModelOverlay::Line& line : model.lines) {
      for (size_t k = 0; k < line.ln_p.size(); ++k) {
        rows.push_back({std::exp(line.ln_p[k]), line.ln_1_plus_e[k], line.psi_sigma_deg});
      }
      rows.push_back({});
    }
    lines.Add(model.title, rows);
    // The paper's ψ_ε ≥ 0 (the curve spans the whole circle).
    std::vector<std::vector<double>> curve;
    for (size_t k = 0; k < model.psi_epsilon_deg.size() && k < model.psi_sigma_deg.size(); ++k) {
      if (model.psi_epsilon_deg[k] >= 0) {
        curve.push_back({model.psi_epsilon_deg[k], model.psi_sigma_deg[k]});
      }
    }
    curves.Add(model.title, curve);
  }
  lines.Write(ctx.File("fig16_model_lines.tsv"));
  curves.Write(ctx.File("fig16_model_curves.tsv"));
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_states", states.blocks());
  Set(&spec, "state_titles", states.titles());
  Set(&spec, "n_models", std::min(lines.blocks(), curves.blocks()));
  return spec;
}

// The states projected to each level, and which levels.
struct Sections {
  std::vector<double> levels;
  std::vector<std::vector<std::vector<double>>> rows;  // per level: p/pe, q/pe, ψ_ε, point type
};

Sections Project(const Context& ctx, std::vector<double> levels) {
  Sections s;
  s.levels = levels;
  s.rows.resize(levels.size());
  for (const StateRow& row : ctx.states) {
    if (!ConstantDirectionKind(row.kind) || !UsableState(row)) continue;
    const NclLine ncl = ctx.StudyNcl(row.replicate);
    for (size_t l = 0; l < levels.size(); ++l) {
      SectionPoint point;
      if (ProjectToLevel(row, levels[l], ncl, ctx.options.max_projection_lnp, &point)) {
        s.rows[l].push_back({point.p_over_pe, point.q_over_pe, point.psi_epsilon_deg,
                             row.status == TableStatus::kDetected ? 7.0 : 6.0});
      }
    }
  }
  return s;
}

std::vector<double> StateLevels(const Context& ctx) {
  std::vector<double> ln_v;
  for (const StateRow& row : ctx.states) {
    if (ConstantDirectionKind(row.kind) && UsableState(row)) ln_v.push_back(row.ln_1_plus_e);
  }
  return ln_v;
}

std::string ProjectionMethod(const FigureDataOptions& options) {
  return fmt::format(
      "Each asymptotic state (all replicates; filled: detected, open: drifting) is moved to the "
      "level along its own asymptotic line — the detector's slope d ln(1+e)/d ln p for "
      "compression and extension states, the line parallel to the NCL (constant OCR) for "
      "isochoric and NCL states — keeping ψ_σ, if that moves it by at most {:g} in ln p; p_e* is "
      "that of the replicate's NCL at the level.",
      options.max_projection_lnp);
}

FigureSpec Fig17(const Context& ctx) {
  FigureSpec spec =
      Spec("fig17_asbs_sections", "17", "Constant-e cross-sections of the ASBS",
           "q/p_e* against p/p_e* at constant ln(1+e) (each level its own colour; labels: "
           "ψ_ε in degrees). " +
               ProjectionMethod(ctx.options) +
               " Lines: each calibrated model's cross-section at the same ln(1+e), "
               "normalised by the same p_e* (dash type per model).",
           "asbs_sections.gp");
  const NclLine ncl = ctx.StudyNcl(1);
  if (!ncl.valid()) return NotDrawn(spec, "the study's NCL could not be fitted");
  std::vector<double> levels = ctx.options.asbs_levels;
  if (levels.empty()) levels = SectionLevels(StateLevels(ctx), 3);
  if (levels.empty()) return NotDrawn(spec, "the state table has no usable asymptotic states");
  const Sections sections = Project(ctx, levels);
  BlockFile dem_file({"p_over_pe", "q_over_pe", "psi_epsilon_deg", "point_type"});
  std::vector<double> drawn;
  for (size_t l = 0; l < levels.size(); ++l) {
    const int before = dem_file.blocks();
    dem_file.Add(fmt::format("ln(1+e) = {:.3f}", levels[l]), sections.rows[l]);
    if (dem_file.blocks() > before) drawn.push_back(levels[l]);
  }
  if (dem_file.blocks() == 0) {
    return NotDrawn(spec, "no asymptotic state lies within the projection distance of a level");
  }
  dem_file.Write(ctx.File("fig17_dem.tsv"));
  BlockFile model_file({"p_over_pe", "q_over_pe"});
  for (const ModelOverlay& model : ctx.models) {
    for (double level : drawn) {
      std::vector<double> x, y;
      ModelSectionAt(model, level, ncl, &x, &y);
      model_file.Add(fmt::format("{}, ln(1+e) = {:.3f}", model.title, level), Rows({&x, &y}));
    }
  }
  model_file.Write(ctx.File("fig17_models.tsv"));
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_levels", static_cast<int>(drawn.size()));
  Set(&spec, "level_titles", dem_file.titles());
  Set(&spec, "n_models", model_file.blocks() / static_cast<int>(drawn.size()));
  return spec;
}

FigureSpec Fig18(const Context& ctx) {
  FigureSpec spec = Spec("fig18_asbs_level", "18", "The ASBS cross-section with ψ_ε = 90° paths",
                         "", "asbs_level.gp");
  const NclLine ncl = ctx.StudyNcl(1);
  if (!ncl.valid()) return NotDrawn(spec, "the study's NCL could not be fitted");
  std::vector<double> ln_v = StateLevels(ctx);
  if (ln_v.empty()) return NotDrawn(spec, "the state table has no usable asymptotic states");
  const double lo = *std::min_element(ln_v.begin(), ln_v.end());
  const double hi = *std::max_element(ln_v.begin(), ln_v.end());
  const double level = std::clamp(ctx.options.fig18_level, lo, hi);
  spec.caption = fmt::format(
      "The cross-section of the ASBS at ln(1+e) = {:.3f}{} in (a) logarithmic and (b) linear "
      "p/p_e*, with the NC and OC ψ_ε = 90° paths of replicate 1 (cases serving Fig. 18) whose "
      "mean ln(1+e) is nearest to the level, each row normalised by p_e* at its own void ratio. ",
      level,
      level == ctx.options.fig18_level
          ? " (the paper's level)"
          : fmt::format(" (the paper's {:g} lies outside the states' range {:.3f}–{:.3f})",
                        ctx.options.fig18_level, lo, hi));
  spec.caption += ProjectionMethod(ctx.options);
  const Sections sections = Project(ctx, {level});
  BlockFile dem_file({"p_over_pe", "q_over_pe", "psi_epsilon_deg", "point_type"});
  dem_file.Add(fmt::format("asymptotic states at ln(1+e) = {:.3f}", level), sections.rows[0]);
  if (dem_file.blocks() == 0) {
    return NotDrawn(spec, "no asymptotic state lies within the projection distance of the level");
  }
  dem_file.Write(ctx.File("fig18_dem.tsv"));
  // The NC and OC 90° paths nearest to the level.
  const CaseData* best[2] = {nullptr, nullptr};
  double distance[2] = {1e300, 1e300};
  for (const CaseData* c : ctx.Serving("18")) {
    if (std::abs(c->NominalPsiEpsilon() - 90) > 0.5) continue;
    const std::string start = StartLabel(ctx.cases, *c);
    const int k = start.rfind("NC", 0) == 0 ? 0 : start.rfind("OC", 0) == 0 ? 1 : -1;
    if (k < 0) continue;
    const double d = std::abs(Mean(c->path.ln_v) - level);
    if (d < distance[k]) distance[k] = d, best[k] = c;
  }
  BlockFile path_file({"p_over_pe", "q_over_pe"});
  for (const CaseData* c : best) {
    if (!c) continue;
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; k < c->path.p.size(); ++k) {
      const double pe = ncl.EquivalentPressure(c->path.ln_v[k]);
      rows.push_back({c->path.p[k] / pe, c->path.q[k] / pe});
    }
    path_file.Add(fmt::format("ψ_ε = 90°, {} (mean ln(1+e) = {:.3f})", StartLabel(ctx.cases, *c),
                              Mean(c->path.ln_v)),
                  rows);
  }
  path_file.Write(ctx.File("fig18_paths.tsv"));
  BlockFile model_file({"p_over_pe", "q_over_pe"});
  for (const ModelOverlay& model : ctx.models) {
    std::vector<double> x, y;
    ModelSectionAt(model, level, ncl, &x, &y);
    model_file.Add(model.title, Rows({&x, &y}));
  }
  model_file.Write(ctx.File("fig18_models.tsv"));
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_paths", path_file.blocks());
  Set(&spec, "n_models", model_file.blocks());
  return spec;
}

FigureSpec Fig19(const Context& ctx) {
  FigureSpec spec = Spec(
      "fig19_triaxial_directions", "19", "Stretching directions along drained triaxial paths",
      fmt::format("States picked along the constant-σ_r paths (all replicates; open triangles) "
                  "where their stretching direction ψ_ε (strain increments over ±{} output rows) "
                  "first reaches the ψ_ε of a constant-ψ_ε path, against the asymptotic states of "
                  "those paths (all replicates; circles), one colour per ψ_ε: (a) ψ_σ against "
                  "ln(1+e), (b) ln(1+e) against p.",
                  ctx.options.psi_epsilon_half_rows),
      "triaxial_picks.gp");
  std::map<double, std::vector<std::vector<double>>> by_direction;
  for (const StateRow& row : ctx.states) {
    if (row.kind == TableKind::kNcl || !ConstantDirectionKind(row.kind) || !UsableState(row)) {
      continue;
    }
    by_direction[NominalOf(row)].push_back({row.p_kpa, row.ln_1_plus_e, row.psi_sigma_deg, 7.0});
  }
  std::vector<double> targets;
  for (const auto& [psi, rows] : by_direction) targets.push_back(psi);
  int picked = 0;
  for (const CaseData& c : ctx.cases) {
    if (!c.finished || !c.Serves("19") || c.path.empty()) continue;
    for (const StretchingPick& pick : PickStretchingDirections(
             c.path.psi_epsilon, c.path.p, c.path.ln_v, c.path.psi_sigma, targets)) {
      by_direction[pick.psi_epsilon_deg].push_back(
          {pick.p_kpa, pick.ln_1_plus_e, pick.psi_sigma_deg, 8.0});
      ++picked;
    }
  }
  BlockFile file({"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "point_type"});
  for (const auto& [psi, rows] : by_direction) file.Add(fmt::format("ψ_ε = {}°", Short(psi)), rows);
  if (targets.empty()) return NotDrawn(spec, "the state table has no usable asymptotic states");
  if (picked == 0) return NotDrawn(spec, "no triaxial path reaches the ψ_ε of a constant-ψ_ε path");
  file.Write(ctx.File("fig19_states.tsv"));
  Set(&spec, "n_directions", file.blocks());
  Set(&spec, "direction_titles", file.titles());
  return spec;
}

// The counterpart of a variant case: "phi0_nc100_psi90" → "nc100_psi90",
// "ncl_phi0" → "ncl".
std::string Counterpart(const std::string& name, const std::string& tag) {
  if (name.rfind(tag + "_", 0) == 0) return name.substr(tag.size() + 1);
  const std::string suffix = "_" + tag;
  if (name.size() > suffix.size() &&
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
    return name.substr(0, name.size() - suffix.size());
  }
  return "";
}

// Variant cases (tag) against their counterparts: NCLs in ln(1+e)–p and the
// 90° paths in a second panel.
FigureSpec Variants(const Context& ctx, FigureSpec spec, const std::string& tag,
                    const std::function<std::string(const CaseData&)>& label) {
  BlockFile ncl({"p_kpa", "ln_1_plus_e"});
  BlockFile paths({"p_kpa", "q_kpa", "psi_sigma_deg", "eps_s"});
  std::vector<const CaseData*> pairs;
  for (const CaseData* c : ctx.Serving(spec.figure)) {
    const std::string other = Counterpart(c->name, tag);
    const CaseData* reference = FindCase(ctx.cases, 1, other);
    if (reference && reference->finished && !reference->path.empty()) pairs.push_back(reference);
    pairs.push_back(c);
  }
  for (const CaseData* c : pairs) {
    const bool is_ncl = std::abs(c->NominalPsiEpsilon()) < 0.5;
    const std::string title =
        label(*c) + (is_ncl ? "" : ", " + DirectionLabel(*c) + ", " + StartLabel(ctx.cases, *c));
    if (is_ncl) {
      ncl.Add(title, Rows({&c->path.p, &c->path.ln_v}));
    } else {
      paths.Add(title, Rows({&c->path.p, &c->path.q, &c->path.psi_sigma, &c->path.eps_s}));
    }
  }
  if (ncl.blocks() == 0 && paths.blocks() == 0) {
    return NotDrawn(spec, "no finished case serves " + spec.figure);
  }
  if (ncl.blocks() == 0 || paths.blocks() == 0) {
    return NotDrawn(spec, ncl.blocks() == 0 ? "no NCL to compare" : "no ψ_ε = 90° path to compare");
  }
  ncl.Write(ctx.File(spec.stem + "_ncl.tsv"));
  paths.Write(ctx.File(spec.stem + "_paths.tsv"));
  Set(&spec, "stem", spec.stem);
  Set(&spec, "n_ncl", ncl.blocks());
  Set(&spec, "n_paths", paths.blocks());
  return spec;
}

FigureSpec Fig20(const Context& ctx) {
  FigureSpec spec =
      Spec("fig20_friction", "20", "Contact friction φ = 0 against φ = 0.5 rad",
           "(a) The isotropic NCL in ln(1+e) against p and (b) the stress paths q against "
           "p of the ψ_ε = 90° tests from NC states, for frictionless contacts (cases "
           "serving Fig. 20) and the paper's φ = 0.5 rad (the same cases without the "
           "phi0 tag), replicate 1.",
           "friction.gp");
  return Variants(ctx, spec, "phi0", [](const CaseData& c) {
    return c.name.find("phi0") != std::string::npos ? "φ = 0" : "φ = 0.5 rad";
  });
}

FigureSpec Sec52(const Context& ctx) {
  FigureSpec spec =
      Spec("sec52_time_step", "Sec. 5.2", "Time-step independence: Δt against Δt/5",
           "(a) The isotropic NCL in ln(1+e) against p and (b) ψ_σ against the shear "
           "strain ε_s of the ψ_ε = 90° path from NC 100 kPa, with the programme's time "
           "step and with a fifth of it (cases serving Sec. 5.2 against the same cases "
           "without the dt5 tag), replicate 1.",
           "time_step.gp");
  return Variants(ctx, spec, "dt5",
                  [](const CaseData& c) { return fmt::format("Δt = {:.3g} s", c.time_step); });
}

// The paper's Fig. 21 is da Cruz et al.'s μ*(I) from plane shear; the study's
// own counterpart is the critical-state stress ratio against I.
FigureSpec Fig21(const Context& ctx) {
  FigureSpec spec = Spec("fig21_friction_inertial", "21",
                         "Critical-state stress ratio against the inertial number",
                         "The stress ratio M = q/p of the detected isochoric (ψ_ε = 90°) and "
                         "drained triaxial asymptotic states, all replicates, against their "
                         "inertial number for the smallest and the largest diameter: the study's "
                         "counterpart of the paper's Fig. 21 (da Cruz et al.'s μ*(I), which "
                         "grows with I beyond about 10^{-2}).",
                         "friction_inertial.gp");
  BlockFile file({"inertial_number", "q_over_p"});
  std::vector<std::vector<double>> dmin, dmax;
  for (const StateRow& row : ctx.states) {
    if ((row.kind != TableKind::kCsl && row.kind != TableKind::kTriaxial) ||
        row.status != TableStatus::kDetected) {
      continue;
    }
    if (!(row.q_over_p > 0)) continue;
    if (row.inertial_number_dmin > 0) dmin.push_back({row.inertial_number_dmin, row.q_over_p});
    if (row.inertial_number_dmax > 0) dmax.push_back({row.inertial_number_dmax, row.q_over_p});
  }
  if (dmin.empty() && dmax.empty()) {
    return NotDrawn(spec, "no detected isochoric or triaxial asymptotic state");
  }
  file.Add("I(d_{min})", dmin);
  file.Add("I(d_{max})", dmax);
  file.Write(ctx.File("fig21_friction_inertial.tsv"));
  return spec;
}

FigureSpec Fig22(const Context& ctx) {
  FigureSpec spec =
      Spec("fig22_inertial_number", "22", "Inertial number against mean stress",
           "The inertial number I = ‖D‖ d √(2ρ_s/p) (paper Eq. 5) for the smallest and the "
           "largest particle diameter along the cases serving Figs. 21–22 (the isotropic "
           "NCL, replicate 1), with I = 10^{-2} (quasi-static) and the stricter 10^{-3}.",
           "inertial.gp");
  BlockFile file({"p_kpa", "inertial_number"});
  std::set<const CaseData*> cases;
  for (const char* f : {"21", "22"}) {
    for (const CaseData* c : ctx.Serving(f)) cases.insert(c);
  }
  for (const CaseData* c : cases) {
    auto positive = [&](const std::vector<double>& i) {
      std::vector<std::vector<double>> rows;
      for (size_t k = 0; k < c->path.p.size(); ++k) {
        if (c->path.p[k] > 0 && i[k] > 0) rows.push_back({c->path.p[k], i[k]});
      }
      return rows;
    };
    file.Add("d_{min}, " + DirectionLabel(*c), positive(c->path.i_dmin));
    file.Add("d_{max}, " + DirectionLabel(*c), positive(c->path.i_dmax));
  }
  if (file.blocks() == 0) return NotDrawn(spec, "no finished case serves Figs. 21-22");
  file.Write(ctx.File("fig22_inertial.tsv"));
  Set(&spec, "n_curves", file.blocks());
  return spec;
}

// ---------------------------------------------------------------- the rate study

// The range of an axis that holds every point of a figure, padded so that no
// point sits on the frame and a single value still spans a range (gnuplot
// warns about an empty autoscaled range, which `study figures` treats as an
// error): 8 % each side, in log for a log axis (and at least a decade);
// a single linear value ±1.
struct AxisRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool log = false;
  void Add(double v) {
    if (!std::isfinite(v) || (log && !(v > 0))) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void Add(double v, double half_width) {
    Add(v);
    if (std::isfinite(half_width)) {
      Add(v - half_width);
      Add(v + half_width);
    }
  }
  bool empty() const { return !(lo <= hi); }
  std::pair<double, double> Padded() const {
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
};

// Sets `<name>_min` and `<name>_max` for a script's `set xrange`.
void SetRange(FigureSpec* spec, const std::string& name, const AxisRange& range) {
  const auto [lo, hi] = range.Padded();
  spec->variables.emplace_back(name + "_min", fmt::format("{:.8g}", lo));
  spec->variables.emplace_back(name + "_max", fmt::format("{:.8g}", hi));
}

// Colour (linetype) of each rate: the I* ascending, then the constant ‖D‖.
std::map<std::pair<int, double>, int> RateColours(const RateStudy& rate) {
  std::set<std::pair<int, double>> rates;
  for (const RateGroup& g : rate.groups) rates.insert({static_cast<int>(g.key.rule), g.key.rate});
  std::vector<std::pair<int, double>> order(rates.begin(), rates.end());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    const bool ia = a.first == static_cast<int>(dem::RateRule::kInertial);
    const bool ib = b.first == static_cast<int>(dem::RateRule::kInertial);
    return ia != ib ? ia : a.second < b.second;
  });
  std::map<std::pair<int, double>, int> colours;
  for (size_t k = 0; k < order.size(); ++k) colours[order[k]] = static_cast<int>(k) + 1;
  return colours;
}

std::string RateTitle(int rule, double rate) {
  return RateKey{0, 0, 0, static_cast<dem::RateRule>(rule), rate}.RateLabel();
}

// Gnuplot words ("a b" "c") of the rates' legend titles, in colour order.
std::string RateTitles(const std::map<std::pair<int, double>, int>& colours) {
  std::vector<std::string> titles(colours.size());
  for (const auto& [rate, colour] : colours) {
    titles[static_cast<size_t>(colour - 1)] = RateTitle(rate.first, rate.second);
  }
  std::string words;
  for (const std::string& t : titles) words += (words.empty() ? "\"" : " \"") + t + "\"";
  return words;
}

double Zeroed(double v) { return std::isfinite(v) ? v : 0.0; }
// The half-width of an interval of a positive value on a log axis: at most
// 0.9 of the value (the lower end stays positive).
double LogHalfWidth(double mean, double half_width) {
  return std::min(Zeroed(half_width), 0.9 * mean);
}

// Point types: filled for the reference Young's modulus, open for others;
// a triangle for ψ_ε = 0°, a circle at 90°, a square beyond (rate_lines.gp).
int DirectionPoint(double psi, bool reference_modulus) {
  const int filled = std::abs(psi) < 1e-6 ? 9 : std::abs(psi - 90) < 1e-6 ? 7 : 5;
  return reference_modulus ? filled : filled - 1;
}

std::string ModulusNote(const RateStudy& rate, double reference) {
  std::set<double> moduli;
  for (const RateGroup& g : rate.groups) moduli.insert(g.key.youngs_modulus_mpa);
  std::string others;
  for (double e : moduli) {
    if (e != reference) others += (others.empty() ? "" : ", ") + Short(e);
  }
  return others.empty()
             ? fmt::format("E = {} MPa", Short(reference))
             : fmt::format("filled: E = {} MPa, open: E = {} MPa", Short(reference), others);
}

FigureSpec RatePsiSigma(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  FigureSpec spec =
      Spec("rate_psi_sigma_p", "rate (a)", "Asymptotic ψ_σ against p at each rate",
           "The asymptotic stress obliquity ψ_σ against the asymptotic mean stress p of the rate "
           "cases, one panel per ψ_ε: the mean over the replicates' usable states of each start "
           "(NC at p_0) and rate, with the 95 % intervals of both means (Student t; none below two "
           "states), one colour per rate (the fixed inertial numbers I* and the paper's constant "
           "‖D‖), lines joining the starts of one rate; " +
               ModulusNote(rate, reference) +
               ". The last panel: the drained triaxial cases (σ_r = p_0, triangles), one curve "
               "per rank of the axial rate at each σ_r, coloured as the I* nearest their measured "
               "I (rate_drained.csv): where the isochoric paths liquefy as I* falls, these keep "
               "a critical state. If the paper's p-dependence of ψ_σ (its Sec. 5.3) is a rate "
               "effect, the curves flatten and coincide as I* falls. Data: rate_summary.csv.",
           "rate_psi_sigma.gp");
  const auto colours = RateColours(rate);
  std::map<double,
           std::map<std::pair<double, std::pair<int, double>>, std::vector<const RateGroup*>>>
      panels;  // ψ_ε → (E, rate) → groups
  for (const RateGroup& g : rate.groups) {
    if (g.used == 0) continue;
    panels[g.key.psi_epsilon_deg]
          [{g.key.youngs_modulus_mpa, {static_cast<int>(g.key.rule), g.key.rate}}]
              .push_back(&g);
  }
  // The drained cases (σ_r = p_0): one curve per (E, rank of the axial rate
  // at each σ_r, slowest first), coloured as the I* nearest its measured I.
  std::map<std::pair<double, int>, std::vector<const DrainedGroup*>> drained;
  {
    std::map<std::pair<double, double>, std::vector<const DrainedGroup*>> by_start;
    for (const DrainedGroup& g : rate.drained.groups) {
      if (g.used > 0 && std::isfinite(g.psi_sigma_deg.mean)) {
        by_start[{g.youngs_modulus_mpa, g.radial_stress_kpa}].push_back(&g);
      }
    }
    for (auto& [start, groups] : by_start) {
      std::sort(groups.begin(), groups.end(), [](const DrainedGroup* a, const DrainedGroup* b) {
        return a->axial_strain_rate < b->axial_strain_rate;
      });
      for (size_t r = 0; r < groups.size(); ++r) {
        drained[{start.first, static_cast<int>(r)}].push_back(groups[r]);
      }
    }
  }
  auto nearest_colour = [&colours](double inertial) {
    int best = 1;
    double distance = std::numeric_limits<double>::infinity();
    for (const auto& [key, colour] : colours) {
      if (key.first != static_cast<int>(dem::RateRule::kInertial) || !(inertial > 0)) continue;
      const double d = std::abs(std::log(inertial / key.second));
      if (d < distance) distance = d, best = colour;
    }
    return best;
  };
  if (panels.empty() && drained.empty()) {
    return NotDrawn(spec, "no rate case has a usable asymptotic state");
  }
  std::string panel_titles, panel_blocks, ranges[4];
  int k = 0;
  auto add_ranges = [&ranges](const AxisRange& x, const AxisRange& y) {
    const auto [x_lo, x_hi] = x.Padded();
    const auto [y_lo, y_hi] = y.Padded();
    const double values[4] = {x_lo, x_hi, y_lo, y_hi};
    for (int r = 0; r < 4; ++r) {
      ranges[r] += fmt::format("{}{:.8g}", ranges[r].empty() ? "" : " ", values[r]);
    }
  };
  for (const auto& [psi, curves] : panels) {
    ++k;
    AxisRange x{}, y{};
    x.log = true;
    BlockFile file({"p_kpa", "p_ci95", "psi_sigma_deg", "psi_sigma_ci95", "point_type", "colour"});
    for (const auto& [curve, groups] : curves) {
      std::vector<const RateGroup*> sorted = groups;
      std::sort(sorted.begin(), sorted.end(), [](const RateGroup* a, const RateGroup* b) {
        return a->p_kpa.mean < b->p_kpa.mean;
      });
      std::vector<std::vector<double>> rows;
      for (const RateGroup* g : sorted) {
        x.Add(g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width));
        y.Add(g->psi_sigma_deg.mean, g->psi_sigma_deg.half_width);
        rows.push_back({g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width),
                        g->psi_sigma_deg.mean, Zeroed(g->psi_sigma_deg.half_width),
                        static_cast<double>(DirectionPoint(90, curve.first == reference)),
                        static_cast<double>(colours.at(curve.second))});
      }
      file.Add(fmt::format("{}, E = {} MPa", RateTitle(curve.second.first, curve.second.second),
                           Short(curve.first)),
               rows);
    }
    file.Write(ctx.File(fmt::format("rate_psi_sigma_{}.tsv", k)));
    panel_titles += fmt::format("{}\"ψ_ε = {}°\"", panel_titles.empty() ? "" : " ", Short(psi));
    panel_blocks += fmt::format("{}{}", panel_blocks.empty() ? "" : " ", file.blocks());
    add_ranges(x, y);
  }
  if (!drained.empty()) {
    ++k;
    AxisRange x{}, y{};
    x.log = true;
    BlockFile file({"p_kpa", "p_ci95", "psi_sigma_deg", "psi_sigma_ci95", "point_type", "colour"});
    for (const auto& [curve, groups] : drained) {
      std::vector<double> inertial;
      for (const DrainedGroup* g : groups) inertial.push_back(g->inertial_number_dmax.mean);
      const double i_mean = Estimate::Of(inertial).mean;
      std::vector<std::vector<double>> rows;
      for (const DrainedGroup* g : groups) {  // ascending σ_r
        x.Add(g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width));
        y.Add(g->psi_sigma_deg.mean, g->psi_sigma_deg.half_width);
        rows.push_back({g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width),
                        g->psi_sigma_deg.mean, Zeroed(g->psi_sigma_deg.half_width),
                        curve.first == reference ? 9.0 : 8.0,
                        static_cast<double>(nearest_colour(i_mean))});
      }
      file.Add(fmt::format("drained, I ≈ {:.2g}, E = {} MPa", i_mean, Short(curve.first)), rows);
    }
    file.Write(ctx.File(fmt::format("rate_psi_sigma_{}.tsv", k)));
    panel_titles += fmt::format("{}\"drained, σ_r = p_0\"", panel_titles.empty() ? "" : " ");
    panel_blocks += fmt::format("{}{}", panel_blocks.empty() ? "" : " ", file.blocks());
    add_ranges(x, y);
  }
  Set(&spec, "panel_x_min", ranges[0]);
  Set(&spec, "panel_x_max", ranges[1]);
  Set(&spec, "panel_y_min", ranges[2]);
  Set(&spec, "panel_y_max", ranges[3]);
  Set(&spec, "n_panels", k);
  Set(&spec, "panel_titles", panel_titles);
  Set(&spec, "panel_blocks", panel_blocks);
  Set(&spec, "n_rates", static_cast<int>(colours.size()));
  Set(&spec, "rate_titles", RateTitles(colours));
  Set(&spec, "modulus_note", ModulusNote(rate, reference));
  return spec;
}

FigureSpec RateLines(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  FigureSpec spec =
      Spec("rate_csl_ncl", "rate (b)", "NCL, CSL and NEL at each rate",
           fmt::format(
               "ln(1+e) against p (log scale) of the rate cases' usable asymptotic states, all "
               "replicates and starts: ψ_ε = 0° (triangles: the NCL at that rate), 90° (circles: "
               "the CSL), other directions (squares: e.g. the NEL of 100°); {}; one colour per "
               "rate. Lines: ln(1+e) = N − λ ln p fitted through the states of one direction and "
               "rate (at least two starts; at ψ_ε = 0°, whose states all lie at the stress cap, "
               "the mean of the paths' own lines past their first unit of ln p: a least-squares "
               "secant of an NCL that steepens with p), drawn over their p range; rate_lines.csv "
               "gives N, λ "
               "and ln(1+e) at {} kPa with its 95 % interval. Data: rate_states.csv.",
               ModulusNote(rate, reference), Short(rate.options.reference_p_kpa)),
           "rate_lines.gp");
  const auto colours = RateColours(rate);
  std::map<std::tuple<double, double, int, double>, std::vector<std::vector<double>>> blocks;
  for (const RateState& s : rate.states) {
    if (!rate.Usable(s)) continue;
    blocks[{s.psi_epsilon_deg, s.youngs_modulus_mpa, static_cast<int>(s.rule), s.rate()}].push_back(
        {s.p_kpa, s.ln_1_plus_e,
         static_cast<double>(DirectionPoint(s.psi_epsilon_deg, s.youngs_modulus_mpa == reference)),
         static_cast<double>(colours.at({static_cast<int>(s.rule), s.rate()}))});
  }
  if (blocks.empty()) return NotDrawn(spec, "no rate case has a usable asymptotic state");
  AxisRange x{}, y{};
  x.log = true;
  for (const auto& [key, rows] : blocks) {
    for (const std::vector<double>& row : rows) {
      x.Add(row[0]);
      y.Add(row[1]);
    }
  }
  BlockFile states({"p_kpa", "ln_1_plus_e", "point_type", "colour"});
  for (const auto& [key, rows] : blocks) {
    states.Add(fmt::format("ψ_ε = {}°, E = {} MPa, {}", Short(std::get<0>(key)),
                           Short(std::get<1>(key)), RateTitle(std::get<2>(key), std::get<3>(key))),
               rows);
  }
  states.Write(ctx.File("rate_lines_states.tsv"));
  BlockFile lines({"p_kpa", "ln_1_plus_e", "colour"});
  for (const RateLine& l : rate.lines) {
    if (!l.valid()) continue;
    const double colour = colours.at({static_cast<int>(l.rule), l.rate});
    std::vector<std::vector<double>> rows;
    for (double p : {l.p_min_kpa, l.p_max_kpa}) {
      rows.push_back({p, l.n - l.lambda * std::log(p), colour});
      y.Add(rows.back()[1]);
    }
    lines.Add(fmt::format("ψ_ε = {}°, E = {} MPa, {}: N = {:.4f}, λ = {:.4f}",
                          Short(l.psi_epsilon_deg), Short(l.youngs_modulus_mpa),
                          RateKey{0, 0, 0, l.rule, l.rate}.RateLabel(), l.n, l.lambda),
              rows);
  }
  if (lines.blocks() > 0) lines.Write(ctx.File("rate_lines_fits.tsv"));
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_states", states.blocks());
  Set(&spec, "n_lines", lines.blocks());
  Set(&spec, "n_rates", static_cast<int>(colours.size()));
  Set(&spec, "rate_titles", RateTitles(colours));
  Set(&spec, "modulus_note", ModulusNote(rate, reference));
  return spec;
}

// Rate (d), issue 10 §3: σ_r/p of the extension sweep against ψ_ε, one
// colour per sweep (E, rate, p_0); liquefied steps on the zero line, and
// ψ_ε(d) with its interval where a sweep reached the limit d.
FigureSpec RateExtension(const Context& ctx, const RateStudy& rate) {
  FigureSpec spec =
      Spec("rate_extension", "rate (d)", "Extension states up to the limit d",
           "The asymptotic σ_r/p = 1 − (q/p)/3 of the rate cases with ψ_ε ≥ 90° against ψ_ε (means "
           "over the replicates' usable states with their 95 % intervals), one colour per sweep "
           "(E, rate, start p_0). σ_r/p = 0 is the limit d (ψ_σ = 54.74°). Crosses on the zero "
           "line: steps at which most replicates liquefied (a gas: mechanical coordination below 3 "
           "or p below 0.5 kPa; no asymptote). Squares with horizontal bars: ψ_ε(d), the root of "
           "the least-squares line of σ_r/p through the last steps, with its 95 % interval. Data: "
           "rate_extension.csv, rate_extension_limit.csv.",
           "rate_extension.gp");
  using SweepKey = std::tuple<double, int, double, double>;
  auto key_of = [](double e_mpa, dem::RateRule rule, double r, double p0) {
    return SweepKey{e_mpa, static_cast<int>(rule), r, p0};
  };
  std::map<SweepKey, int> colour_of;
  for (const ExtensionLimit& l : rate.extension_limits) {
    colour_of.emplace(key_of(l.youngs_modulus_mpa, l.rule, l.rate, l.start_p_kpa),
                      static_cast<int>(colour_of.size()) + 1);
  }
  if (colour_of.empty()) return NotDrawn(spec, "no rate case runs at ψ_ε > 90°");
  auto title = [](const SweepKey& k) {
    return fmt::format("E = {} MPa, {}, NC {} kPa", Short(std::get<0>(k)),
                       RateTitle(std::get<1>(k), std::get<2>(k)), Short(std::get<3>(k)));
  };
  std::map<SweepKey, std::vector<std::vector<double>>> steps, liquefied;
  AxisRange x{}, y{};
  y.Add(0.0);
  for (const ExtensionStep& st : rate.extension_steps) {
    const SweepKey k = key_of(st.youngs_modulus_mpa, st.rule, st.rate, st.start_p_kpa);
    const auto colour = colour_of.find(k);
    if (colour == colour_of.end()) continue;
    x.Add(st.psi_epsilon_deg);
    if (st.status == "liquefied") {
      liquefied[k].push_back({st.psi_epsilon_deg, 0.0, static_cast<double>(colour->second)});
    } else if (st.used > 0 && std::isfinite(st.sigma_r_over_p.mean)) {
      y.Add(st.sigma_r_over_p.mean, st.sigma_r_over_p.half_width);
      steps[k].push_back({st.psi_epsilon_deg, st.sigma_r_over_p.mean,
                          Zeroed(st.sigma_r_over_p.half_width),
                          static_cast<double>(colour->second)});
    }
  }
  BlockFile step_file({"psi_epsilon_deg", "sigma_r_over_p", "sigma_r_over_p_ci95", "colour"});
  for (const auto& [k, rows] : steps) step_file.Add(title(k), rows);
  BlockFile liquefied_file({"psi_epsilon_deg", "sigma_r_over_p", "colour"});
  for (const auto& [k, rows] : liquefied) liquefied_file.Add(title(k), rows);
  BlockFile limit_file({"psi_epsilon_deg", "psi_epsilon_ci95", "sigma_r_over_p", "colour"});
  for (const ExtensionLimit& l : rate.extension_limits) {
    if (l.result != "limit_d" || !std::isfinite(l.psi_d_deg.mean)) continue;
    const SweepKey k = key_of(l.youngs_modulus_mpa, l.rule, l.rate, l.start_p_kpa);
    x.Add(l.psi_d_deg.mean, l.psi_d_deg.half_width);
    limit_file.Add(title(k) + ": " + l.Text(), {{l.psi_d_deg.mean, Zeroed(l.psi_d_deg.half_width),
                                                 0.0, static_cast<double>(colour_of.at(k))}});
  }
  if (step_file.blocks() > 0) step_file.Write(ctx.File("rate_extension_steps.tsv"));
  if (liquefied_file.blocks() > 0) liquefied_file.Write(ctx.File("rate_extension_liquefied.tsv"));
  if (limit_file.blocks() > 0) limit_file.Write(ctx.File("rate_extension_limits.tsv"));
  std::string sweep_titles;
  std::vector<std::string> ordered(colour_of.size());
  for (const auto& [k, colour] : colour_of) ordered[static_cast<size_t>(colour - 1)] = title(k);
  for (const std::string& t : ordered) {
    sweep_titles += fmt::format("{}\"{}\"", sweep_titles.empty() ? "" : " ", t);
  }
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_steps", step_file.blocks());
  Set(&spec, "n_liquefied", liquefied_file.blocks());
  Set(&spec, "n_limits", limit_file.blocks());
  Set(&spec, "n_sweeps", static_cast<int>(colour_of.size()));
  Set(&spec, "sweep_titles", sweep_titles);
  return spec;
}

// Rate (e), issue 10 §4: the quasi-static asymptotic states (the rate
// cases at the I* the models were calibrated to, calibration/quasi_static.toml,
// or the default selection) beside the paper-rate ones (constant ‖D‖) at the
// reference modulus, with the calibrated models of this folder.
FigureSpec RateAgainstModels(const Context& ctx, const RateStudy& rate) {
  std::optional<QuasiStaticSelection> selection = ReadQuasiStaticSelection(ctx.directory);
  const bool calibrated = selection.has_value();
  if (!selection) selection = SelectQuasiStatic(rate);
  FigureSpec spec = Spec(
      "rate_against_models", "rate (e)",
      "Quasi-static and paper-rate asymptotic states against the calibrated models",
      fmt::format(
          "The asymptotic states of the rate cases at {} (filled circles: the quasi-static "
          "set{}) and at the paper's constant ‖D‖ (open diamonds), E = {} MPa, all ψ_ε: (a) ψ_σ "
          "against ψ_ε, the means over the replicates of each start with their 95 % intervals; "
          "(b) ln(1+e) against p, every usable state, one colour per ψ_ε, with the drained "
          "triaxial states of the quasi-static set (filled triangles: the slowest axial rate of "
          "each σ_r, rate_drained_states.csv). Lines: the models "
          "calibrated in this folder to the quasi-static set (`granasym study calibrate`), "
          "their ψ_σ(ψ_ε) in (a) and their asymptotic lines in (b). Data: rate_summary.csv, "
          "rate_states.csv.",
          selection->valid() ? fmt::format("I* = {:g}", selection->inertial_number)
                             : std::string("the smallest I*"),
          calibrated ? ", calibration/quasi_static.toml" : ", not yet calibrated",
          Short(selection->youngs_modulus_mpa)),
      "rate_models.gp");
  if (!selection->valid()) return NotDrawn(spec, selection->reason);
  const double e_mpa = selection->youngs_modulus_mpa, i_star = selection->inertial_number;
  auto quasi = [&](dem::RateRule rule, double r) {
    return rule == dem::RateRule::kInertial && r == i_star;
  };
  // (a) group means of each set (0: quasi-static, 1: the paper rate); (b) states.
  std::vector<std::vector<double>> set_rows[2];
  for (const RateGroup& g : rate.groups) {
    if (g.key.youngs_modulus_mpa != e_mpa || g.used == 0) continue;
    const int set = quasi(g.key.rule, g.key.rate)            ? 0
                    : g.key.rule == dem::RateRule::kConstant ? 1
                                                             : -1;
    if (set < 0) continue;
    // Side by side at each ψ_ε, so that the intervals do not hide each other.
    set_rows[set].push_back({g.key.psi_epsilon_deg + (set == 0 ? -0.6 : 0.6), g.psi_sigma_deg.mean,
                             Zeroed(g.psi_sigma_deg.half_width)});
  }
  const char* set_files[2] = {"rate_models_quasi_static.tsv", "rate_models_paper_rate.tsv"};
  for (int set = 0; set < 2; ++set) {
    if (set_rows[set].empty()) continue;
    BlockFile means({"psi_epsilon_deg", "psi_sigma_deg", "psi_sigma_ci95"});
    means.Add(set == 0 ? fmt::format("I* = {:g}", i_star) : std::string("constant ‖D‖"),
              set_rows[set]);
    means.Write(ctx.File(set_files[set]));
  }
  std::map<double, std::vector<std::vector<double>>> by_psi;
  std::set<double> directions;
  for (const RateState& s : rate.states) {
    if (s.youngs_modulus_mpa != e_mpa || !rate.Usable(s)) continue;
    const bool is_quasi = quasi(s.rule, s.rate());
    if (!is_quasi && s.rule != dem::RateRule::kConstant) continue;
    directions.insert(s.psi_epsilon_deg);
    by_psi[s.psi_epsilon_deg].push_back({s.p_kpa, s.ln_1_plus_e, is_quasi ? 7.0 : 12.0});
  }
  // The drained cases of the quasi-static set: the critical state under stress control.
  std::vector<std::vector<double>> drained_rows;
  for (const DrainedState& s : rate.drained.states) {
    if (std::find(selection->drained_cases.begin(), selection->drained_cases.end(), s.case_name) !=
            selection->drained_cases.end() &&
        s.youngs_modulus_mpa == e_mpa && rate.Usable(s)) {
      drained_rows.push_back({s.p_kpa, s.ln_1_plus_e, 9.0});
    }
  }
  if (by_psi.empty() && drained_rows.empty()) {
    return NotDrawn(spec, "no usable state at the selected rates");
  }
  BlockFile states({"p_kpa", "ln_1_plus_e", "point_type"});
  std::string psi_titles;
  for (const auto& [psi, rows] : by_psi) {
    states.Add(fmt::format("ψ_ε = {}°", Short(psi)), rows);
    psi_titles += fmt::format("{}\"ψ_ε = {}°\"", psi_titles.empty() ? "" : " ", Short(psi));
  }
  if (!drained_rows.empty()) {
    states.Add("drained triaxial, slowest axial rate", drained_rows);
    psi_titles += fmt::format("{}\"drained\"", psi_titles.empty() ? "" : " ");
  }
  states.Write(ctx.File("rate_models_states.tsv"));
  // The models: ψ_σ(ψ_ε) over the swept range, lines at the study's directions.
  BlockFile curves({"psi_epsilon_deg", "psi_sigma_deg"});
  BlockFile lines({"p_kpa", "ln_1_plus_e"});
  const double lo = *directions.begin() - 5, hi = *directions.rbegin() + 5;
  for (const ModelOverlay& model : ctx.models) {
    std::vector<std::vector<double>> curve, rows;
    for (size_t k = 0; k < model.psi_epsilon_deg.size() && k < model.psi_sigma_deg.size(); ++k) {
      if (model.psi_epsilon_deg[k] >= lo && model.psi_epsilon_deg[k] <= hi) {
        curve.push_back({model.psi_epsilon_deg[k], model.psi_sigma_deg[k]});
      }
    }
    for (const ModelOverlay::Line& line : model.lines) {
      if (line.psi_epsilon_deg < lo || line.psi_epsilon_deg > hi) continue;
      for (size_t k = 0; k < line.ln_p.size(); ++k) {
        rows.push_back({std::exp(line.ln_p[k]), line.ln_1_plus_e[k]});
      }
      rows.push_back({});
    }
    if (curve.empty() || rows.empty()) continue;
    curves.Add(model.title, curve);
    lines.Add(model.title, rows);
  }
  if (curves.blocks() > 0) {
    curves.Write(ctx.File("rate_models_curves.tsv"));
    lines.Write(ctx.File("rate_models_lines.tsv"));
  }
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_models", curves.blocks());
  Set(&spec, "n_psi", states.blocks());
  Set(&spec, "psi_titles", psi_titles);
  Set(&spec, "quasi_title", fmt::format("I* = {:g}", i_star));
  Set(&spec, "n_quasi_static", set_rows[0].empty() ? 0 : 1);
  Set(&spec, "n_paper_rate", set_rows[1].empty() ? 0 : 1);
  return spec;
}

FigureSpec RateCriticalState(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  const LiteratureBand& band = rate.options.literature_m;
  FigureSpec spec =
      Spec("rate_critical_state_ratio", "rate (c)",
           "Critical-state stress ratio M against the inertial number, and its quasi-static limit",
           fmt::format(
               "M = q/p of the ψ_ε = 90° asymptotic states against their measured I(d_max) (means "
               "over the replicates with 95 % intervals of both; circles: fixed I*, diamonds: the "
               "paper's constant ‖D‖; triangles: drained triaxial compression at σ_r = p_0 and a "
               "constant axial rate, rate_drained.csv), one colour per start p_0; {}. Lines: the "
               "quasi-static fit M = M_0 + b·I through the states of the {} smallest I* (of every "
               "axial rate for the drained cases; least squares: the "
               "small-I form of the μ(I) laws of the paper's refs. [10], da Cruz et al. 2005, "
               "and [29], Jop et al. 2006); the "
               "points at the left edge are M_0 = M(I → 0) with its 95 % interval "
               "(rate_quasi_static.csv, rate_drained_limit.csv). Band: the published "
               "critical-state ratio of frictional spheres without rolling resistance, {}. "
               "Dashed: I = 10^{{-2}} (quasi-static, paper Sec. 5.3) and 10^{{-3}} (SPEC §8.2).",
               ModulusNote(rate, reference), rate.options.fit_rates, band.source),
           "rate_critical_state.gp");
  // Colours by start; point types by modulus (filled reference) and rule.
  std::set<double> starts;
  for (const RateGroup& g : rate.groups) {
    if (std::abs(g.key.psi_epsilon_deg - 90) < 1e-6 && g.used > 0) starts.insert(g.key.start_p_kpa);
  }
  for (const DrainedGroup& g : rate.drained.groups) {
    if (g.used > 0) starts.insert(g.radial_stress_kpa);
  }
  if (starts.empty()) {
    return NotDrawn(spec, "no ψ_ε = 90° or drained rate case has a usable asymptotic state");
  }
  std::map<double, int> colour_of;
  std::string start_titles;
  for (double p : starts) {
    colour_of[p] = static_cast<int>(colour_of.size()) + 1;
    start_titles += fmt::format("{}\"NC {} kPa\"", start_titles.empty() ? "" : " ", Short(p));
  }
  BlockFile groups({"inertial_number", "inertial_number_ci95", "q_over_p", "q_over_p_ci95",
                    "point_type", "colour"});
  double i_min = 1e300;
  std::map<std::pair<double, double>, std::vector<std::vector<double>>> by_curve;  // (E, p_0)
  for (const RateGroup& g : rate.groups) {
    if (std::abs(g.key.psi_epsilon_deg - 90) > 1e-6 || g.used == 0) continue;
    if (!(g.inertial_number_dmax.mean > 0) || !std::isfinite(g.q_over_p.mean)) continue;
    const bool ref = g.key.youngs_modulus_mpa == reference;
    const int point = g.key.rule == dem::RateRule::kInertial ? (ref ? 7 : 6) : (ref ? 13 : 12);
    i_min = std::min(i_min, g.inertial_number_dmax.mean);
    by_curve[{g.key.youngs_modulus_mpa, g.key.start_p_kpa}].push_back(
        {g.inertial_number_dmax.mean,
         LogHalfWidth(g.inertial_number_dmax.mean, g.inertial_number_dmax.half_width),
         g.q_over_p.mean, Zeroed(g.q_over_p.half_width), static_cast<double>(point),
         static_cast<double>(colour_of.at(g.key.start_p_kpa))});
  }
  // The drained cases (constant σ_r = p_0): triangles, one block per (E, σ_r).
  std::map<std::pair<double, double>, std::vector<std::vector<double>>> drained_curves;
  for (const DrainedGroup& g : rate.drained.groups) {
    if (g.used == 0 || !(g.inertial_number_dmax.mean > 0) || !std::isfinite(g.q_over_p.mean)) {
      continue;
    }
    const bool ref = g.youngs_modulus_mpa == reference;
    i_min = std::min(i_min, g.inertial_number_dmax.mean);
    drained_curves[{g.youngs_modulus_mpa, g.radial_stress_kpa}].push_back(
        {g.inertial_number_dmax.mean,
         LogHalfWidth(g.inertial_number_dmax.mean, g.inertial_number_dmax.half_width),
         g.q_over_p.mean, Zeroed(g.q_over_p.half_width), ref ? 9.0 : 8.0,
         static_cast<double>(colour_of.at(g.radial_stress_kpa))});
  }
  if (by_curve.empty() && drained_curves.empty()) {
    return NotDrawn(spec, "no ψ_ε = 90° or drained rate state has a measured I");
  }
  AxisRange x{}, y{};
  x.log = true;
  y.Add(band.low);
  y.Add(band.high);
  for (const auto& [curve, rows] : by_curve) {
    for (const std::vector<double>& row : rows) {
      x.Add(row[0], row[1]);
      y.Add(row[2], row[3]);
    }
  }
  for (const auto& [curve, rows] : drained_curves) {
    for (const std::vector<double>& row : rows) {
      x.Add(row[0], row[1]);
      y.Add(row[2], row[3]);
    }
  }
  for (auto& [curve, rows] : by_curve) {
    std::sort(rows.begin(), rows.end());
    groups.Add(fmt::format("E = {} MPa, NC {} kPa", Short(curve.first), Short(curve.second)), rows);
  }
  for (auto& [curve, rows] : drained_curves) {
    std::sort(rows.begin(), rows.end());
    groups.Add(fmt::format("E = {} MPa, drained at sigma_r = {} kPa", Short(curve.first),
                           Short(curve.second)),
               rows);
  }
  groups.Write(ctx.File("rate_critical_state_groups.tsv"));
  // The quasi-static lines and limits, drawn from a left edge a third of
  // the smallest measured I.
  const double i_left = i_min / 3;
  x.Add(i_left);
  BlockFile fits({"inertial_number", "q_over_p", "q_over_p_ci95", "point_type", "colour"});
  BlockFile limits({"inertial_number", "q_over_p", "q_over_p_ci95", "point_type", "colour"});
  // A quasi-static line M_0 + b·I from the left edge to the largest I
  // fitted, and its limit M_0 at the edge.
  auto add_fit = [&](const std::string& title, double m0, double half_width, double slope,
                     double i_max, double line_point, double limit_point, int colour) {
    std::vector<std::vector<double>> rows;
    for (int k = 0; k <= 20; ++k) {
      const double i = std::exp(std::log(i_left) + (std::log(i_max) - std::log(i_left)) * k / 20);
      rows.push_back({i, m0 + slope * i, 0.0, line_point, static_cast<double>(colour)});
    }
    fits.Add(title, rows);
    limits.Add(title, {{i_left, m0, Zeroed(half_width), limit_point, static_cast<double>(colour)}});
    y.Add(m0, half_width);
    y.Add(rows.back()[1]);
  };
  for (const QuasiStaticFit& f : rate.quasi_static) {
    if (f.quantity != "q_over_p" || std::abs(f.psi_epsilon_deg - 90) > 1e-6 || !f.valid()) continue;
    const auto colour = colour_of.find(f.start_p_kpa);
    if (colour == colour_of.end()) continue;
    const bool ref = f.youngs_modulus_mpa == reference;
    add_fit(fmt::format("E = {} MPa, NC {} kPa: M_0 = {:.3f}", Short(f.youngs_modulus_mpa),
                        Short(f.start_p_kpa), f.limit.mean),
            f.limit.mean, f.limit.half_width, f.slope.mean, f.i_max, ref ? 7.0 : 6.0,
            ref ? 5.0 : 4.0, colour->second);
  }
  for (const DrainedLimit& l : rate.drained.limits) {
    if (!l.valid()) continue;
    const auto colour = colour_of.find(l.radial_stress_kpa);
    if (colour == colour_of.end()) continue;
    const bool ref = l.youngs_modulus_mpa == reference;
    add_fit(fmt::format("E = {} MPa, drained at sigma_r = {} kPa: M_0 = {:.3f}",
                        Short(l.youngs_modulus_mpa), Short(l.radial_stress_kpa), l.m.mean),
            l.m.mean, l.m.half_width, l.m_slope.mean, l.i_max, ref ? 9.0 : 8.0, ref ? 9.0 : 8.0,
            colour->second);
  }
  if (fits.blocks() > 0) {
    fits.Write(ctx.File("rate_critical_state_fits.tsv"));
    limits.Write(ctx.File("rate_critical_state_limits.tsv"));
  }
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_groups", groups.blocks());
  Set(&spec, "n_fits", fits.blocks());
  Set(&spec, "n_starts", static_cast<int>(colour_of.size()));
  Set(&spec, "start_titles", start_titles);
  Set(&spec, "modulus_note", ModulusNote(rate, reference));
  spec.variables.emplace_back("band_low", fmt::format("{:g}", band.low));
  spec.variables.emplace_back("band_high", fmt::format("{:g}", band.high));
  spec.variables.emplace_back("i_left", fmt::format("{:.6g}", i_left));
  return spec;
}

}  // namespace

bool FigureDataOptions::IsValid(std::string* why) const {
  for (double level : asbs_levels) {
    if (!(std::isfinite(level) && level > 0)) {
      *why = fmt::format("asbs_levels: {} is not a finite positive ln(1+e)", level);
      return false;
    }
  }
  if (!(fig18_level > 0)) {
    *why = "fig18_level: must be a positive ln(1+e)";
    return false;
  }
  if (!(max_projection_lnp > 0)) {
    *why = "max_projection_lnp: must be positive";
    return false;
  }
  if (psi_epsilon_half_rows < 1) {
    *why = "psi_epsilon_half_rows: must be at least 1";
    return false;
  }
  return true;
}

double NclLine::EquivalentPressure(double ln_v) const { return std::exp((n - ln_v) / lambda); }

bool ProjectToLevel(const StateRow& state, double level, const NclLine& ncl, double max_lnp,
                    SectionPoint* point) {
  if (!ncl.valid() || !(state.p_kpa > 0) || !std::isfinite(state.ln_1_plus_e)) return false;
  double slope = -ncl.lambda;
  if ((state.kind == TableKind::kCompression || state.kind == TableKind::kExtension) &&
      std::isfinite(state.dln1pe_dlnp) && state.dln1pe_dlnp < -1e-3) {
    slope = state.dln1pe_dlnp;
  }
  const double shift = (level - state.ln_1_plus_e) / slope;
  if (!(std::abs(shift) <= max_lnp)) return false;
  const double p = state.p_kpa * std::exp(shift);
  const double pe = ncl.EquivalentPressure(level);
  const double q_over_p = 3.0 / std::sqrt(2.0) * std::tan(state.psi_sigma_deg * kDegree);
  point->p_over_pe = p / pe;
  point->q_over_pe = q_over_p * p / pe;
  point->psi_epsilon_deg = state.psi_epsilon_deg;
  point->lnp_shift = shift;
  return true;
}

std::vector<double> PathPsiEpsilon(const std::vector<double>& eps_a,
                                   const std::vector<double>& eps_r, int half_rows) {
  const int n = static_cast<int>(std::min(eps_a.size(), eps_r.size()));
  std::vector<double> psi(n, std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < n; ++k) {
    const int a = std::max(0, k - half_rows), b = std::min(n - 1, k + half_rows);
    if (a == b) continue;
    const double da = eps_a[b] - eps_a[a], dr = eps_r[b] - eps_r[a];
    if (da == 0 && dr == 0) continue;
    psi[k] = std::atan2(std::sqrt(2.0) * (da - dr), da + 2 * dr) / kDegree;
  }
  return psi;
}

std::vector<StretchingPick> PickStretchingDirections(const std::vector<double>& psi_epsilon_deg,
                                                     const std::vector<double>& p_kpa,
                                                     const std::vector<double>& ln_1_plus_e,
                                                     const std::vector<double>& psi_sigma_deg,
                                                     const std::vector<double>& targets_deg) {
  std::vector<StretchingPick> picks;
  const size_t n =
      std::min({psi_epsilon_deg.size(), p_kpa.size(), ln_1_plus_e.size(), psi_sigma_deg.size()});
  for (double target : targets_deg) {
    for (size_t k = 1; k < n; ++k) {
      const double a = psi_epsilon_deg[k - 1] - target, b = psi_epsilon_deg[k] - target;
      if (!std::isfinite(a) || !std::isfinite(b)) continue;
      if (!((a < 0 && b >= 0) || (a > 0 && b <= 0))) continue;
      const double t = a / (a - b);
      auto at = [&](const std::vector<double>& v) { return v[k - 1] + t * (v[k] - v[k - 1]); };
      StretchingPick pick;
      pick.psi_epsilon_deg = target;
      pick.p_kpa =
          std::exp(std::log(p_kpa[k - 1]) + t * (std::log(p_kpa[k]) - std::log(p_kpa[k - 1])));
      pick.ln_1_plus_e = at(ln_1_plus_e);
      pick.psi_sigma_deg = at(psi_sigma_deg);
      pick.row = static_cast<double>(k - 1) + t;
      if (std::isfinite(pick.p_kpa)) picks.push_back(pick);
      break;
    }
  }
  return picks;
}

std::vector<double> SectionLevels(std::vector<double> ln_v, int count) {
  ln_v.erase(std::remove_if(ln_v.begin(), ln_v.end(), [](double v) { return !std::isfinite(v); }),
             ln_v.end());
  if (ln_v.empty() || count < 1) return {};
  const double lo = *std::min_element(ln_v.begin(), ln_v.end());
  const double hi = *std::max_element(ln_v.begin(), ln_v.end());
  auto round = [](double v) { return std::round(v / 0.005) * 0.005; };
  if (hi - lo < 0.01 || count == 1) return {round(0.5 * (lo + hi))};
  std::vector<double> levels;
  for (int k = 0; k < count; ++k) {
    const double level = round(lo + (hi - lo) * (0.2 + 0.6 * k / (count - 1)));
    if (levels.empty() || level > levels.back()) levels.push_back(level);
  }
  return levels;
}

ModelOverlay ReadModelOverlay(const std::string& folder, const std::string& name) {
  ModelOverlay model;
  model.name = name;
  model.title = ModelTitle(name);
  const CsvTable curve = CsvTable::ReadFile(folder + "/model_curve.csv");
  model.psi_epsilon_deg = curve.ColumnValues("psi_epsilon_deg");
  model.psi_sigma_deg = curve.ColumnValues("psi_sigma_deg");
  model.p_over_pe = curve.ColumnValues("p_over_pe");
  model.q_over_pe = curve.ColumnValues("q_over_pe");
  // model_lines.dat: comma-separated psi_epsilon_deg, ln_p, ln_1_plus_e,
  // psi_sigma_deg, '#' comments, blocks by blank lines.
  const std::string path = folder + "/model_lines.dat";
  std::istringstream in(ReadTextFile(path));
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (Trimmed(line).empty() || Trimmed(line)[0] == '#') continue;
    double v[4];
    std::istringstream fields(line);
    std::string field;
    for (int k = 0; k < 4; ++k) {
      if (!std::getline(fields, field, ',')) {
        throw InputError(
            fmt::format("{}:{}: expected 4 comma-separated numbers, got '{}'", path, number, line));
      }
      try {
        size_t used = 0;
        v[k] = std::stod(field, &used);
        if (Trimmed(field.substr(used)) != "") throw std::invalid_argument(field);
      } catch (const std::exception&) {
        throw InputError(fmt::format("{}:{}: '{}' is not a number", path, number, field));
      }
    }
    if (model.lines.empty() || model.lines.back().psi_epsilon_deg != v[0]) {
      model.lines.push_back({v[0], v[3], {}, {}});
    }
    model.lines.back().ln_p.push_back(v[1]);
    model.lines.back().ln_1_plus_e.push_back(v[2]);
  }
  // The model's NCL from its ψ_ε = 0° line (least squares: a straight line
  // for the clay models; the sand's Bauer curve gets its mean slope).
  for (const ModelOverlay::Line& l : model.lines) {
    if (std::abs(l.psi_epsilon_deg) > 1e-9 || l.ln_p.size() < 2) continue;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = static_cast<double>(l.ln_p.size());
    for (size_t k = 0; k < l.ln_p.size(); ++k) {
      sx += l.ln_p[k], sy += l.ln_1_plus_e[k];
      sxx += l.ln_p[k] * l.ln_p[k], sxy += l.ln_p[k] * l.ln_1_plus_e[k];
    }
    const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    model.ncl = NclLine{(sy - slope * sx) / m, -slope};
  }
  if (!model.ncl.valid()) {
    throw RuntimeError(path + ": no psi_epsilon = 0 line with a falling ln(1+e) (the model's NCL)");
  }
  return model;
}

void ModelSectionAt(const ModelOverlay& model, double level, const NclLine& study_ncl,
                    std::vector<double>* p_over_pe, std::vector<double>* q_over_pe) {
  p_over_pe->clear();
  q_over_pe->clear();
  const double scale = model.ncl.EquivalentPressure(level) / study_ncl.EquivalentPressure(level);
  for (size_t k = 0; k < model.p_over_pe.size() && k < model.q_over_pe.size(); ++k) {
    p_over_pe->push_back(model.p_over_pe[k] * scale);
    q_over_pe->push_back(model.q_over_pe[k] * scale);
  }
}

std::vector<FigureSpec> WriteFigureData(const std::string& directory,
                                        const FigureDataOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("figure options: " + why);
  const std::string table = directory + "/asymptotic_states.h5";
  if (!fs::exists(table)) {
    throw InputError(table +
                     " does not exist: run `granasym study run` (or `study merge`) "
                     "on the study folder first");
  }
  Context ctx;
  ctx.directory = directory;
  ctx.data = directory + "/figures/data";
  ctx.options = options;
  fs::create_directories(ctx.data);
  for (const auto& entry : fs::directory_iterator(ctx.data)) {
    if (entry.path().extension() == ".tsv") fs::remove(entry.path());
  }
  ctx.cases = LoadCases(directory, options.psi_epsilon_half_rows);
  ctx.states = ReadStateTable(directory);
  ctx.ncl_fits = ReadNclFits(directory);
  ctx.study_ncl = StudyNclName(directory);
  std::vector<std::string> overlaid, absent;
  for (const std::string& name : options.models) {
    const std::string folder = directory + "/calibration/" + name + "/plot_data";
    if (fs::exists(folder + "/model_curve.csv") && fs::exists(folder + "/model_lines.dat")) {
      ctx.models.push_back(ReadModelOverlay(folder, name));
      overlaid.push_back(ModelTitle(name));
    } else {
      absent.push_back(ModelTitle(name));
    }
  }
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + v[k];
    return s;
  };
  ctx.models_note = overlaid.empty()
                        ? "No calibrated model is overlaid"
                        : "Models overlaid (DIR/calibration/<model>/plot_data): " + join(overlaid);
  if (!absent.empty())
    ctx.models_note += "; not calibrated in this study, so not shown: " + join(absent);
  ctx.models_note += ".";

  std::vector<FigureSpec> figures;
  figures.push_back(Fig05(ctx));
  for (FigureSpec& spec : Fig05Calibrated(ctx)) figures.push_back(std::move(spec));
  figures.push_back(Fig08(ctx));
  figures.push_back(Fig09(ctx));
  figures.push_back(PathFamily(ctx, "10", "fig10_csl_nc", "Isochoric paths from NC states",
                               "ψ_ε = 90° paths from normally consolidated states: the critical "
                               "state line.",
                               {}));
  figures.push_back(
      PathFamily(ctx, "11", "fig11_csl_oc", "Isochoric paths from OC states",
                 "ψ_ε = 90° paths from overconsolidated states (loaded to 1000 kPa, "
                 "unloaded along ψ_ε = 180°): the asymptotic state does not depend "
                 "on the start.",
                 {{TableKind::kCsl, "NC ψ_ε = 90° asymptotes (Fig. 10), all replicates"}}));
  figures.push_back(Fig12(ctx));
  figures.push_back(
      PathFamily(ctx, "13", "fig13_triaxial", "Drained triaxial paths",
                 "Constant-σ_r paths from NC and OC states.",
                 {{TableKind::kCsl, "ψ_ε = 90° asymptotes (Figs. 10-11), all replicates"}}));
  figures.push_back(PathFamily(ctx, "14", "fig14_compression", "Compression asymptotic states",
                               "Proportional compression paths, 0° < ψ_ε < 90°, from NC states.",
                               {}));
  figures.push_back(PathFamily(ctx, "15", "fig15_extension", "Extension asymptotic states",
                               "Proportional extension paths, ψ_ε > 90°, from NC states: the "
                               "normal extension lines (a path that ends as a gas has no "
                               "asymptotic state).",
                               {}));
  figures.push_back(Fig16(ctx));
  figures.push_back(Fig17(ctx));
  figures.push_back(Fig18(ctx));
  figures.push_back(Fig19(ctx));
  figures.push_back(Fig20(ctx));
  figures.push_back(Fig21(ctx));
  figures.push_back(Fig22(ctx));
  figures.push_back(Sec52(ctx));
  // The paper's figures that this study's programme declares (every one, for
  // paper.toml): a programme of other cases lists its own figures only.
  std::set<std::string> declared;
  for (const CaseData& c : ctx.cases) {
    declared.insert(c.figures.entries().begin(), c.figures.entries().end());
  }
  const bool models = fs::exists(fs::path(directory) / "models");
  figures.erase(
      std::remove_if(figures.begin(), figures.end(),
                     [&](const FigureSpec& f) {
                       if (f.stem.rfind("fig05_", 0) == 0 && f.stem != "fig05_model_paths") {
                         return false;  // a calibrated model's: drawn when it ran
                       }
                       if (f.figure == "5") return !models;
                       return !declared.count(f.figure);
                     }),
      figures.end());
  // The rate study's figures, when it has rate cases.
  if (const std::optional<RateStudy> read = ReadRateStudy(directory)) {
    const RateStudy& rate = *read;
    figures.push_back(RatePsiSigma(ctx, rate));
    figures.push_back(RateLines(ctx, rate));
    figures.push_back(RateCriticalState(ctx, rate));
    if (!rate.extension_limits.empty()) figures.push_back(RateExtension(ctx, rate));
    figures.push_back(RateAgainstModels(ctx, rate));
  }
  return figures;
}

void WriteFigureIndex(const std::string& directory, const std::vector<FigureSpec>& figures) {
  auto clean = [](std::string s) {
    for (char& c : s) {
      if (c == '\t' || c == '\n' || c == '\r') c = ' ';
    }
    return s;
  };
  std::string text = "stem\tfigure\ttitle\tcaption\n";
  for (const FigureSpec& f : figures) {
    text += clean(f.stem) + "\t" + clean(f.figure) + "\t" + clean(f.title) + "\t" +
            clean(f.caption) + "\n";
  }
  fs::create_directories(directory + "/figures");
  WriteTextFileAtomically(directory + "/figures/index.tsv", text);
}

}  // namespace granasym::analysis
