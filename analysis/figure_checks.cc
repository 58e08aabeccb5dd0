// The checks of the DEM (paper Fig. 8 and Sec. 5, Figs. 20-22): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "analysis/figure_families.h"
#include "common/hdf5_file.h"
#include "common/time_series.h"
#include "dem/run_record_names.h"

namespace granasym::analysis::figures {
namespace {

// The study's own case that a variant case (another sample) repeats: the
// study's NCL for a variant's isotropic compression from the sample, else
// the replicate-1 case of the study's sample with the same ψ_ε (or σ_r) from
// the same start.
const CaseData* Counterpart(const Context& ctx, const CaseData& variant) {
  const bool is_ncl = std::abs(variant.NominalPsiEpsilon()) < 0.5;
  if (is_ncl) return ctx.Case(1, ctx.study_ncl);
  const std::string direction = DirectionLabel(variant);
  const std::string start = StartLabel(ctx.cases, variant);
  for (const CaseData& c : ctx.cases) {
    if (c.replicate == 1 && c.finished && c.sample == Sample::kMain && !c.path.empty() &&
        DirectionLabel(c) == direction && StartLabel(ctx.cases, c) == start) {
      return &c;
    }
  }
  return nullptr;
}

// The cases of another sample (serving the figure) against their
// counterparts of the study's sample: NCLs in ln(1+e)–p and the 90° paths
// in a second panel.
FigureSpec Variants(const Context& ctx, FigureSpec spec, Sample sample,
                    const std::function<std::string(const CaseData&)>& label) {
  BlockFile ncl({"p_kpa", "ln_1_plus_e"});
  BlockFile paths({"p_kpa", "q_kpa", "psi_sigma_deg", "eps_s"});
  std::vector<const CaseData*> pairs;
  for (const CaseData* c : ctx.Serving(spec.figure, sample)) {
    const CaseData* reference = Counterpart(ctx, *c);
    if (reference && reference->finished && !reference->path.empty()) pairs.push_back(reference);
    pairs.push_back(c);
  }
  // Colour 1: the study's sample, 2: the other; one dash type per start.
  std::vector<std::string> starts;
  std::string ncl_colours, path_colours, path_dashes;
  std::string reference_title, variant_title;
  for (const CaseData* c : pairs) {
    const bool is_ncl = std::abs(c->NominalPsiEpsilon()) < 0.5;
    const int colour = c->sample == Sample::kMain ? 1 : 2;
    (colour == 1 ? reference_title : variant_title) = label(*c);
    if (is_ncl) {
      const int before = ncl.blocks();
      ncl.Add(label(*c), Rows({&c->path.p, &c->path.ln_v}));
      if (ncl.blocks() > before) ncl_colours += fmt::format("{} ", colour);
    } else {
      const std::string start = DirectionLabel(*c) + ", " + StartLabel(ctx.cases, *c);
      auto it = std::find(starts.begin(), starts.end(), start);
      if (it == starts.end()) it = starts.insert(starts.end(), start);
      const int before = paths.blocks();
      paths.Add(label(*c) + ", " + start,
                Rows({&c->path.p, &c->path.q, &c->path.psi_sigma, &c->path.eps_s}));
      if (paths.blocks() > before) {
        path_colours += fmt::format("{} ", colour);
        path_dashes += fmt::format("{} ", static_cast<int>(it - starts.begin()) + 1);
      }
    }
  }
  Set(&spec, "ncl_colours", ncl_colours);
  Set(&spec, "path_colours", path_colours);
  Set(&spec, "path_dashes", path_dashes);
  Set(&spec, "sample_titles", QuotedWords({reference_title, variant_title}));
  Set(&spec, "start_titles", QuotedWords(starts));
  if (ncl.blocks() == 0 && paths.blocks() == 0) {
    return NotDrawn(spec, "no finished case of that sample serves " + spec.figure);
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

}  // namespace

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
    histograms.Add(fmt::format("p = {} kPa", Short(Rounded(stage.validity.final_mean_stress_kpa))),
                   rows);
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

FigureSpec Fig20(const Context& ctx) {
  FigureSpec spec =
      Spec("fig20_friction", "20", "Contact friction φ = 0 against φ = 0.5 rad",
           "(a) The isotropic NCL in ln(1+e) against p and (b) the stress paths q against "
           "p of the ψ_ε = 90° tests from NC states, for the cases of another contact "
           "friction (read from their results; those serving Fig. 20) against the study's "
           "own cases of the same direction and start, replicate 1.",
           "friction.gp");
  return Variants(ctx, spec, Sample::kOtherFriction, [](const CaseData& c) {
    return "φ = " + (c.friction == 0 ? std::string("0") : Short(c.friction) + " rad");
  });
}

FigureSpec Sec52(const Context& ctx) {
  FigureSpec spec =
      Spec("sec52_time_step", "Sec. 5.2", "Time-step independence: Δt against Δt/5",
           "(a) The isotropic NCL in ln(1+e) against p and (b) ψ_σ against the shear "
           "strain ε_s of the ψ_ε = 90° path from NC 100 kPa, with the programme's time "
           "step and with a smaller one (the cases whose results have a time step below "
           "¾ of the study's, serving Sec. 5.2, against the study's own cases of the same "
           "direction and start), replicate 1.",
           "time_step.gp");
  return Variants(ctx, spec, Sample::kFineStep,
                  [](const CaseData& c) { return fmt::format("Δt = {:.3g} s", c.time_step); });
}

// The paper's Fig. 21 is da Cruz et al.'s μ*(I) from plane shear; the study's
// own counterpart is the critical-state stress ratio against I.
FigureSpec Fig21(const Context& ctx) {
  FigureSpec spec = Spec("fig21_friction_inertial", "21",
                         "Critical-state stress ratio against the inertial number",
                         "The stress ratio M = q/p of the detected isochoric (ψ_ε = 90°) and "
                         "drained triaxial asymptotic states, all replicates, against their "
                         "inertial number: each state at the geometric mean of I for the "
                         "smallest and the largest diameter, its bar from one to the other; the "
                         "study's "
                         "counterpart of the paper's Fig. 21 (da Cruz et al.'s μ*(I), which "
                         "grows with I beyond about 10^{-2}).",
                         "friction_inertial.gp");
  // Each state once: at the geometric mean of its two inertial numbers, with
  // a bar from I(d_min) to I(d_max).
  StateSelection critical;
  critical.kinds = {TableKind::kCsl, TableKind::kTriaxial};
  critical.drifting = false;
  BlockFile file({"inertial_number", "i_dmin", "i_dmax", "q_over_p", "label"});
  std::map<TableKind, std::pair<std::vector<std::vector<double>>, std::vector<std::string>>> rows;
  for (const StateRow* row : ctx.Select(critical)) {
    if (!(row->q_over_p > 0) || !(row->inertial_number_dmin > 0) ||
        !(row->inertial_number_dmax > 0)) {
      continue;
    }
    rows[row->kind].first.push_back(
        {std::sqrt(row->inertial_number_dmin * row->inertial_number_dmax),
         row->inertial_number_dmin, row->inertial_number_dmax, row->q_over_p});
    rows[row->kind].second.push_back(StateLabel(*row));
  }
  for (const auto& [kind, block] : rows) {
    file.AddLabelled(kind == TableKind::kCsl ? "isochoric (ψ_ε = 90°) critical states"
                                             : "drained triaxial critical states",
                     block.first, block.second);
  }
  if (file.blocks() == 0) {
    return NotDrawn(spec, "no detected isochoric or triaxial asymptotic state");
  }
  spec.caption += " " + critical.Describe(ctx);
  file.Write(ctx.File("fig21_friction_inertial.tsv"));
  Set(&spec, "n_blocks", file.blocks());
  Set(&spec, "block_titles", file.titles());
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
  double lowest = 1e-3;  // the stricter reference line stays inside the axis
  for (const CaseData* c : cases) {
    auto positive = [&](const std::vector<double>& i) {
      std::vector<std::vector<double>> rows;
      for (size_t k = 0; k < c->path.p.size(); ++k) {
        if (c->path.p[k] > 0 && i[k] > 0) {
          rows.push_back({c->path.p[k], i[k]});
          lowest = std::min(lowest, i[k]);
        }
      }
      return rows;
    };
    file.Add("d_{min}, " + DirectionLabel(*c), positive(c->path.i_dmin));
    file.Add("d_{max}, " + DirectionLabel(*c), positive(c->path.i_dmax));
  }
  if (file.blocks() == 0) return NotDrawn(spec, "no finished case serves Figs. 21-22");
  file.Write(ctx.File("fig22_inertial.tsv"));
  Set(&spec, "n_curves", file.blocks());
  SetNumber(&spec, "i_lo", lowest / 2);
  return spec;
}

}  // namespace granasym::analysis::figures
