#include "analysis/drained_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "common/state_measures.h"
#include "common/statistics.h"

namespace granasym::analysis {
namespace {

// φ_c of a triaxial-compression stress ratio M: sin φ = 3M / (6 + M).
double FrictionAngleDeg(double m) { return std::asin(3 * m / (6 + m)) / kDegree; }

// Per (material, σ_r, ε̇_a): the replicates' means over their usable states.
std::vector<DrainedGroup> Groups(const std::vector<DrainedState>& states,
                                 const RateStudyOptions& options) {
  using GroupKey = std::tuple<DrainedMaterial, double, double>;  // material, σ_r, ε̇_a
  std::map<GroupKey, std::vector<const DrainedState*>> members;
  for (const DrainedState& s : states) {
    members[{MaterialOf(s), s.radial_stress_kpa, s.axial_strain_rate}].push_back(&s);
  }
  std::vector<DrainedGroup> groups;
  for (const auto& [key, list] : members) {
    DrainedGroup g;
    SetMaterial(std::get<0>(key), &g);
    g.radial_stress_kpa = std::get<1>(key);
    g.axial_strain_rate = std::get<2>(key);
    g.states = static_cast<int>(list.size());
    std::vector<const DrainedState*> used;
    for (const DrainedState* s : list) {
      if (DrainedUsable(*s, options)) used.push_back(s);
    }
    g.used = static_cast<int>(used.size());
    auto estimate = [&used](double DrainedState::*member) { return MeanOver(used, member); };
    g.p_kpa = estimate(&DrainedState::p_kpa);
    g.e = estimate(&DrainedState::e);
    g.ln_1_plus_e = estimate(&DrainedState::ln_1_plus_e);
    g.psi_sigma_deg = estimate(&DrainedState::psi_sigma_deg);
    g.q_over_p = estimate(&DrainedState::q_over_p);
    g.inertial_number_dmax = estimate(&DrainedState::inertial_number_dmax);
    groups.push_back(g);
  }
  return groups;
}

// The limits as I → 0 of one (material, σ_r) through the usable states of its
// groups (ascending ε̇_a), and the verdict of its two slowest rates.
DrainedLimit LimitOf(const std::vector<const DrainedGroup*>& groups,
                     const std::vector<DrainedState>& states, const RateStudyOptions& options) {
  DrainedLimit l;
  SetMaterial(MaterialOf(*groups.front()), &l);
  l.radial_stress_kpa = groups.front()->radial_stress_kpa;
  std::vector<double> x, m, lnv, lnp;
  for (const DrainedGroup* g : groups) {
    if (g->used > 0) ++l.rates;
    for (const DrainedState& s : states) {
      if (MaterialOf(s) != MaterialOf(*g) || s.radial_stress_kpa != g->radial_stress_kpa ||
          s.axial_strain_rate != g->axial_strain_rate || !DrainedUsable(s, options) ||
          !(s.inertial_number_dmax > 0)) {
        continue;
      }
      x.push_back(s.inertial_number_dmax);
      m.push_back(s.q_over_p);
      lnv.push_back(s.ln_1_plus_e);
      lnp.push_back(std::log(s.p_kpa));
    }
  }
  l.points = static_cast<int>(x.size());
  if (!x.empty()) {
    l.i_min = *std::min_element(x.begin(), x.end());
    l.i_max = *std::max_element(x.begin(), x.end());
  }
  if (l.rates >= 2) {
    const LineFit fm = FitLine(x, m), fv = FitLine(x, lnv), fp = FitLine(x, lnp);
    if (fm.valid() && fv.valid() && fp.valid()) {
      l.m = Estimate::Fitted(fm.intercept, fm.intercept_error, fm.points);
      l.m_slope = Estimate::Fitted(fm.slope, fm.slope_error, fm.points);
      l.ln_1_plus_e = Estimate::Fitted(fv.intercept, fv.intercept_error, fv.points);
      l.ln_p_kpa = Estimate::Fitted(fp.intercept, fp.intercept_error, fp.points);
    }
  }
  if (groups.size() < 2) {
    l.verdict = "undetermined";
    l.reason = "fewer than two axial rates";
    return l;
  }
  const DrainedGroup& a = *groups[0];
  const DrainedGroup& b = *groups[1];
  l.slowest = a.axial_strain_rate;
  l.next = b.axial_strain_rate;
  l.m_change = Compare(a.q_over_p, b.q_over_p);
  l.ln_1_plus_e_change = Compare(a.ln_1_plus_e, b.ln_1_plus_e);
  std::vector<std::string> missing;
  for (const DrainedGroup* g : {&a, &b}) {
    if (g->used < 2) {
      missing.push_back(
          fmt::format("axial rate {:g} 1/s: {} usable of {} states (an "
                      "interval needs 2)",
                      g->axial_strain_rate, g->used, g->states));
    }
  }
  l.verdict =
      VerdictOf({{"M", &l.m_change}, {"ln(1+e)", &l.ln_1_plus_e_change}}, missing, &l.reason);
  return l;
}

// The quasi-static critical state of one material through the limits of its σ_r.
DrainedCriticalState CriticalStateOf(const DrainedMaterial& material,
                                     const std::vector<const DrainedLimit*>& limits,
                                     double ln_reference) {
  DrainedCriticalState c;
  SetMaterial(material, &c);
  c.starts = static_cast<int>(limits.size());
  std::vector<double> ms, x, y;
  for (const DrainedLimit* l : limits) {
    ms.push_back(l->m.mean);
    x.push_back(l->ln_p_kpa.mean - ln_reference);
    y.push_back(l->ln_1_plus_e.mean);
  }
  c.m = Estimate::Of(ms);
  c.phi_c_deg = FrictionAngleOf(c.m);
  const LineFit fm = FitLine(x, ms);
  if (fm.valid()) c.m_per_ln_p = Estimate::Fitted(fm.slope, fm.slope_error, fm.points);
  const LineFit csl = FitLine(x, y);
  if (csl.valid()) {
    c.lambda = Estimate::Fitted(-csl.slope, csl.slope_error, csl.points);
    c.gamma = csl.intercept - csl.slope * ln_reference;
    c.position = Estimate::Fitted(csl.intercept, csl.intercept_error, csl.points);
  }
  return c;
}

}  // namespace

Estimate FrictionAngleOf(const Estimate& m) {
  Estimate phi = m;
  if (!std::isfinite(m.mean)) return phi;
  phi.mean = FrictionAngleDeg(m.mean);
  // dφ/dM = 18 / ((6 + M)² cos φ).
  const double derivative =
      18.0 / ((6 + m.mean) * (6 + m.mean) * std::cos(phi.mean * kDegree)) / kDegree;
  phi.standard_error = derivative * m.standard_error;
  phi.half_width = derivative * m.half_width;
  return phi;
}

std::string MaterialText(const DrainedMaterial& material) {
  const auto& [modulus, damping, ratio, fraction] = material;
  return fmt::format("E = {:g} MPa, χ = {:g}, k_t/k_n = {:g}, {}", modulus, damping, ratio,
                     fraction > 0 ? fmt::format("f = {:g}", fraction) : "a fixed time step");
}

bool DrainedUsable(const DrainedState& s, const RateStudyOptions& options) {
  return PassesFilters(s.status, s.flags, options.statuses, options) && s.p_kpa > 0 &&
         std::isfinite(s.ln_1_plus_e) && std::isfinite(s.q_over_p);
}

DrainedStudy DrainedStudy::Analyse(std::vector<DrainedState> states,
                                   const RateStudyOptions& options) {
  DrainedStudy study;
  study.states = std::move(states);
  study.groups = Groups(study.states, options);

  // Per (material, σ_r): the groups in ascending ε̇_a (map order).
  std::map<std::pair<DrainedMaterial, double>, std::vector<const DrainedGroup*>> by_start;
  for (const DrainedGroup& g : study.groups) {
    by_start[{MaterialOf(g), g.radial_stress_kpa}].push_back(&g);
  }
  for (const auto& [start, groups] : by_start) {
    study.limits.push_back(LimitOf(groups, study.states, options));
  }

  // Per material: the quasi-static critical state through the limits.
  std::map<DrainedMaterial, std::vector<const DrainedLimit*>> by_material;
  for (const DrainedLimit& l : study.limits) {
    if (l.valid() && std::isfinite(l.ln_p_kpa.mean) && std::isfinite(l.ln_1_plus_e.mean)) {
      by_material[MaterialOf(l)].push_back(&l);
    }
  }
  const double ln_reference = std::log(options.reference_p_kpa);
  for (const auto& [material, limits] : by_material) {
    study.critical.push_back(CriticalStateOf(material, limits, ln_reference));
  }
  return study;
}

std::string DrainedCriticalState::Text(double reference_p_kpa) const {
  auto pm = [](const Estimate& e, int digits) {
    return e.has_interval()
               ? fmt::format("{:.{}f} +- {:.{}f}", e.mean, digits, e.half_width, digits)
               : fmt::format("{:.{}f} (no interval)", e.mean, digits);
  };
  std::string text = fmt::format("M = {}, phi_c = {} deg from {} radial stresses", pm(m, 3),
                                 pm(phi_c_deg, 1), starts);
  if (std::isfinite(m_per_ln_p.mean)) text += fmt::format("; dM/d ln p = {}", pm(m_per_ln_p, 3));
  if (std::isfinite(lambda.mean)) {
    text += fmt::format("; CSL lambda = {}, ln(1+e) at {:g} kPa = {}", pm(lambda, 4),
                        reference_p_kpa, pm(position, 4));
  }
  return text;
}

}  // namespace granasym::analysis
