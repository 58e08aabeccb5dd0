// The asymptotic states and the ASBS (paper Figs. 16-19): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/figure_families.h"
#include "common/statistics.h"

namespace granasym::analysis::figures {
namespace {

// Nominal ψ_ε of a state: the measured one, rounded to 0.1°.
double NominalOf(const StateRow& row) { return std::round(row.psi_epsilon_deg * 10) / 10; }

bool ConstantDirectionKind(TableKind kind) {
  return kind == TableKind::kNcl || kind == TableKind::kCsl || kind == TableKind::kCompression ||
         kind == TableKind::kExtension;
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

}  // namespace

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
  std::vector<double> levels = ctx.options.settings.levels;
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
  const double wanted = ctx.options.settings.fig18_level.value_or(0.58);
  const double level = std::clamp(wanted, lo, hi);
  spec.caption = fmt::format(
      "The cross-section of the ASBS at ln(1+e) = {:.3f}{} in (a) logarithmic and (b) linear "
      "p/p_e*, with the NC and OC ψ_ε = 90° paths of replicate 1 (cases serving Fig. 18) whose "
      "mean ln(1+e) is nearest to the level, each row normalised by p_e* at its own void ratio. ",
      level,
      level == wanted
          ? " (the paper's level)"
          : fmt::format(" (the paper's {:g} lies outside the states' range {:.3f}–{:.3f})", wanted,
                        lo, hi));
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

}  // namespace granasym::analysis::figures
