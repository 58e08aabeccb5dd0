#include "analysis/rate_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "common/error.h"
#include "common/statistics.h"

namespace granasym::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The line of (E, ψ_ε, rule, rate), or nullptr.
const RateLine* FindLine(const std::vector<RateLine>& lines, double youngs_modulus_mpa,
                         double psi_epsilon_deg, dem::RateRule rule, double rate) {
  for (const RateLine& l : lines) {
    if (l.youngs_modulus_mpa == youngs_modulus_mpa && l.psi_epsilon_deg == psi_epsilon_deg &&
        l.rule == rule && l.rate == rate) {
      return &l;
    }
  }
  return nullptr;
}

// "2 rate_dependent, 1 undetermined": the verdicts of a list, counted.
template <typename List>
std::string VerdictCounts(const List& list, const char* separator) {
  std::map<std::string, int> n;
  for (const auto& v : list) ++n[v.verdict];
  std::string text;
  for (const auto& [verdict, k] : n) {
    text += fmt::format("{}{} {}", text.empty() ? "" : separator, k, verdict);
  }
  return text;
}

std::string RateText(dem::RateRule rule, double rate) {
  return rule == dem::RateRule::kInertial ? fmt::format("I* = {:g}", rate)
                                          : fmt::format("‖D‖ = {:g} 1/s", rate);
}

// Lines per (E, ψ_ε, rate) through the usable states of every start.
void FitLines(RateStudy* study) {
  using LineKey = std::tuple<double, double, dem::RateRule, double>;
  std::map<LineKey, std::vector<const RateState*>> line_members;
  for (const RateState& s : study->states) {
    if (study->Usable(s)) {
      line_members[{s.youngs_modulus_mpa, s.psi_epsilon_deg, s.rule, s.rate()}].push_back(&s);
    }
  }
  const double reference_p = study->options.reference_p_kpa;
  const double ln_reference = std::log(reference_p);
  for (const auto& [key, list] : line_members) {
    RateLine line;
    std::tie(line.youngs_modulus_mpa, line.psi_epsilon_deg, line.rule, line.rate) = key;
    if (std::any_of(list.begin(), list.end(),
                    [](const RateState* s) { return s->HasPathLine(); })) {
      // ψ_ε = 0°: the mean of the paths' own lines; the position over the
      // paths whose range holds the reference p.
      std::vector<double> ns, lambdas, positions;
      line.p_min_kpa = std::numeric_limits<double>::infinity();
      for (const RateState* s : list) {
        if (!s->HasPathLine()) continue;
        ns.push_back(s->path_n);
        lambdas.push_back(s->path_lambda);
        line.p_min_kpa = std::min(line.p_min_kpa, s->path_p_min_kpa);
        line.p_max_kpa = std::max(line.p_max_kpa, s->path_p_max_kpa);
        if (s->path_p_min_kpa <= reference_p && reference_p <= s->path_p_max_kpa) {
          positions.push_back(s->path_n - s->path_lambda * ln_reference);
        }
      }
      line.points = static_cast<int>(ns.size());
      line.n = Estimate::Of(ns).mean;
      line.lambda = Estimate::Of(lambdas).mean;
      line.position = Estimate::Of(positions);
      study->lines.push_back(line);
      continue;
    }
    std::set<double> starts;
    std::vector<double> x, y;
    for (const RateState* s : list) {
      starts.insert(s->start_p_kpa);
      x.push_back(std::log(s->p_kpa) - ln_reference);
      y.push_back(s->ln_1_plus_e);
    }
    line.points = static_cast<int>(x.size());
    line.p_min_kpa = std::exp(*std::min_element(x.begin(), x.end()) + ln_reference);
    line.p_max_kpa = std::exp(*std::max_element(x.begin(), x.end()) + ln_reference);
    const LineFit fit = FitLine(x, y);
    if (starts.size() >= 2 && fit.valid()) {
      line.lambda = -fit.slope;
      line.n = fit.intercept - fit.slope * ln_reference;  // at p = 1 kPa
      line.position = Estimate::Fitted(fit.intercept, fit.intercept_error, fit.points);
    }
    study->lines.push_back(line);
  }
}

// OCR against the NCL of the same E and rate (the ψ_ε = 0° line of that
// rate): p_e*/p with ln(1+e) = N − λ ln(p_e* / 1 kPa) at the state's
// ln(1+e), where p_e* lies in the line's p range (the NCL of frictional
// spheres is curved: the line is no NCL outside it).
void SetSameRateOcr(RateStudy* study) {
  for (RateState& s : study->states) {
    s.ocr_same_rate = kNaN;
    const RateLine* l = FindLine(study->lines, s.youngs_modulus_mpa, 0, s.rule, s.rate());
    if (l && l->valid() && l->lambda > 0 && s.p_kpa > 0) {
      const double p_e = std::exp((l->n - s.ln_1_plus_e) / l->lambda);
      if (p_e >= l->p_min_kpa && p_e <= l->p_max_kpa) s.ocr_same_rate = p_e / s.p_kpa;
    }
  }
}

// Groups: the replicates of one (E, ψ_ε, p_0, rate).
void FormGroups(RateStudy* study) {
  std::map<RateKey, std::vector<const RateState*>> members;
  for (const RateState& s : study->states) members[KeyOf(s)].push_back(&s);
  for (const auto& [key, list] : members) {
    RateGroup group;
    group.key = key;
    group.states = static_cast<int>(list.size());
    std::vector<const RateState*> used;
    for (const RateState* s : list) {
      if (study->Usable(*s)) used.push_back(s);
    }
    group.used = static_cast<int>(used.size());
    for (const RateState* s : list) group.liquefied += IsLiquefied(s->status, s->flags);
    auto estimate = [&used](double RateState::*member) { return MeanOver(used, member); };
    group.p_kpa = estimate(&RateState::p_kpa);
    group.e = estimate(&RateState::e);
    group.ln_1_plus_e = estimate(&RateState::ln_1_plus_e);
    group.psi_sigma_deg = estimate(&RateState::psi_sigma_deg);
    group.q_over_p = estimate(&RateState::q_over_p);
    group.ocr = estimate(&RateState::ocr);
    group.ocr_same_rate = estimate(&RateState::ocr_same_rate);
    group.inertial_number_dmin = estimate(&RateState::inertial_number_dmin);
    group.inertial_number_dmax = estimate(&RateState::inertial_number_dmax);
    group.stiffness_number = estimate(&RateState::stiffness_number);
    study->groups.push_back(group);
  }
}

// The quasi-static limits of one (E, ψ_ε, p_0) whose inertial groups are
// `groups` (ascending I*): the line through the states of the smallest I*
// with usable states, per quantity.
void FitQuasiStatic(RateStudy* study, const std::vector<const RateGroup*>& groups) {
  const RateKey& start = groups.front()->key;
  std::vector<const RateGroup*> fitted;
  for (const RateGroup* g : groups) {
    if (g->used > 0 && static_cast<int>(fitted.size()) < study->options.fit_rates) {
      fitted.push_back(g);
    }
  }
  for (const char* quantity : {"psi_sigma_deg", "q_over_p", "ln_1_plus_e"}) {
    const std::string name = quantity;
    double RateState::*member = name == "psi_sigma_deg" ? &RateState::psi_sigma_deg
                                : name == "q_over_p"    ? &RateState::q_over_p
                                                        : &RateState::ln_1_plus_e;
    QuasiStaticFit fit;
    fit.youngs_modulus_mpa = start.youngs_modulus_mpa;
    fit.psi_epsilon_deg = start.psi_epsilon_deg;
    fit.start_p_kpa = start.start_p_kpa;
    fit.quantity = name;
    std::vector<double> x, y;
    for (const RateGroup* g : fitted) {
      fit.rates.push_back(g->key.rate);
      for (const RateState& s : study->states) {
        if (!(KeyOf(s) == g->key) || !study->Usable(s)) continue;
        if (!(s.inertial_number_dmax > 0) || !std::isfinite(s.*member)) continue;
        x.push_back(s.inertial_number_dmax);
        y.push_back(s.*member);
      }
    }
    fit.points = static_cast<int>(x.size());
    if (!x.empty()) {
      fit.i_min = *std::min_element(x.begin(), x.end());
      fit.i_max = *std::max_element(x.begin(), x.end());
    }
    if (fitted.size() >= 2) {
      const LineFit line = FitLine(x, y);
      if (line.valid()) {
        fit.limit = Estimate::Fitted(line.intercept, line.intercept_error, line.points);
        fit.slope = Estimate::Fitted(line.slope, line.slope_error, line.points);
      }
    }
    study->quasi_static.push_back(fit);
  }
}

// Rate independence of one (E, ψ_ε, p_0): its two smallest I* (`a`, `b`) of
// the programme, whatever they reached.
RateVerdict RateIndependence(const RateStudy& study, const RateGroup& a, const RateGroup& b) {
  RateVerdict v;
  v.youngs_modulus_mpa = a.key.youngs_modulus_mpa;
  v.psi_epsilon_deg = a.key.psi_epsilon_deg;
  v.start_p_kpa = a.key.start_p_kpa;
  v.smallest = a.key.rate;
  v.next = b.key.rate;
  v.ln_v_smallest = a.ln_1_plus_e;
  v.ln_v_next = b.ln_1_plus_e;
  v.psi_smallest = a.psi_sigma_deg;
  v.psi_next = b.psi_sigma_deg;
  v.ln_1_plus_e = Compare(a.ln_1_plus_e, b.ln_1_plus_e);
  v.psi_sigma = Compare(a.psi_sigma_deg, b.psi_sigma_deg);
  std::vector<std::string> missing;
  for (const RateGroup* g : {&a, &b}) {
    if (g->used < 2) {
      missing.push_back(
          fmt::format("I* = {:g}: {} (an interval needs 2)", g->key.rate, g->UsableText()));
    }
  }
  const double e_mpa = v.youngs_modulus_mpa;
  const RateLine* csl_a = FindLine(study.lines, e_mpa, 90.0, dem::RateRule::kInertial, a.key.rate);
  const RateLine* csl_b = FindLine(study.lines, e_mpa, 90.0, dem::RateRule::kInertial, b.key.rate);
  if (csl_a) v.csl_smallest = csl_a->position;
  if (csl_b) v.csl_next = csl_b->position;
  v.csl_position = Compare(v.csl_smallest, v.csl_next);
  for (const auto& [line, rate] : {std::pair{csl_a, a.key.rate}, std::pair{csl_b, b.key.rate}}) {
    if (!line || !line->position.has_interval()) {
      missing.push_back(fmt::format(
          "no CSL with an interval at I* = {:g}, E = {:g} MPa (psi_epsilon = 90 deg states of "
          "at least two starts, three points)",
          rate, e_mpa));
    }
  }
  v.verdict = VerdictOf({{"ln(1+e)", &v.ln_1_plus_e},
                         {"psi_sigma", &v.psi_sigma},
                         {"the CSL position", &v.csl_position}},
                        missing, &v.reason);
  return v;
}

// One step of an extension sweep: group g's σ_r/p = 1 − (q/p)/3 and its status.
ExtensionStep StepOf(const ExtensionLimit& sweep, double psi, const RateGroup& g) {
  ExtensionStep step;
  step.youngs_modulus_mpa = sweep.youngs_modulus_mpa;
  step.start_p_kpa = sweep.start_p_kpa;
  step.psi_epsilon_deg = psi;
  step.rule = sweep.rule;
  step.rate = sweep.rate;
  step.states = g.states;
  step.used = g.used;
  step.liquefied = g.liquefied;
  step.sigma_r_over_p = g.q_over_p;
  step.sigma_r_over_p.mean = 1.0 - g.q_over_p.mean / 3.0;
  step.sigma_r_over_p.standard_error = g.q_over_p.standard_error / 3.0;
  step.sigma_r_over_p.half_width = g.q_over_p.half_width / 3.0;
  step.psi_sigma_deg = g.psi_sigma_deg;
  step.p_kpa = g.p_kpa;
  step.ln_1_plus_e = g.ln_1_plus_e;
  const Estimate& r = step.sigma_r_over_p;
  if (2 * step.liquefied > step.states) {
    step.status = "liquefied";
  } else if (step.used >= 2 && r.has_interval()) {
    step.status = r.mean - r.half_width > 0 ? "asymptote" : "limit_d";
  } else {
    step.status = "undetermined";
  }
  return step;
}

// ψ_ε(d): the root of the least-squares line σ_r/p = a + b ψ_ε through the
// usable states of the steps `through`, x centred on the points' mean (so
// that a and b are uncorrelated), with its delta-method interval.
Estimate LimitRoot(const RateStudy& study, const ExtensionLimit& sweep,
                   const std::vector<double>& through) {
  std::vector<double> x, y;
  for (const RateState& s : study.states) {
    const bool in_step = std::any_of(through.begin(), through.end(), [&](double step_psi) {
      return KeyOf(s) ==
             RateKey{sweep.youngs_modulus_mpa, step_psi, sweep.start_p_kpa, sweep.rule, sweep.rate};
    });
    if (!in_step || !study.Usable(s) || !std::isfinite(s.q_over_p)) continue;
    x.push_back(s.psi_epsilon_deg);
    y.push_back(1.0 - s.q_over_p / 3.0);
  }
  double centre = 0;
  for (double v : x) centre += v / static_cast<double>(std::max<size_t>(x.size(), 1));
  for (double& v : x) v -= centre;
  const LineFit fit = FitLine(x, y);
  if (!fit.valid() || !(fit.slope < 0)) return Estimate{};
  const double offset = -fit.intercept / fit.slope;
  const double se = std::sqrt(fit.intercept_error * fit.intercept_error +
                              offset * offset * fit.slope_error * fit.slope_error) /
                    std::abs(fit.slope);
  return Estimate::Fitted(centre + offset, se, fit.points);
}

// §3: the extension sweeps, their steps and where each ends.
void AnalyseExtension(RateStudy* study) {
  // Per (E, rule, rate, p_0): the groups at ψ_ε ≥ 90° (map order: ψ_ε ascending).
  using SweepKey = std::tuple<double, int, double, double>;
  std::map<SweepKey, std::map<double, const RateGroup*>> sweeps;
  for (const RateGroup& g : study->groups) {
    if (g.key.psi_epsilon_deg < 90.0) continue;
    sweeps[{g.key.youngs_modulus_mpa, static_cast<int>(g.key.rule), g.key.rate, g.key.start_p_kpa}]
          [g.key.psi_epsilon_deg] = &g;
  }
  for (const auto& [key, groups] : sweeps) {
    if (groups.rbegin()->first <= 90.0) continue;  // no extension step
    ExtensionLimit limit;
    limit.youngs_modulus_mpa = std::get<0>(key);
    limit.rule = static_cast<dem::RateRule>(std::get<1>(key));
    limit.rate = std::get<2>(key);
    limit.start_p_kpa = std::get<3>(key);
    limit.steps = static_cast<int>(groups.size());
    limit.psi_max_deg = groups.rbegin()->first;
    std::vector<double> asymptote_steps;  // ψ_ε of the asymptote steps so far
    for (const auto& [psi, g] : groups) {
      const ExtensionStep step = StepOf(limit, psi, *g);
      study->extension_steps.push_back(step);
      if (!limit.result.empty()) continue;  // the sweep's end is found; later steps are listed
      if (step.status == "asymptote") {
        limit.last_asymptote_deg = psi;
        asymptote_steps.push_back(psi);
      } else if (step.status == "liquefied") {
        limit.result = "liquefied";
        limit.liquefied_at_deg = psi;
      } else if (step.status == "limit_d") {
        limit.result = "limit_d";
        limit.limit_step_deg = psi;
        // The line through this step and the last two asymptote steps.
        std::vector<double> through = {psi};
        for (size_t k = asymptote_steps.size(); k-- > 0 && through.size() < 3;) {
          through.push_back(asymptote_steps[k]);
        }
        limit.psi_d_deg = LimitRoot(*study, limit, through);
      }
    }
    if (limit.result.empty()) {
      const std::string last = study->extension_steps.back().status;
      limit.result = last == "asymptote" ? "not_reached" : "undetermined";
    }
    study->extension_limits.push_back(limit);
  }
}

// §1: the other moduli against the reference, per start and rate.
void AnalyseStiffness(RateStudy* study) {
  const double reference = study->ReferenceModulus();
  for (const RateGroup& g : study->groups) {
    if (g.key.youngs_modulus_mpa == reference) continue;
    RateKey key = g.key;
    key.youngs_modulus_mpa = reference;
    const RateGroup* r = study->Find(key);
    if (!r) continue;
    StiffnessComparison c;
    c.youngs_modulus_mpa = g.key.youngs_modulus_mpa;
    c.reference_modulus_mpa = reference;
    c.psi_epsilon_deg = g.key.psi_epsilon_deg;
    c.start_p_kpa = g.key.start_p_kpa;
    c.rule = g.key.rule;
    c.rate = g.key.rate;
    c.psi_reference = r->psi_sigma_deg;
    c.psi_other = g.psi_sigma_deg;
    c.kappa_reference = r->stiffness_number;
    c.kappa_other = g.stiffness_number;
    c.psi_sigma = Compare(c.psi_reference, c.psi_other);
    std::vector<std::string> missing;
    for (const RateGroup* x : {r, &g}) {
      if (x->used < 2) {
        missing.push_back(fmt::format("E = {:g} MPa: {} (an interval needs 2)",
                                      x->key.youngs_modulus_mpa, x->UsableText()));
      }
    }
    const RateLine* line_r = FindLine(study->lines, reference, 90, c.rule, c.rate);
    const RateLine* line_o = FindLine(study->lines, c.youngs_modulus_mpa, 90, c.rule, c.rate);
    if (line_r) c.csl_reference = line_r->position;
    if (line_o) c.csl_other = line_o->position;
    c.csl_position = Compare(c.csl_reference, c.csl_other);
    for (const auto& [line, e_mpa] :
         {std::pair{line_r, reference}, std::pair{line_o, c.youngs_modulus_mpa}}) {
      if (!line || !line->position.has_interval()) {
        missing.push_back(fmt::format("no CSL with an interval at E = {:g} MPa, {}", e_mpa,
                                      RateText(c.rule, c.rate)));
      }
    }
    c.verdict = VerdictOf({{"psi_sigma", &c.psi_sigma}, {"the CSL position", &c.csl_position}},
                          missing, &c.reason, "stiffness");
    study->stiffness.push_back(c);
  }
}

}  // namespace

bool RateKey::operator<(const RateKey& other) const {
  return std::tie(youngs_modulus_mpa, psi_epsilon_deg, start_p_kpa, rule, rate) <
         std::tie(other.youngs_modulus_mpa, other.psi_epsilon_deg, other.start_p_kpa, other.rule,
                  other.rate);
}

std::string RateKey::RateLabel() const { return RateText(rule, rate); }

RateKey KeyOf(const RateState& state) {
  return RateKey{state.youngs_modulus_mpa, state.psi_epsilon_deg, state.start_p_kpa, state.rule,
                 state.rate()};
}

bool RateStudy::Usable(const RateState& s) const {
  const bool isotropic = s.kind == TableKind::kNcl;
  if (!PassesFilters(s.status, s.flags, isotropic ? options.ncl_statuses : options.statuses,
                     options)) {
    return false;
  }
  return s.p_kpa > 0 && std::isfinite(s.ln_1_plus_e) && std::isfinite(s.psi_sigma_deg);
}

const RateGroup* RateStudy::Find(const RateKey& key) const {
  for (const RateGroup& g : groups) {
    if (g.key == key) return &g;
  }
  return nullptr;
}

double RateStudy::ReferenceModulus() const {
  std::map<double, int> count;
  for (const RateGroup& g : groups) ++count[g.key.youngs_modulus_mpa];
  // A study of drained cases alone (e.g. what sets M, issue 39 §2): theirs.
  if (count.empty()) {
    for (const DrainedGroup& g : drained.groups) ++count[g.youngs_modulus_mpa];
  }
  double best = kNaN;
  int most = 0;
  for (const auto& [modulus, n] : count) {
    if (n >= most) {
      most = n;
      best = modulus;
    }
  }
  return best;
}

bool RateStudy::Usable(const DrainedState& s) const { return DrainedUsable(s, options); }

RateStudy RateStudy::Analyse(std::vector<RateState> states, const RateStudyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("rate study options: " + why);
  RateStudy study;
  study.options = options;
  study.states = std::move(states);
  FitLines(&study);
  SetSameRateOcr(&study);
  FormGroups(&study);
  // Per (E, ψ_ε, p_0): the inertial groups in ascending I*.
  using StartKey = std::tuple<double, double, double>;
  std::map<StartKey, std::vector<const RateGroup*>> by_start;
  for (const RateGroup& g : study.groups) {
    if (g.key.rule != dem::RateRule::kInertial) continue;
    by_start[{g.key.youngs_modulus_mpa, g.key.psi_epsilon_deg, g.key.start_p_kpa}].push_back(&g);
  }
  for (const auto& [start, groups] : by_start) {
    FitQuasiStatic(&study, groups);
    if (groups.size() >= 2)
      study.verdicts.push_back(RateIndependence(study, *groups[0], *groups[1]));
  }
  AnalyseExtension(&study);
  AnalyseStiffness(&study);
  return study;
}

std::string RateGroup::UsableText() const {
  return fmt::format("{} usable of {} states{}", used, states,
                     liquefied > 0 ? fmt::format(" ({} liquefied)", liquefied) : std::string());
}

std::string ExtensionLimit::Text() const {
  const std::string last =
      std::isfinite(last_asymptote_deg)
          ? fmt::format("asymptotes up to psi_epsilon = {:g} deg", last_asymptote_deg)
          : std::string("no asymptote at psi_epsilon > 90 deg before it");
  if (result == "liquefied") {
    return fmt::format("liquefied at psi_epsilon = {:g} deg ({})", liquefied_at_deg, last);
  }
  if (result == "limit_d") {
    const std::string bracket =
        std::isfinite(last_asymptote_deg)
            ? fmt::format("between {:g} and {:g} deg", last_asymptote_deg, limit_step_deg)
            : fmt::format("at or below {:g} deg", limit_step_deg);
    if (psi_d_deg.has_interval()) {
      return fmt::format("psi_epsilon(d) = {:.1f} +- {:.1f} deg (sigma_r/p reaches 0 {})",
                         psi_d_deg.mean, psi_d_deg.half_width, bracket);
    }
    return fmt::format("psi_epsilon(d) {} (sigma_r/p zero within its interval at {:g} deg)",
                       bracket, limit_step_deg);
  }
  if (result == "not_reached") {
    return fmt::format("sigma_r/p > 0 at every psi_epsilon up to {:g} deg: the limit d lies beyond",
                       psi_max_deg);
  }
  return fmt::format("undetermined up to psi_epsilon = {:g} deg ({})", psi_max_deg, last);
}

std::vector<std::string> RateStudy::Answers() const {
  std::vector<std::string> answers;
  auto pm = [](const Estimate& e, int digits) {
    return e.has_interval() ? fmt::format("{:.{}f} ± {:.{}f}", e.mean, digits, e.half_width, digits)
                            : fmt::format("{:.{}f} (no interval)", e.mean, digits);
  };
  // Materials beyond E (the study of what sets M, issue 39 §2): the
  // critical state of each at each rate, with its intervals.
  std::set<std::tuple<double, double, double>> beyond_modulus;
  for (const DrainedGroup& g : drained.groups) {
    beyond_modulus.insert({g.local_damping, g.stiffness_ratio, g.time_step_fraction});
  }
  for (const DrainedGroup& g : drained.groups) {
    if (beyond_modulus.size() < 2 || g.used == 0) continue;
    answers.push_back(fmt::format(
        "Drained critical state, {}, σ_r = {:g} kPa, I(d_max) = {:.2g}: M = {}, φ_c = {}°, "
        "ln(1+e) = {} at p = {:.0f} kPa ({} of {} replicates).",
        MaterialText(MaterialOf(g)), g.radial_stress_kpa, g.inertial_number_dmax.mean,
        pm(g.q_over_p, 3), pm(FrictionAngleOf(g.q_over_p), 1), pm(g.ln_1_plus_e, 4), g.p_kpa.mean,
        g.used, g.states));
  }
  for (const DrainedCriticalState& c : drained.critical) {
    answers.push_back(fmt::format(
        "Quasi-static critical state (drained triaxial compression extrapolated to I → 0 at {} "
        "radial stresses, {}): M = {}, φ_c = {}°{}.",
        c.starts, MaterialText(MaterialOf(c)), pm(c.m, 3), pm(c.phi_c_deg, 1),
        std::isfinite(c.lambda.mean)
            ? fmt::format("; CSL λ = {}, ln(1+e) at {:g} kPa = {}", pm(c.lambda, 4),
                          options.reference_p_kpa, pm(c.position, 4))
            : std::string()));
    if (std::isfinite(c.m.mean)) {
      const LiteratureBand& band = options.literature_m;
      const double lo = c.m.has_interval() ? c.m.mean - c.m.half_width : c.m.mean;
      const double hi = c.m.has_interval() ? c.m.mean + c.m.half_width : c.m.mean;
      const char* where = hi < band.low                       ? "below the band"
                          : lo > band.high                    ? "above the band"
                          : lo >= band.low && hi <= band.high ? "inside the band"
                                                              : "across an edge of the band";
      answers.push_back(
          fmt::format("Against the literature (E = {:g} MPa): M = {} is {} M = {:g}–{:g}, {}.",
                      c.youngs_modulus_mpa, pm(c.m, 3), where, band.low, band.high, band.source));
    }
    if (c.m_per_ln_p.has_interval()) {
      const bool zero = std::abs(c.m_per_ln_p.mean) <= c.m_per_ln_p.half_width;
      answers.push_back(fmt::format(
          "p-dependence as I → 0 (E = {:g} MPa): dM/d ln p = {}, {}.", c.youngs_modulus_mpa,
          pm(c.m_per_ln_p, 3),
          zero ? "zero within its interval: the quasi-static stress ratio does not depend on p"
               : "not zero: the quasi-static stress ratio depends on p"));
    }
  }
  const double reference = ReferenceModulus();
  std::string limits;
  for (const QuasiStaticFit& f : quasi_static) {
    if (f.youngs_modulus_mpa != reference || f.psi_epsilon_deg != 90 ||
        f.quantity != "psi_sigma_deg" || !f.valid()) {
      continue;
    }
    std::string rates;
    for (double r : f.rates) rates += (rates.empty() ? "" : ", ") + fmt::format("{:g}", r);
    limits += fmt::format("{}from {:g} kPa {}° (I* = {})", limits.empty() ? "" : "; ",
                          f.start_p_kpa, pm(f.limit, 1), rates);
  }
  // Where every replicate of an isochoric group liquefied (in I*, then p_0 order).
  std::map<std::pair<double, double>, bool> all_liquefied;  // (I*, p_0)
  for (const RateGroup& g : groups) {
    if (g.key.youngs_modulus_mpa == reference && g.key.psi_epsilon_deg == 90 &&
        g.key.rule == dem::RateRule::kInertial && g.states > 0 && g.liquefied == g.states) {
      all_liquefied[{g.key.rate, g.key.start_p_kpa}] = true;
    }
  }
  std::string liquefied;
  for (const auto& [key, yes] : all_liquefied) {
    liquefied += fmt::format("{}I* = {:g} from {:g} kPa", liquefied.empty() ? "" : ", ", key.first,
                             key.second);
  }
  if (!limits.empty() || !liquefied.empty()) {
    answers.push_back(fmt::format(
        "Isochoric paths (ψ_ε = 90°, E = {:g} MPa): ψ_σ as I → 0 {}{}.", reference,
        limits.empty() ? std::string("not determined") : limits,
        liquefied.empty() ? std::string()
                          : "; every replicate liquefied (no asymptotic state) at " + liquefied));
  }
  for (const ExtensionLimit& l : extension_limits) {
    answers.push_back(fmt::format("Extension (E = {:g} MPa, {}, from {:g} kPa): {}.",
                                  l.youngs_modulus_mpa, RateText(l.rule, l.rate), l.start_p_kpa,
                                  l.Text()));
  }
  if (!verdicts.empty()) {
    // Undetermined only for want of a CSL (a difference would have made it
    // rate_dependent): where e and ψ_σ alone agree.
    std::string state_only;
    for (const RateVerdict& v : verdicts) {
      if (v.verdict == "undetermined" && v.ln_1_plus_e.agreement == Agreement::kAgree &&
          v.psi_sigma.agreement == Agreement::kAgree) {
        state_only +=
            fmt::format("{}E = {:g} MPa, ψ_ε = {:g}° from {:g} kPa", state_only.empty() ? "" : "; ",
                        v.youngs_modulus_mpa, v.psi_epsilon_deg, v.start_p_kpa);
      }
    }
    answers.push_back(
        "Rate independence between the two smallest I* (per E, ψ_ε, p_0): " +
        VerdictCounts(verdicts, ", ") +
        (state_only.empty()
             ? std::string()
             : "; ln(1+e) and ψ_σ agree, with no CSL to compare at one of the two I*, at " +
                   state_only) +
        ".");
  }
  std::string drained_verdicts;
  for (const DrainedLimit& l : drained.limits) {
    if (l.verdict.empty()) continue;
    drained_verdicts +=
        fmt::format("{}E = {:g} MPa, σ_r = {:g} kPa: {}{}", drained_verdicts.empty() ? "" : "; ",
                    l.youngs_modulus_mpa, l.radial_stress_kpa, l.verdict,
                    l.reason.empty() ? std::string() : " (" + l.reason + ")");
  }
  if (!drained_verdicts.empty()) {
    answers.push_back(
        "Drained critical state between the two slowest axial rates (M and ln(1+e)): " +
        drained_verdicts + ".");
  }
  if (!stiffness.empty()) {
    answers.push_back(fmt::format(
        "Stiffness scaling against E = {:g} MPa (ψ_σ and the CSL per start and rate): {}.",
        reference, VerdictCounts(stiffness, ", ")));
  }
  return answers;
}

std::string RateStudy::Text() const {
  int fits = 0;
  for (const QuasiStaticFit& f : quasi_static) fits += f.valid() ? 1 : 0;
  std::string text = fmt::format(
      "  rate study: {} states in {} groups of (E, psi_epsilon, start p, rate), {} lines, {} of "
      "{} quasi-static limits determined;",
      states.size(), groups.size(), lines.size(), fits, quasi_static.size());
  text += verdicts.empty() ? std::string(" no verdict (fewer than two I* per start)")
                           : " " + VerdictCounts(verdicts, " ");
  text += "\n";
  std::map<double, std::vector<StiffnessComparison>> by_modulus;
  for (const StiffnessComparison& c : stiffness) by_modulus[c.youngs_modulus_mpa].push_back(c);
  for (const auto& [e_mpa, list] : by_modulus) {
    text += fmt::format(
        "  stiffness, E {:g} against {:g} MPa (psi_sigma and the CSL per start and "
        "rate): {}\n",
        e_mpa, ReferenceModulus(), VerdictCounts(list, " "));
  }
  for (const ExtensionLimit& l : extension_limits) {
    text += fmt::format("  extension, E {:g} MPa, {}, from {:g} kPa: {}\n", l.youngs_modulus_mpa,
                        RateText(l.rule, l.rate), l.start_p_kpa, l.Text());
  }
  for (const DrainedCriticalState& c : drained.critical) {
    text += fmt::format("  drained critical state as I -> 0, {}: {}\n", MaterialText(MaterialOf(c)),
                        c.Text(options.reference_p_kpa));
  }
  return text;
}

}  // namespace granasym::analysis
