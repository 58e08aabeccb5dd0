#include "analysis/figure_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "analysis/figure_families.h"
#include "analysis/rate_files.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/quantity_names.h"
#include "common/state_measures.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace fs = std::filesystem;
namespace figures {
namespace {

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

}  // namespace

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

}  // namespace figures

bool FigureDataOptions::IsValid(std::string* why) const {
  for (double level : settings.levels) {
    if (!(std::isfinite(level) && level > 0)) {
      *why = fmt::format("levels: {} is not a finite positive ln(1+e)", level);
      return false;
    }
  }
  if (settings.fig18_level && !(*settings.fig18_level > 0)) {
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
  model.title = figures::ModelTitle(name);
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
  const std::string out = options.out.empty() ? directory : options.out;
  if (fs::exists(out + "/study.toml") && !fs::equivalent(out, directory)) {
    throw InputError("--out " + out +
                     " is another study's folder: its figures would be replaced; give a new "
                     "folder or the study itself");
  }
  const std::string data = out + "/figures/data";
  fs::create_directories(data);
  for (const auto& entry : fs::directory_iterator(data)) {
    if (entry.path().extension() == ".tsv") fs::remove(entry.path());
  }
  const figures::Context ctx = figures::ReadContext(directory, options);

  std::vector<FigureSpec> specs;
  specs.push_back(figures::Fig05(ctx));
  for (FigureSpec& spec : figures::Fig05Calibrated(ctx)) specs.push_back(std::move(spec));
  specs.push_back(figures::Fig08(ctx));
  specs.push_back(figures::Fig09(ctx));
  specs.push_back(figures::PathFamily(
      ctx, {"10",
            "fig10_csl_nc",
            "Isochoric paths from NC states",
            "ψ_ε = 90° paths from normally consolidated states: the critical state line.",
            {},
            true}));
  specs.push_back(figures::PathFamily(
      ctx, {"11",
            "fig11_csl_oc",
            "Isochoric paths from OC states",
            "ψ_ε = 90° paths from overconsolidated states (loaded to 1000 kPa, unloaded along "
            "ψ_ε = 180°): the asymptotic state does not depend on the start.",
            {{TableKind::kCsl, "NC ψ_ε = 90° asymptotes (Fig. 10), all replicates"}},
            true}));
  specs.push_back(figures::Fig12(ctx));
  specs.push_back(figures::PathFamily(
      ctx, {"13",
            "fig13_triaxial",
            "Drained triaxial paths",
            "Constant-σ_r paths from NC and OC states.",
            {{TableKind::kCsl, "ψ_ε = 90° asymptotes (Figs. 10-11), all replicates"}},
            true}));
  specs.push_back(
      figures::PathFamily(ctx, {"14",
                                "fig14_compression",
                                "Compression asymptotic states",
                                "Proportional compression paths, 0° < ψ_ε < 90°, from NC states.",
                                {},
                                false}));
  specs.push_back(figures::PathFamily(
      ctx, {"15",
            "fig15_extension",
            "Extension asymptotic states",
            "Proportional extension paths, ψ_ε > 90°, from NC states: the normal extension "
            "lines, proportional paths towards the origin (a path that ends as a gas has no "
            "asymptotic state).",
            {},
            true}));
  specs.push_back(figures::Fig16(ctx));
  specs.push_back(figures::Fig17(ctx));
  specs.push_back(figures::Fig18(ctx));
  specs.push_back(figures::Fig19(ctx));
  specs.push_back(figures::Fig20(ctx));
  specs.push_back(figures::Fig21(ctx));
  specs.push_back(figures::Fig22(ctx));
  specs.push_back(figures::Sec52(ctx));
  // The paper's figures that this study's programme declares (every one, for
  // paper.toml): a programme of other cases lists its own figures only.
  std::set<std::string> declared;
  for (const figures::CaseData& c : ctx.cases) {
    declared.insert(c.figures.entries().begin(), c.figures.entries().end());
  }
  const bool models = fs::exists(fs::path(directory) / "models");
  specs.erase(
      std::remove_if(specs.begin(), specs.end(),
                     [&](const FigureSpec& f) {
                       if (f.stem.rfind("fig05_", 0) == 0 && f.stem != "fig05_model_paths") {
                         return false;  // a calibrated model's: drawn when it ran
                       }
                       if (f.figure == "5") return !models;
                       return !declared.count(f.figure);
                     }),
      specs.end());
  // The rate study's figures, when it has rate cases.
  if (const std::optional<RateStudy> read = ReadRateStudy(directory)) {
    const RateStudy& rate = *read;
    specs.push_back(figures::RatePsiSigma(ctx, rate));
    specs.push_back(figures::RateLines(ctx, rate));
    specs.push_back(figures::RateCriticalState(ctx, rate));
    if (!rate.extension_limits.empty()) specs.push_back(figures::RateExtension(ctx, rate));
    specs.push_back(figures::RateAgainstModels(ctx, rate));
  }
  return specs;
}

void WriteFigureIndex(const std::string& out, const std::vector<FigureSpec>& figures) {
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
  fs::create_directories(out + "/figures");
  WriteTextFileAtomically(out + "/figures/index.tsv", text);
}

std::vector<std::pair<std::string, std::string>> WriteFigureScripts(
    const std::string& out, const std::string& plots, const std::vector<FigureSpec>& figures) {
  const fs::path folder = fs::absolute(fs::path(out) / "figures").lexically_normal();
  const fs::path scripts = folder / "scripts";
  fs::create_directories(scripts);
  for (const std::string& path : {folder.string(), fs::absolute(plots).string()}) {
    if (path.find('\'') != std::string::npos) {
      throw InputError("'" + path + "': a folder name with a quote cannot be passed to gnuplot");
    }
  }
  // The scripts the figures load, and those they load in turn (common.gp).
  std::set<std::string> copied;
  auto copy = [&](const std::string& name) {
    if (!copied.insert(name).second) return;
    const fs::path source = fs::path(plots) / name;
    if (!fs::exists(source)) {
      throw InputError("the figure script " + source.string() +
                       " does not exist (GRANASYM_PLOTS_DIR names the folder of the scripts)");
    }
    WriteTextFileAtomically((scripts / name).string(), ReadTextFile(source.string()));
  };
  std::vector<std::pair<std::string, std::string>> wrappers;
  for (const FigureSpec& f : figures) {
    if (!f.not_drawn.empty()) continue;
    copy("common.gp");
    copy(f.script);
    std::string text = fmt::format(
        "# {}: {} (granasym study figures).\n"
        "# Redraw: gnuplot {}.plt (PNG); gnuplot -e \"term='pdf'\" {}.plt (or 'svg').\n"
        "# The script and its shared settings are the copies in scripts/: edit them to "
        "restyle.\n"
        "if (!exists(\"term\")) term = 'png'\n"
        "data = '{}'\nout = '{}'\nscripts = '{}'\n",
        f.figure.find_first_not_of("0123456789") == std::string::npos ? "Fig. " + f.figure
                                                                      : f.figure,
        f.title, f.stem, f.stem, (folder / "data").string(), (folder / f.stem).string(),
        scripts.string());
    for (const auto& [name, value] : f.variables) text += name + " = " + value + "\n";
    text += "load scripts.'/" + f.script + "'\n";
    const std::string path = (folder / (f.stem + ".plt")).string();
    WriteTextFileAtomically(path, text);
    wrappers.emplace_back(f.stem, path);
  }
  return wrappers;
}

}  // namespace granasym::analysis
