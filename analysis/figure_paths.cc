// The DEM's paths (paper Sec. 4, Figs. 9-15): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/figure_families.h"

namespace granasym::analysis::figures {
namespace {

void AddLine(BlockFile* file, const std::string& title, const NclLine& line, double p_min,
             double p_max) {
  std::vector<std::vector<double>> rows;
  for (int k = 0; k <= 20; ++k) {
    const double ln_p = std::log(p_min) + (std::log(p_max) - std::log(p_min)) * k / 20;
    rows.push_back({std::exp(ln_p), line.n - line.lambda * ln_p});
  }
  file->Add(title, rows);
}

}  // namespace

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

}  // namespace granasym::analysis::figures
