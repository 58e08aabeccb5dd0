// The DEM's paths (paper Sec. 4, Figs. 9-15): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "analysis/figure_families.h"
#include "common/statistics.h"

namespace granasym::analysis::figures {
namespace {

// The floor of the valid range of p (SPEC §8.3): rows below it are a gas's
// tail, drawn faint and never setting an axis.
constexpr double kFloorKpa = 0.5;

// The CSL ln(1+e) = Γ − λ ln p through the study's detected critical states.
LineFit CslFit(const Context& ctx) {
  std::vector<double> x, y;
  StateSelection csl;
  csl.kinds = {TableKind::kCsl};
  csl.drifting = false;
  for (const StateRow* row : ctx.Select(csl)) {
    x.push_back(std::log(row->p_kpa));
    y.push_back(row->ln_1_plus_e);
  }
  return x.size() >= 3 ? FitLine(x, y) : LineFit{};
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
  AxisRange cycle_p, cycle_v;  // panel (b): the cycles' own range
  for (const CaseData* c : cases) {
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; k < c->path.p.size(); ++k) {
      if (!(c->path.p[k] > 0)) continue;
      rows.push_back({c->path.p[k], c->path.ln_v[k]});
      p_min = std::min(p_min, c->path.p[k]);
      p_max = std::max(p_max, c->path.p[k]);
      if (cycles_of(c)) cycle_p.Add(c->path.p[k]), cycle_v.Add(c->path.ln_v[k]);
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
    file.Add(fmt::format("fitted NCL: N = {:.3f}, λ* = {:.4f}", ncl.n, ncl.lambda),
             LineRows(ncl.n, ncl.lambda, p_min, p_max, 20));
  }
  file.Write(ctx.File("fig09_paths.tsv"));
  Set(&spec, "n_paths", paths);
  Set(&spec, "has_fit", file.blocks() - paths);
  Set(&spec, "has_cycles", !cycle_p.empty() ? 1 : 0);
  if (!cycle_p.empty()) {
    const auto [lo, hi] = cycle_p.Logarithmic(0.05);
    const auto [v_lo, v_hi] = cycle_v.Linear(0.08);
    SetNumber(&spec, "cycle_p_lo", lo);
    SetNumber(&spec, "cycle_p_hi", hi);
    SetNumber(&spec, "cycle_v_lo", v_lo);
    SetNumber(&spec, "cycle_v_hi", v_hi);
    spec.caption += " (b) The cycles' range enlarged.";
  }
  return spec;
}

// A figure of path families (Figs. 10, 11, 13-15): ψ_σ–p, ln(1+e)–p,
// ψ_σ–ln(1+e). Each case is drawn as the mean of its replicates with a band
// of ± one standard error of that mean (one replicate: its own path; the
// 95 % interval, t(n−1) standard errors, is 12.7 of them for two replicates
// and would cover the figure), one colour per direction (per
// start when all share one direction) and one dash per start; its
// asymptotic states (all replicates) are marked with hover labels.
FigureSpec PathFamily(const Context& ctx, const FamilySpec& family) {
  const std::string& figure = family.figure;
  const std::string& stem = family.stem;
  StateSelection own;
  FigureSpec spec =
      Spec(stem, figure, family.title,
           family.what +
               " Paths: the mean of the replicates of each case (cases whose "
               "`figures` include " +
               figure +
               ") with a band of ± one standard error of that mean (for two replicates, their "
               "half-range), aligned on the accumulated strain as the ensemble rows "
               "of the state table (a path that stops at its asymptote is aligned at its end, "
               "so its mean starts where the shortest replicate's does; `study figures "
               "--replicates` draws every replicate); rows below p = 0.5 kPa (a gas's tail) are "
               "drawn faint "
               "and do not set the axes. (a) ψ_σ against p, (b) ln(1+e) against p, (c) ψ_σ "
               "against ln(1+e). Marks: the detector's asymptotic states of these cases, "
               "every replicate. ",
           "paths.gp");
  std::vector<const CaseData*> cases = ctx.Serving(figure);
  // An unloading case (ψ_ε = 180°) that serves the figure leads to its OC
  // starts: drawn in grey, not a family of its own.
  BlockFile unloading({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  cases.erase(
      std::remove_if(cases.begin(), cases.end(),
                     [&](const CaseData* c) {
                       if (!(std::abs(c->NominalPsiEpsilon() - 180) <= 0.5)) return false;
                       std::vector<std::vector<double>> rows;
                       for (size_t k = 0; k < c->path.p.size(); ++k) {
                         if (c->path.p[k] >= kFloorKpa) {
                           rows.push_back({c->path.p[k], c->path.ln_v[k], c->path.psi_sigma[k]});
                         }
                       }
                       unloading.Add("unloading (ψ_ε = 180°) to the OC starts", rows);
                       return true;
                     }),
      cases.end());
  bool all_isochoric = true;
  auto direction_of = [](const CaseData* c) {
    const double sigma_r = c->RadialStress();
    return std::isfinite(sigma_r) ? sigma_r : c->NominalPsiEpsilon();
  };
  auto start_key = [&](const CaseData* c) {
    const Start s = StartOf(ctx.cases, c ? *c : CaseData{});
    return std::make_tuple(s.kind == "OC" ? 1 : 0, Rounded(s.p_kpa), c ? c->rate_label : "");
  };
  std::stable_sort(cases.begin(), cases.end(), [&](const CaseData* a, const CaseData* b) {
    const double da = direction_of(a), db = direction_of(b);
    if (da != db) return da < db;
    return start_key(a) < start_key(b);
  });
  // Paths at more than one rate (a rate sweep's cases that share a
  // direction and a start) are told apart by their start's label with the
  // rate: "NC 1000 kPa, I* = 0.001".
  std::set<std::string> rates;
  for (const CaseData* c : cases) rates.insert(c->rate_label);
  const bool by_rate = rates.size() > 1;
  auto start_label = [&](const CaseData& c) {
    const std::string s = StartLabel(ctx.cases, c);
    return by_rate && !c.rate_label.empty() ? s + ", " + c.rate_label : s;
  };
  // Colour groups and dash groups, in numeric order.
  std::vector<std::string> directions, starts;
  for (const CaseData* c : cases) {
    const std::string d = DirectionLabel(*c), s = start_label(*c);
    if (std::find(directions.begin(), directions.end(), d) == directions.end()) {
      directions.push_back(d);
    }
  }
  std::vector<const CaseData*> by_start = cases;
  std::stable_sort(by_start.begin(), by_start.end(), [&](const CaseData* a, const CaseData* b) {
    return start_key(a) < start_key(b);
  });
  for (const CaseData* c : by_start) {
    const std::string s = start_label(*c);
    if (std::find(starts.begin(), starts.end(), s) == starts.end()) starts.push_back(s);
  }
  const bool colour_by_start = directions.size() == 1;
  // Dash by the start's kind (NC, OC) alone when that and the direction tell
  // every path apart (drained tests from NC and OC states at each σ_r).
  std::set<std::pair<std::string, std::string>> direction_kind;
  std::vector<std::string> kinds;
  for (const CaseData* c : cases) {
    const std::string kind = StartOf(ctx.cases, *c).kind;
    direction_kind.insert({DirectionLabel(*c), kind});
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
  }
  const bool dash_by_kind =
      !colour_by_start && direction_kind.size() == cases.size() &&
      std::none_of(kinds.begin(), kinds.end(), [](const std::string& k) { return k.empty(); });
  if (dash_by_kind) {
    std::sort(kinds.begin(), kinds.end(), [](const std::string& a, const std::string& b) {
      return (a == "NC" ? 0 : 1) < (b == "NC" ? 0 : 1);
    });
  }
  auto dash_group = [&](const CaseData& c) {
    return dash_by_kind ? StartOf(ctx.cases, c).kind + " states" : start_label(c);
  };
  std::vector<std::string> dash_groups;
  if (dash_by_kind) {
    for (const std::string& k : kinds) dash_groups.push_back(k + " states");
  } else {
    dash_groups = starts;
  }
  auto index_in = [](const std::vector<std::string>& list, const std::string& item) {
    return static_cast<int>(std::find(list.begin(), list.end(), item) - list.begin()) + 1;
  };
  BlockFile paths({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  // Each mean path's band (± one standard error) as a closed outline: the
  // upper edge forward, the lower edge back.
  BlockFile bands({"p_kpa", "psi_sigma_edge", "ln_1_plus_e_edge"});
  std::string band_colours;
  BlockFile tails({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  BlockFile replicates({"p_kpa", "ln_1_plus_e", "psi_sigma_deg"});
  AxisRange p_range, lnv_range, psi_range;
  std::string colours, dashes, replicate_colours, tail_colours;
  std::set<std::string> names;
  int mean_paths = 0, single_paths = 0;
  for (const CaseData* c : cases) {
    all_isochoric = all_isochoric && std::abs(c->NominalPsiEpsilon() - 90) < 0.5;
    names.insert(c->name);
    const std::string d = DirectionLabel(*c), s = start_label(*c);
    const int colour = colour_by_start ? index_in(starts, s) : index_in(directions, d);
    const int dash = colour_by_start ? 1 : index_in(dash_groups, dash_group(*c));
    const MeanCasePath mean = MeanPathOf(ctx.cases, c->name);
    std::vector<double> p = c->path.p, ln_v = c->path.ln_v, psi = c->path.psi_sigma;
    std::vector<double> psi_band(p.size(), 0.0), lnv_band(p.size(), 0.0);
    if (mean.paths >= 2) {
      p = mean.p, ln_v = mean.ln_v, psi = mean.psi_sigma;
      // The mean path's bands are 95 % half-widths: one standard error is
      // that over Student's t for n − 1 degrees of freedom.
      const double t = StudentT95(mean.paths - 1);
      psi_band.assign(p.size(), 0.0), lnv_band.assign(p.size(), 0.0);
      for (size_t k = 0; k < p.size(); ++k) {
        psi_band[k] = mean.psi_sigma_band[k] / t;
        lnv_band[k] = mean.ln_v_band[k] / t;
      }
      ++mean_paths;
    } else {
      ++single_paths;
    }
    std::vector<std::vector<double>> valid, tail, upper, lower;
    for (size_t k = 0; k < p.size(); ++k) {
      const double bp = std::isfinite(psi_band[k]) ? psi_band[k] : 0.0;
      const double bv = std::isfinite(lnv_band[k]) ? lnv_band[k] : 0.0;
      if (p[k] >= kFloorKpa) {
        valid.push_back({p[k], ln_v[k], psi[k]});
        upper.push_back({p[k], psi[k] + bp, ln_v[k] + bv});
        lower.push_back({p[k], psi[k] - bp, ln_v[k] - bv});
        p_range.Add(p[k]);
        lnv_range.Add(ln_v[k]);
        psi_range.Add(psi[k]);
      } else if (p[k] > 0) {
        tail.push_back({p[k], ln_v[k], psi[k]});
      }
      // A tail is drawn from the last valid row on, so that it joins the path.
      if (p[k] < kFloorKpa && k > 0 && p[k - 1] >= kFloorKpa) {
        tail.insert(tail.end() - (p[k] > 0 ? 1 : 0), {p[k - 1], ln_v[k - 1], psi[k - 1]});
      }
    }
    const int before = paths.blocks();
    paths.Add(d + ", " + s, valid);
    if (paths.blocks() == before) continue;
    colours += fmt::format("{} ", colour);
    dashes += fmt::format("{} ", dash);
    if (mean.paths >= 2) {
      upper.insert(upper.end(), lower.rbegin(), lower.rend());
      const int bands_before = bands.blocks();
      bands.Add(d + ", " + s, upper);
      if (bands.blocks() > bands_before) band_colours += fmt::format("{} ", colour);
    }
    const int tails_before = tails.blocks();
    tails.Add(d + ", " + s, tail);
    if (tails.blocks() > tails_before) tail_colours += fmt::format("{} ", colour);
    if (ctx.options.settings.replicates) {
      for (const CaseData& r : ctx.cases) {
        if (r.name != c->name || !r.finished || r.path.empty()) continue;
        std::vector<std::vector<double>> rows;
        for (size_t k = 0; k < r.path.p.size(); ++k) {
          if (r.path.p[k] >= kFloorKpa) {
            rows.push_back({r.path.p[k], r.path.ln_v[k], r.path.psi_sigma[k]});
          }
        }
        const int b = replicates.blocks();
        replicates.Add(fmt::format("{} replicate {}", c->name, r.replicate), rows);
        if (replicates.blocks() > b) replicate_colours += fmt::format("{} ", colour);
      }
    }
  }
  if (paths.blocks() == 0) return NotDrawn(spec, "no finished case serves Fig. " + figure);
  // The states: detected filled, drifting open, with hover labels; then the
  // reference states (grey squares) of other figures.
  own.cases = names;
  BlockFile marks({"p_kpa", "ln_1_plus_e", "psi_sigma_deg", "label"});
  std::vector<std::vector<double>> detected, drifting;
  std::vector<std::string> detected_labels, drifting_labels;
  for (const StateRow* row : ctx.Select(own)) {
    const bool is_detected = row->status == TableStatus::kDetected;
    (is_detected ? detected : drifting)
        .push_back({row->p_kpa, row->ln_1_plus_e, row->psi_sigma_deg});
    (is_detected ? detected_labels : drifting_labels).push_back(StateLabel(*row));
    p_range.Add(row->p_kpa);
    lnv_range.Add(row->ln_1_plus_e);
    psi_range.Add(row->psi_sigma_deg);
  }
  marks.AddLabelled("asymptotic states (detected)", detected, detected_labels);
  marks.AddLabelled("still drifting at the stage end", drifting, drifting_labels);
  const int own_marks = marks.blocks();
  for (const auto& [kind, label] : family.reference_kinds) {
    StateSelection reference;
    reference.kinds = {kind};
    reference.drifting = false;
    std::vector<std::vector<double>> rows;
    std::vector<std::string> labels;
    for (const StateRow* row : ctx.Select(reference)) {
      if (names.count(row->case_name)) continue;
      rows.push_back({row->p_kpa, row->ln_1_plus_e, row->psi_sigma_deg});
      labels.push_back(StateLabel(*row));
    }
    const int before = marks.blocks();
    marks.AddLabelled(label, rows, labels);
    if (marks.blocks() > before) spec.caption += "Grey squares: " + label + ". ";
  }
  spec.caption += own.Describe(ctx);
  // The fitted lines of panel (b): the study's NCL and, where the paper
  // draws it, the CSL through the detected critical states.
  BlockFile lines({"p_kpa", "ln_1_plus_e"});
  if (!p_range.empty()) {
    const auto [p_lo, p_hi] = p_range.Logarithmic();
    auto add_line = [&](const std::string& title, double n, double lambda) {
      lines.Add(title, LineRows(n, lambda, p_lo, p_hi, 40));
    };
    const NclLine ncl = ctx.StudyNcl(1);
    if (ncl.valid()) {
      add_line(fmt::format("NCL (replicate 1): N = {:.3f}, λ* = {:.4f}", ncl.n, ncl.lambda), ncl.n,
               ncl.lambda);
    }
    const LineFit csl = family.draw_csl ? CslFit(ctx) : LineFit{};
    if (csl.valid()) {
      add_line(fmt::format("CSL (detected ψ_ε = 90° states): Γ = {:.3f}, λ = {:.4f}", csl.intercept,
                           -csl.slope),
               csl.intercept, -csl.slope);
    }
  }
  paths.Write(ctx.File(stem + "_paths.tsv"));
  tails.Write(ctx.File(stem + "_tails.tsv"));
  bands.Write(ctx.File(stem + "_bands.tsv"));
  unloading.Write(ctx.File(stem + "_unloading.tsv"));
  marks.Write(ctx.File(stem + "_states.tsv"));
  lines.Write(ctx.File(stem + "_lines.tsv"));
  if (replicates.blocks() > 0) replicates.Write(ctx.File(stem + "_replicates.tsv"));
  if (mean_paths > 0 && single_paths > 0) {
    spec.caption += fmt::format(" {} of the {} cases have one replicate: their own path.",
                                single_paths, mean_paths + single_paths);
  }
  Set(&spec, "stem", stem);
  Set(&spec, "n_paths", paths.blocks());
  Set(&spec, "path_colours", colours);
  Set(&spec, "path_dashes", dashes);
  Set(&spec, "colour_titles", QuotedWords(colour_by_start ? starts : directions));
  Set(&spec, "dash_titles",
      !colour_by_start && dash_groups.size() > 1 ? QuotedWords(dash_groups) : "");
  Set(&spec, "colour_heading", colour_by_start ? directions.front() + ", from" : "direction");
  Set(&spec, "n_marks", marks.blocks());
  Set(&spec, "mark_titles", marks.titles());
  Set(&spec, "first_open", detected.empty() ? 0 : 1);
  Set(&spec, "n_own_marks", own_marks);
  Set(&spec, "n_lines", lines.blocks());
  Set(&spec, "line_titles", lines.titles());
  Set(&spec, "n_replicates", replicates.blocks());
  Set(&spec, "replicate_colours", replicate_colours);
  Set(&spec, "n_bands", bands.blocks());
  // An isochoric path keeps its void ratio: its band in (b) would only be
  // the replicates' spread of e drawn across the whole range of p.
  Set(&spec, "bands_in_b", all_isochoric ? 0 : 1);
  Set(&spec, "n_unloading", unloading.blocks());
  if (unloading.blocks() > 0) spec.caption += "Grey lines: the unloading to the OC starts. ";
  Set(&spec, "band_colours", band_colours);
  Set(&spec, "n_tails", tails.blocks());
  Set(&spec, "tail_colours", tail_colours);
  const auto [p_lo, p_hi] = p_range.Logarithmic();
  const auto [v_lo, v_hi] = lnv_range.Linear();
  const auto [s_lo, s_hi] = psi_range.Linear();
  SetNumber(&spec, "p_lo", p_lo);
  SetNumber(&spec, "p_hi", p_hi);
  SetNumber(&spec, "lnv_lo", v_lo);
  SetNumber(&spec, "lnv_hi", v_hi);
  SetNumber(&spec, "psi_lo", s_lo);
  SetNumber(&spec, "psi_hi", s_hi);
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
  // In numeric order of σ_r, then NC before OC: one colour per σ_r, solid
  // from NC and dashed from OC states.
  std::vector<const CaseData*> cases = ctx.Serving("12");
  auto radial = [](const CaseData* c) { return c->RadialStress(); };
  auto is_oc = [&](const CaseData* c) { return StartOf(ctx.cases, *c).kind == "OC"; };
  std::stable_sort(cases.begin(), cases.end(), [&](const CaseData* a, const CaseData* b) {
    return radial(a) != radial(b) ? radial(a) < radial(b) : is_oc(a) < is_oc(b);
  });
  std::vector<double> radials;
  std::string colours, dashes;
  for (const CaseData* c : cases) {
    const int before = paths.blocks();
    paths.Add(DirectionLabel(*c) + ", " + StartLabel(ctx.cases, *c),
              Rows({&c->path.eps_s, &c->path.psi_sigma, &c->path.psi_epsilon}));
    if (paths.blocks() == before) continue;
    if (std::find(radials.begin(), radials.end(), radial(c)) == radials.end()) {
      radials.push_back(radial(c));
    }
    colours += fmt::format("{} ", radials.size());
    dashes += is_oc(c) ? "2 " : "1 ";
  }
  Set(&spec, "path_colours", colours);
  Set(&spec, "path_dashes", dashes);
  if (paths.blocks() == 0) return NotDrawn(spec, "no finished case serves Fig. 12");
  paths.Write(ctx.File("fig12_paths.tsv"));
  Set(&spec, "n_paths", paths.blocks());
  return spec;
}

}  // namespace granasym::analysis::figures
