// The asymptotic states and the ASBS (paper Figs. 16-19): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "analysis/figure_families.h"
#include "analysis/quasi_static_selection.h"
#include "common/statistics.h"

namespace granasym::analysis::figures {
namespace {

// Nominal ψ_ε of a state: the measured one, rounded to 0.1°.
double NominalOf(const StateRow& row) { return std::round(row.psi_epsilon_deg * 10) / 10; }

bool ConstantDirectionKind(TableKind kind) {
  return kind == TableKind::kNcl || kind == TableKind::kCsl || kind == TableKind::kCompression ||
         kind == TableKind::kExtension;
}

// Every usable state of the study's own sample (detected and drifting).
StateSelection MainStates() { return StateSelection{}; }

// The states of the ASBS sections (Fig. 17): those of the constant-ψ_ε
// paths; in a rate study whose models were fitted to its quasi-static set
// (calibration/quasi_static.toml, issue 39 §3) only the cases of that set,
// with its drained triaxial critical states (ψ_ε ≈ 90° there), so that the
// sections are those of the states the models were calibrated to.
struct SectionStates {
  StateSelection selection;
  std::optional<QuasiStaticSelection> quasi_static;
  bool Takes(TableKind kind) const {
    return ConstantDirectionKind(kind) || (quasi_static && kind == TableKind::kTriaxial);
  }
  // The captions' sentence on the states ("" without a quasi-static set).
  std::string Describe() const {
    if (!quasi_static) return "";
    return fmt::format(
        " The states: the quasi-static set that the models were calibrated to ({}: {}), the "
        "drained triaxial critical states (triaxial) with them; the other states of the study "
        "(other rates) are left out.",
        kQuasiStaticSelectionFile, SelectionText(*quasi_static));
  }
};
SectionStates SectionStatesOf(const Context& ctx) {
  SectionStates states;
  states.quasi_static = ReadQuasiStaticSelection(ctx.directory);
  if (states.quasi_static) {
    for (const std::string& name : states.quasi_static->AllCases()) {
      states.selection.cases.insert(name);
    }
  }
  return states;
}

// One colour (gnuplot linetype) per nominal ψ_ε of the study's states, in
// ascending order: Figs. 16 and 19 colour a direction alike.
std::map<double, int> DirectionColours(const Context& ctx) {
  std::map<double, int> colours;
  for (const StateRow* row : ctx.Select(MainStates())) {
    if (ConstantDirectionKind(row->kind)) colours[NominalOf(*row)] = 0;
  }
  int k = 0;
  for (auto& [psi, colour] : colours) colour = k++ % 10 + 1;
  return colours;
}

// The states projected to each level, and which levels.
struct Sections {
  std::vector<double> levels;
  std::vector<std::vector<std::vector<double>>> rows;  // per level: p/pe, q/pe, ψ_ε, point type
  std::vector<std::vector<std::string>> labels;        // per level: hover labels
  int beyond_ncl = 0;  // projections left out past kMaxSectionPOverPe
};

// A state projected past the NCL (p/p_e* = 1) by more than this is left out
// of the sections: no asymptotic state lies beyond the NCL, so such a point
// measures the projection's error (a curved NCL fitted by a line, a state
// still drifting), not the ASBS.
constexpr double kMaxSectionPOverPe = 1.25;

Sections Project(const Context& ctx, std::vector<double> levels,
                 const SectionStates& states = SectionStates{}) {
  Sections s;
  s.levels = levels;
  s.rows.resize(levels.size());
  s.labels.resize(levels.size());
  for (const StateRow* state : ctx.Select(states.selection)) {
    const StateRow& row = *state;
    if (!states.Takes(row.kind)) continue;
    const NclLine ncl = ctx.StudyNcl(row.replicate);
    for (size_t l = 0; l < levels.size(); ++l) {
      SectionPoint point;
      if (ProjectToLevel(row, levels[l], ncl, ctx.options.max_projection_lnp, &point)) {
        if (point.p_over_pe > kMaxSectionPOverPe) {
          ++s.beyond_ncl;
          continue;
        }
        s.rows[l].push_back({point.p_over_pe, point.q_over_pe, point.psi_epsilon_deg,
                             row.status == TableStatus::kDetected ? 7.0 : 6.0});
        s.labels[l].push_back(StateLabel(row) + fmt::format("\\nmoved to ln(1+e) = {:.3f} by "
                                                            "{:+.2f} in ln p",
                                                            levels[l], point.lnp_shift));
      }
    }
  }
  return s;
}

std::vector<double> StateLevels(const Context& ctx, const SectionStates& states = SectionStates{}) {
  std::vector<double> ln_v;
  for (const StateRow* row : ctx.Select(states.selection)) {
    if (states.Takes(row->kind)) ln_v.push_back(row->ln_1_plus_e);
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

}  // namespace

FigureSpec Fig16(const Context& ctx) {
  FigureSpec spec =
      Spec("fig16_asymptotic_states", "16", "Asymptotic states: summary",
           "The asymptotic states of all constant-ψ_ε paths, every replicate (filled: "
           "detected; open: still drifting at the stage end), one colour per ψ_ε (as in "
           "Fig. 19): (a) ψ_σ against p, (b) ln(1+e) against p with the study's NCL and CSL "
           "and each calibrated model's NCL and CSL, (c) ψ_σ against ln(1+e), (d) ψ_σ "
           "against ψ_ε with the models' ψ_σ(ψ_ε). ",
           "asymptotic_states.gp");
  const std::map<double, int> colours = DirectionColours(ctx);
  // The states of the ASBS sections: in a study whose models were fitted to
  // its quasi-static set, that set (Fig. 17's), not the other rates' states.
  const SectionStates section = SectionStatesOf(ctx);
  // One block per nominal ψ_ε; the drained triaxial critical states (whose
  // measured ψ_ε scatters about 90°) in one block after them.
  using Block = std::pair<bool, double>;  // (triaxial, nominal ψ_ε)
  std::map<Block, std::vector<std::vector<double>>> by_direction;
  std::map<Block, std::vector<std::string>> labels;
  AxisRange p_range, lnv_range;
  for (const StateRow* row : ctx.Select(section.selection)) {
    if (!section.Takes(row->kind)) continue;
    const bool triaxial = row->kind == TableKind::kTriaxial;
    const Block block{triaxial, triaxial ? 90.0 : NominalOf(*row)};
    by_direction[block].push_back({row->p_kpa, row->ln_1_plus_e, row->psi_sigma_deg,
                                   row->psi_epsilon_deg,
                                   row->status == TableStatus::kDetected ? 7.0 : 6.0});
    labels[block].push_back(StateLabel(*row));
    p_range.Add(row->p_kpa);
    lnv_range.Add(row->ln_1_plus_e);
  }
  BlockFile states(
      {"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "psi_epsilon_deg", "point_type", "label"});
  std::string state_colours;
  // The drained block's colour: the first that no direction of this figure has.
  std::set<int> used;
  for (const auto& [block, rows] : by_direction) {
    const auto colour = colours.find(block.second);
    if (!block.first && colour != colours.end()) used.insert(colour->second);
  }
  int other_colour = 1;
  while (used.count(other_colour) && other_colour < 10) ++other_colour;
  for (const auto& [block, rows] : by_direction) {
    const auto [triaxial, psi] = block;
    const auto colour = colours.find(psi);
    states.AddLabelled(triaxial ? std::string("drained triaxial (critical state)")
                                : fmt::format("ψ_ε = {}°", Short(psi)),
                       rows, labels[block]);
    state_colours +=
        fmt::format("{} ", !triaxial && colour != colours.end() ? colour->second : other_colour);
  }
  if (states.blocks() == 0)
    return NotDrawn(spec, "the state table has no usable asymptotic states");
  states.Write(ctx.File("fig16_states.tsv"));
  // Panel (b): the NCL (ψ_ε = 0°) and CSL (90°) of the study and of each model.
  BlockFile lines({"p_kpa", "ln_1_plus_e"});
  std::vector<std::string> line_styles;
  auto add = [&](const std::string& title, double n, double lambda, const std::string& style) {
    const int before = lines.blocks();
    lines.Add(title, LineRows(n, lambda, p_range.lo, p_range.hi, 40));
    if (lines.blocks() > before) line_styles.push_back(style);
  };
  const NclLine ncl = ctx.StudyNcl(1);
  if (ncl.valid()) add("DEM: NCL (replicate 1)", ncl.n, ncl.lambda, "0");
  BlockFile curves({"psi_epsilon_deg", "psi_sigma_deg"});
  int m = 0;
  for (const ModelOverlay& model : ctx.models) {
    ++m;
    bool ncl_drawn = false, csl_drawn = false;
    for (const ModelOverlay::Line& line : model.lines) {
      const bool is_ncl = std::abs(line.psi_epsilon_deg) < 0.5 && !ncl_drawn;
      const bool is_csl = std::abs(line.psi_epsilon_deg - 90) < 0.5 && !csl_drawn;
      if ((!is_ncl && !is_csl) || line.ln_p.size() < 2) continue;
      (is_ncl ? ncl_drawn : csl_drawn) = true;
      // The model's line through its first and last points (straight in ln p).
      const double lambda = -(line.ln_1_plus_e.back() - line.ln_1_plus_e.front()) /
                            (line.ln_p.back() - line.ln_p.front());
      const double n = line.ln_1_plus_e.front() + lambda * line.ln_p.front();
      add(fmt::format("{}: {}", model.title, is_ncl ? "NCL" : "CSL"), n, lambda, std::to_string(m));
    }
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
  spec.caption += MainStates().Describe(ctx) + section.Describe() + " " + ctx.models_note;
  std::string styles;
  for (const std::string& st : line_styles) styles += st + " ";
  Set(&spec, "n_states", states.blocks());
  Set(&spec, "state_titles", states.titles());
  Set(&spec, "state_colours", state_colours);
  Set(&spec, "n_lines", lines.blocks());
  Set(&spec, "line_titles", lines.titles());
  Set(&spec, "line_models", styles);
  Set(&spec, "n_models", curves.blocks());
  Set(&spec, "model_titles", curves.titles());
  const auto [p_lo, p_hi] = p_range.Logarithmic(0.08);
  const auto [v_lo, v_hi] = lnv_range.Linear(0.06, 0.01);
  SetNumber(&spec, "p_lo", p_lo);
  SetNumber(&spec, "p_hi", p_hi);
  SetNumber(&spec, "lnv_lo", v_lo);
  SetNumber(&spec, "lnv_hi", v_hi);
  return spec;
}

FigureSpec Fig17(const Context& ctx) {
  FigureSpec spec =
      Spec("fig17_asbs_sections", "17", "Constant-e cross-sections of the ASBS",
           "q/p_e* against p/p_e* at constant ln(1+e), one colour per level (labels: ψ_ε in "
           "degrees); one panel per calibrated model, whose cross-sections at the same "
           "levels (normalised by the same p_e*) are the lines. The levels are at 20, 50 "
           "and 80 % of the states' range of ln(1+e) unless chosen (`study figures "
           "--level`, or `levels` in the programme's [figures]). " +
               ProjectionMethod(ctx.options),
           "asbs_sections.gp");
  const SectionStates states = SectionStatesOf(ctx);
  spec.caption += states.Describe();
  const NclLine ncl = ctx.StudyNcl(1);
  if (!ncl.valid()) return NotDrawn(spec, "the study's NCL could not be fitted");
  std::vector<double> levels = ctx.options.settings.levels;
  if (levels.empty()) levels = SectionLevels(StateLevels(ctx, states), 3);
  if (levels.empty()) {
    return NotDrawn(spec, states.quasi_static
                              ? "the quasi-static set has no usable asymptotic states"
                              : "the state table has no usable asymptotic states");
  }
  std::sort(levels.begin(), levels.end());
  const Sections sections = Project(ctx, levels, states);
  BlockFile dem_file({"p_over_pe", "q_over_pe", "psi_epsilon_deg", "point_type", "label"});
  std::vector<double> drawn;
  double x_hi = 0, y_lo = 0, y_hi = 0;
  for (size_t l = 0; l < levels.size(); ++l) {
    const int before = dem_file.blocks();
    dem_file.AddLabelled(fmt::format("ln(1+e) = {:.3f}", levels[l]), sections.rows[l],
                         sections.labels[l]);
    if (dem_file.blocks() > before) drawn.push_back(levels[l]);
    for (const std::vector<double>& r : sections.rows[l]) {
      x_hi = std::max(x_hi, r[0]);
      y_lo = std::min(y_lo, r[1]);
      y_hi = std::max(y_hi, r[1]);
    }
  }
  if (dem_file.blocks() == 0) {
    return NotDrawn(spec, "no asymptotic state lies within the projection distance of a level");
  }
  dem_file.Write(ctx.File("fig17_dem.tsv"));
  if (sections.beyond_ncl > 0) {
    spec.caption += fmt::format(
        " {} projection(s) past p/p_e* = {:g} (beyond the NCL, where no asymptotic state lies: "
        "the projection's error) are left out.",
        sections.beyond_ncl, kMaxSectionPOverPe);
  }
  // Each model's sections, model-major; also the data of every model's
  // section at each level (the export: DIR/figures/data/fig17_models.tsv).
  BlockFile model_file({"p_over_pe", "q_over_pe"});
  for (const ModelOverlay& model : ctx.models) {
    for (double level : drawn) {
      std::vector<double> x, y;
      ModelSectionAt(model, level, ncl, &x, &y);
      model_file.Add(fmt::format("{}, ln(1+e) = {:.3f}", model.title, level), Rows({&x, &y}));
    }
  }
  model_file.Write(ctx.File("fig17_models.tsv"));
  std::vector<std::string> titles;
  for (const ModelOverlay& model : ctx.models) titles.push_back(model.title);
  const std::string model_titles = QuotedWords(titles);
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_levels", static_cast<int>(drawn.size()));
  Set(&spec, "level_titles", dem_file.titles());
  Set(&spec, "n_models", static_cast<int>(ctx.models.size()));
  Set(&spec, "model_titles", model_titles);
  // The axes from the DEM's states (a model's section may reach far beyond).
  SetNumber(&spec, "x_hi", std::max(1.1, 1.15 * x_hi));
  SetNumber(&spec, "y_lo", 1.15 * y_lo - 0.05);
  SetNumber(&spec, "y_hi", 1.15 * y_hi + 0.05);
  return spec;
}

FigureSpec Fig18(const Context& ctx) {
  FigureSpec spec = Spec("fig18_asbs_level", "18", "The ASBS cross-section with ψ_ε = 90° paths",
                         "", "asbs_level.gp");
  const NclLine ncl = ctx.StudyNcl(1);
  if (!ncl.valid()) return NotDrawn(spec, "the study's NCL could not be fitted");
  std::vector<double> ln_v = StateLevels(ctx);
  if (ln_v.empty()) return NotDrawn(spec, "the state table has no usable asymptotic states");
  // The NC and OC 90° paths of replicate 1 serving Fig. 18; the level is the
  // chosen one, else the OC path's (isochoric: its ln(1+e) stays), the one
  // whose level holds the most states within the projection distance.
  std::vector<const CaseData*> nc, oc;
  for (const CaseData* c : ctx.Serving("18")) {
    if (std::abs(c->NominalPsiEpsilon() - 90) > 0.5) continue;
    const std::string kind = StartOf(ctx.cases, *c).kind;
    if (kind == "NC") nc.push_back(c);
    if (kind == "OC") oc.push_back(c);
  }
  double level = 0;
  std::string why_level;
  const CaseData* oc_path = nullptr;
  if (ctx.options.settings.fig18_level) {
    level = *ctx.options.settings.fig18_level;
    why_level = "the level chosen in the figure settings";
  } else if (!oc.empty()) {
    int most = -1;
    for (const CaseData* c : oc) {
      const double at = Mean(c->path.ln_v);
      const int count = static_cast<int>(Project(ctx, {at}).rows[0].size());
      if (count > most) most = count, level = at, oc_path = c;
    }
    why_level = "the level of the OC path " + StartLabel(ctx.cases, *oc_path) +
                " (the one whose level the most states reach)";
  } else {
    level = SectionLevels(ln_v, 1).front();
    why_level = "the middle of the states' range (no OC ψ_ε = 90° path serves Fig. 18)";
  }
  spec.caption = fmt::format(
      "The cross-section of the ASBS at ln(1+e) = {:.3f}, {}, in (a) logarithmic and (b) "
      "linear p/p_e*, with the NC and OC ψ_ε = 90° paths of replicate 1 nearest to the "
      "level, each row normalised by p_e* at its own void ratio (the paper's level 0.58 is "
      "that of its own sample; choose one with `study figures --fig18-level`). ",
      level, why_level);
  spec.caption += ProjectionMethod(ctx.options);
  const Sections sections = Project(ctx, {level});
  BlockFile dem_file({"p_over_pe", "q_over_pe", "psi_epsilon_deg", "point_type", "label"});
  dem_file.AddLabelled(fmt::format("asymptotic states at ln(1+e) = {:.3f}", level),
                       sections.rows[0], sections.labels[0]);
  if (dem_file.blocks() == 0) {
    return NotDrawn(spec, "no asymptotic state lies within the projection distance of the level");
  }
  dem_file.Write(ctx.File("fig18_dem.tsv"));
  if (sections.beyond_ncl > 0) {
    spec.caption += fmt::format(" {} projection(s) past p/p_e* = {:g} are left out.",
                                sections.beyond_ncl, kMaxSectionPOverPe);
  }
  double x_lo = 1e300, x_hi = 0, y_lo = 0, y_hi = 0;
  for (const std::vector<double>& r : sections.rows[0]) {
    x_lo = std::min(x_lo, r[0]), x_hi = std::max(x_hi, r[0]);
    y_lo = std::min(y_lo, r[1]), y_hi = std::max(y_hi, r[1]);
  }
  BlockFile path_file({"p_over_pe", "q_over_pe"});
  for (const std::vector<const CaseData*>* family : {&nc, &oc}) {
    const CaseData* best = nullptr;
    double distance = 1e300;
    for (const CaseData* c : *family) {
      const double d = std::abs(Mean(c->path.ln_v) - level);
      if (d < distance) distance = d, best = c;
    }
    if (!best) continue;
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; k < best->path.p.size(); ++k) {
      if (!(best->path.p[k] >= 0.5)) continue;
      const double pe = ncl.EquivalentPressure(best->path.ln_v[k]);
      rows.push_back({best->path.p[k] / pe, best->path.q[k] / pe});
      x_lo = std::min(x_lo, rows.back()[0]), x_hi = std::max(x_hi, rows.back()[0]);
      y_hi = std::max(y_hi, rows.back()[1]);
    }
    path_file.Add(fmt::format("ψ_ε = 90°, {} (ln(1+e) = {:.3f})", StartLabel(ctx.cases, *best),
                              Mean(best->path.ln_v)),
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
  // The axes from the DEM's states and paths, not from a model's curve.
  SetNumber(&spec, "x_lo", x_lo / 2);
  SetNumber(&spec, "x_hi", std::max(1.1, 1.15 * x_hi));
  SetNumber(&spec, "y_lo", 1.15 * y_lo - 0.05);
  SetNumber(&spec, "y_hi", 1.15 * y_hi + 0.05);
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
  for (const StateRow* state : ctx.Select(MainStates())) {
    const StateRow& row = *state;
    if (row.kind == TableKind::kNcl || !ConstantDirectionKind(row.kind)) continue;
    by_direction[NominalOf(row)].push_back({row.p_kpa, row.ln_1_plus_e, row.psi_sigma_deg, 7.0});
  }
  std::vector<double> targets;
  for (const auto& [psi, rows] : by_direction) targets.push_back(psi);
  int picked = 0;
  for (const CaseData& c : ctx.cases) {
    if (!c.finished || !c.Serves("19") || c.path.empty() || c.sample != Sample::kMain ||
        !ctx.options.settings.IncludesCase(c.name)) {
      continue;
    }
    for (const StretchingPick& pick : PickStretchingDirections(
             c.path.psi_epsilon, c.path.p, c.path.ln_v, c.path.psi_sigma, targets)) {
      by_direction[pick.psi_epsilon_deg].push_back(
          {pick.p_kpa, pick.ln_1_plus_e, pick.psi_sigma_deg, 8.0});
      ++picked;
    }
  }
  BlockFile file({"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "point_type"});
  const std::map<double, int> colours = DirectionColours(ctx);
  std::string direction_colours;
  for (const auto& [psi, rows] : by_direction) {
    const int before = file.blocks();
    file.Add(fmt::format("ψ_ε = {}°", Short(psi)), rows);
    const auto colour = colours.find(psi);
    if (file.blocks() > before) {
      direction_colours += fmt::format("{} ", colour == colours.end() ? 8 : colour->second);
    }
  }
  if (targets.empty()) return NotDrawn(spec, "the state table has no usable asymptotic states");
  if (picked == 0) return NotDrawn(spec, "no triaxial path reaches the ψ_ε of a constant-ψ_ε path");
  file.Write(ctx.File("fig19_states.tsv"));
  Set(&spec, "n_directions", file.blocks());
  Set(&spec, "direction_titles", file.titles());
  Set(&spec, "direction_colours", direction_colours);
  spec.caption += " " + MainStates().Describe(ctx);
  return spec;
}

}  // namespace granasym::analysis::figures
