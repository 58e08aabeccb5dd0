#include "analysis/findings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "analysis/estimate.h"
#include "analysis/figure_context.h"
#include "analysis/quasi_static_selection.h"
#include "analysis/rate_files.h"
#include "common/state_measures.h"
#include "common/statistics.h"
#include "common/text_file.h"
#include "study/state_table.h"

namespace granasym::analysis {
namespace {

using figures::CaseData;
using figures::Context;
using figures::Sample;

using study::StateRow;
using study::TableKind;
using study::TableStatus;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- the study as the findings read
// it

// A state of the table with its case.
struct State {
  const StateRow* row;
  const CaseData* data;  // null when the case has no result
};

// The start of a case: NC or OC (from its parent stage's ψ_ε), p and ln(1+e).
struct Start {
  std::string kind;  // "NC", "OC" or ""
  double p_kpa = kNaN, ln_v = kNaN;
};

class Study {
 public:
  explicit Study(const Context& ctx) : ctx_(ctx) {
    for (const CaseData& c : ctx.cases) {
      cases_[{c.replicate, c.name}] = &c;
      if (!c.finished || c.path.empty() || c.sample != Sample::kMain) continue;
      if (std::isfinite(c.RadialStress())) drained_.emplace_back(&c, c.RadialStress());
    }
    for (const StateRow& row : ctx.states) {
      if (row.replicate < 1 || row.stage == study::table::kStageJoined) continue;
      const CaseData* data = Case(row.replicate, row.case_name);
      const Sample sample = data ? data->sample : Sample::kMain;
      if (sample == Sample::kOtherFriction) {
        frictionless_.push_back({&row, data});
      } else if (sample == Sample::kFineStep) {
        fine_step_.push_back({&row, data});
      } else if (row.ncl_reference == ctx.study_ncl ||
                 (row.kind == TableKind::kNcl && row.case_name == ctx.study_ncl)) {
        main_.push_back({&row, data});
      }
    }
  }

  const Context& ctx() const { return ctx_; }
  const std::vector<State>& main() const { return main_; }
  const std::vector<State>& frictionless() const { return frictionless_; }
  const std::vector<State>& fine_step() const { return fine_step_; }

  const CaseData* Case(int replicate, const std::string& name) const {
    const auto it = cases_.find({replicate, name});
    return it == cases_.end() ? nullptr : it->second;
  }
  NclLine Ncl(int replicate) const { return ctx_.StudyNcl(replicate); }

  // The main material's states of `kind` that the detector found.
  std::vector<State> Detected(TableKind kind) const {
    std::vector<State> out;
    for (const State& s : main_) {
      if (s.row->kind == kind && s.row->status == TableStatus::kDetected && s.row->p_kpa > 0)
        out.push_back(s);
    }
    return out;
  }

  Start StartOf(const CaseData& c) const {
    Start start;
    if (!c.path.empty()) {
      start.p_kpa = c.path.p.front();
      start.ln_v = c.path.ln_v.front();
    }
    const CaseData* parent = Case(c.replicate, c.parent_name);
    if (!parent) return start;
    for (size_t k = 0; k < parent->stages.size(); ++k) {
      if (parent->stages[k].name != c.parent_stage) continue;
      const double psi = parent->stage_psi_epsilon[k];
      if (std::abs(psi) < 1) start.kind = "NC";
      if (std::abs(psi - 180) < 1) start.kind = "OC";
    }
    return start;
  }

  // The main material's finished cases whose first stage is a strain path at ψ_ε.
  std::vector<const CaseData*> PathsAt(double psi_epsilon_deg) const {
    std::vector<const CaseData*> out;
    for (const CaseData& c : ctx_.cases) {
      if (!c.finished || c.path.empty() || c.sample != Sample::kMain) continue;
      if (std::abs(c.NominalPsiEpsilon() - psi_epsilon_deg) < 1e-6) out.push_back(&c);
    }
    return out;
  }
  // The main material's drained (constant σ_r) cases with their σ_r.
  const std::vector<std::pair<const CaseData*, double>>& Drained() const { return drained_; }
  std::optional<double> RadialStress(const CaseData* c) const {
    for (const auto& [drained, sigma] : drained_) {
      if (drained == c) return sigma;
    }
    return std::nullopt;
  }

 private:
  const Context& ctx_;
  std::map<std::pair<int, std::string>, const CaseData*> cases_;
  std::vector<State> main_, frictionless_, fine_step_;
  std::vector<std::pair<const CaseData*, double>> drained_;
};

// ---------------------------------------------------------------- small helpers

std::string Num(double v, int digits = 3) {
  if (!std::isfinite(v)) return "n/a";
  if (std::abs(v) >= 100 && std::abs(v) < 1e6) return fmt::format("{:.0f}", v);
  return fmt::format("{:.{}g}", v, digits);
}
// "0.0262 ± 0.0011" (or the value alone without an interval).
std::string WithInterval(const Estimate& e, int digits = 3) {
  if (!e.has_interval()) return Num(e.mean, digits);
  return Num(e.mean, digits) + " ± " + Num(e.half_width, 2);
}
Estimate SlopeOf(const LineFit& fit) {
  return Estimate::Fitted(fit.slope, fit.slope_error, fit.points);
}
double Rms(const std::vector<double>& r) {
  double s = 0;
  for (double v : r) s += v * v;
  return r.empty() ? kNaN : std::sqrt(s / static_cast<double>(r.size()));
}
double MaxAbs(const std::vector<double>& r) {
  double m = r.empty() ? kNaN : 0;
  for (double v : r) m = std::max(m, std::abs(v));
  return m;
}
// σ_r/p of a triaxial stress direction: σ_r = p − q/3.
double RadialOverMean(double psi_sigma_deg) {
  return 1.0 - StressRatio(psi_sigma_deg * kDegree) / 3.0;
}
// "20–1000 kPa": the range of p of states.
std::string PRange(const std::vector<State>& states) {
  double lo = kNaN, hi = kNaN;
  for (const State& s : states) {
    if (!(s.row->p_kpa >= lo)) lo = s.row->p_kpa;
    if (!(s.row->p_kpa <= hi)) hi = s.row->p_kpa;
  }
  return Num(lo) + "–" + Num(hi) + " kPa";
}
// The line of ln(1+e) against ln p through states, pooled over replicates.
LineFit VolumeLine(const std::vector<State>& states) {
  std::vector<double> x, y;
  for (const State& s : states) {
    x.push_back(std::log(s.row->p_kpa));
    y.push_back(s.row->ln_1_plus_e);
  }
  return FitLine(x, y);
}
// The line of ψ_σ against ln p through states.
LineFit PsiLine(const std::vector<State>& states) {
  std::vector<double> x, y;
  for (const State& s : states) {
    x.push_back(std::log(s.row->p_kpa));
    y.push_back(s.row->psi_sigma_deg);
  }
  return FitLine(x, y);
}
bool Increasing(const std::vector<double>& v) {
  for (size_t k = 1; k < v.size(); ++k) {
    if (!(v[k] > v[k - 1])) return false;
  }
  return v.size() >= 2;
}

Finding Make(const char* id, const char* source, const char* claim, const char* rule) {
  Finding f;
  f.id = id;
  f.source = source;
  f.claim = claim;
  f.rule = rule;
  return f;
}
Finding NotTested(Finding f, const std::string& why) {
  f.verdict = Verdict::kNotTested;
  f.numbers = why;
  return f;
}

// ---------------------------------------------------------------- the claims

// The NCL path of each replicate above 20 kPa: one line, or two slopes.
Finding NclLinear(const Study& study) {
  Finding f = Make("ncl_linear", "Fig. 9, Sec. 4.1",
                   "The isotropic NCL (ψ_ε = 0°) is linear in ln(1+e)–ln p above 20 kPa.",
                   "along each replicate's NCL path from 20 kPa to its end: reproduced if the "
                   "RMS residual about one line is ≤ 0.003 in ln(1+e) and the slopes of the "
                   "lower and upper halves of the ln p range agree within 25 %; partly if "
                   "one of the two holds; else not reproduced");
  std::vector<double> rms, ratio, lambda, p_max;
  for (const CaseData& c : study.ctx().cases) {
    if (c.name != study.ctx().study_ncl || !c.finished || c.path.empty()) continue;
    std::vector<double> x, y;
    for (size_t k = 0; k < c.path.p.size(); ++k) {
      if (c.path.p[k] >= 20 && std::isfinite(c.path.ln_v[k])) {
        x.push_back(std::log(c.path.p[k]));
        y.push_back(c.path.ln_v[k]);
      }
    }
    if (x.size() < 8 || x.back() - x.front() < 1) continue;
    const LineFit line = FitLine(x, y);
    std::vector<double> residual;
    for (size_t k = 0; k < x.size(); ++k) residual.push_back(y[k] - line.At(x[k]));
    const double middle = 0.5 * (x.front() + x.back());
    std::vector<double> xl, yl, xh, yh;
    for (size_t k = 0; k < x.size(); ++k) {
      (x[k] < middle ? xl : xh).push_back(x[k]);
      (x[k] < middle ? yl : yh).push_back(y[k]);
    }
    const LineFit low = FitLine(xl, yl), high = FitLine(xh, yh);
    rms.push_back(Rms(residual));
    ratio.push_back(high.slope / low.slope);
    lambda.push_back(-line.slope);
    p_max.push_back(std::exp(x.back()));
  }
  if (rms.empty()) return NotTested(f, "no NCL path reaches from 20 kPa over a factor e of p");
  const double worst_rms = *std::max_element(rms.begin(), rms.end());
  bool slopes_agree = true;
  for (double r : ratio) slopes_agree = slopes_agree && r >= 0.8 && r <= 1.25;
  const bool linear = worst_rms <= 0.003;
  f.verdict = linear && slopes_agree   ? Verdict::kReproduced
              : linear || slopes_agree ? Verdict::kPartly
                                       : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{} replicate(s), 20–{} kPa: λ* = {}; RMS residual {} (largest); slope of the upper half "
      "over the lower half {}",
      rms.size(), Num(*std::max_element(p_max.begin(), p_max.end())),
      WithInterval(Estimate::Of(lambda)), Num(worst_rms, 2),
      ratio.size() == 1 ? Num(ratio[0]) : WithInterval(Estimate::Of(ratio)));
  return f;
}

// The unload–reload cycles: where each reload ends against the NCL.
Finding CyclesRejoin(const Study& study) {
  Finding f = Make("cycles_rejoin_ncl", "Fig. 9, Sec. 4.1",
                   "Unload–reload cycles rejoin the isotropic NCL on reloading.",
                   "ln(1+e) at the end of each reload (ψ_ε = 0° after ψ_ε = 180°) against the "
                   "replicate's NCL at that p: reproduced if every offset is ≤ 0.005, partly if "
                   "≤ 0.015, else not reproduced");
  std::vector<double> offsets;
  std::vector<std::string> where;
  for (const CaseData& c : study.ctx().cases) {
    if (!c.finished || c.path.empty() || c.stages.size() < 2) continue;
    const NclLine ncl = study.Ncl(c.replicate);
    if (!ncl.valid() || c.name == study.ctx().study_ncl) continue;
    const int64_t first = c.stages.front().first_row;
    for (size_t k = 1; k < c.stages.size(); ++k) {
      if (std::abs(c.stage_psi_epsilon[k]) > 1 || std::abs(c.stage_psi_epsilon[k - 1] - 180) > 1)
        continue;
      const auto row = static_cast<size_t>(c.stages[k].last_row - first);
      if (row >= c.path.p.size() || !(c.path.p[row] > 0)) continue;
      const double on_ncl = ncl.n - ncl.lambda * std::log(c.path.p[row]);
      offsets.push_back(c.path.ln_v[row] - on_ncl);
      where.push_back(fmt::format("r{} {} at {} kPa: {:+.4f}", c.replicate, c.stages[k].name,
                                  Num(c.path.p[row]), offsets.back()));
    }
  }
  if (offsets.empty()) return NotTested(f, "no case reloads along ψ_ε = 0° after unloading");
  const double worst = MaxAbs(offsets);
  f.verdict = worst <= 0.005   ? Verdict::kReproduced
              : worst <= 0.015 ? Verdict::kPartly
                               : Verdict::kNotReproduced;
  std::string list;
  for (size_t k = 0; k < where.size() && k < 6; ++k) list += (k ? "; " : "") + where[k];
  f.numbers = fmt::format("offset of ln(1+e) from the NCL at the reloads' ends: {}{} (largest {})",
                          list, where.size() > 6 ? "; …" : "", Num(worst, 2));
  return f;
}

// The CSL's slope against the NCL's.
Finding CslParallel(const Study& study) {
  Finding f = Make("csl_parallel_ncl", "Fig. 10, Sec. 4.2",
                   "The critical state line is approximately parallel to the isotropic NCL in "
                   "ln(1+e)–ln p.",
                   "λ of a line through the detected critical states (ψ_ε = 90°) against λ* of "
                   "the NCL fits: reproduced if the difference is within its 95 % interval or "
                   "within 15 %, partly if within 50 %, else not reproduced");
  const std::vector<State> csl = study.Detected(TableKind::kCsl);
  std::vector<double> ncl_lambda;
  for (const auto& [key, line] : study.ctx().ncl_fits) {
    // Per replicate: replicate 0 is the NCL through the ensemble rows.
    if (key.first >= 1 && key.second == study.ctx().study_ncl && line.valid())
      ncl_lambda.push_back(line.lambda);
  }
  if (csl.size() < 3 || ncl_lambda.empty())
    return NotTested(
        f, fmt::format("{} detected critical states, {} NCL fits", csl.size(), ncl_lambda.size()));
  const LineFit line = VolumeLine(csl);
  Estimate csl_lambda = SlopeOf(line);
  csl_lambda.mean = -csl_lambda.mean;
  Estimate ncl = Estimate::Of(ncl_lambda);
  if (!ncl.has_interval()) {
    // One replicate: the interval of its fit is not kept; compare the values.
    ncl.standard_error = 0;
  }
  const Comparison c = Compare(ncl, csl_lambda);
  const double ratio = csl_lambda.mean / ncl.mean;
  f.verdict = (c.agreement == Agreement::kAgree || std::abs(ratio - 1) <= 0.15)
                  ? Verdict::kReproduced
              : (ratio >= 0.5 && ratio <= 1.5) ? Verdict::kPartly
                                               : Verdict::kNotReproduced;
  f.numbers =
      fmt::format("λ(CSL) = {} through {} states ({}), λ*(NCL) = {}; ratio {}",
                  WithInterval(csl_lambda), csl.size(), PRange(csl), WithInterval(ncl), Num(ratio));
  return f;
}

// OC critical states against the line through the NC ones.
Finding OneCsl(const Study& study) {
  Finding f = Make("nc_oc_one_csl", "Figs. 10–11, Sec. 4.2",
                   "Isochoric paths from NC and OC states reach one critical state line: the "
                   "isochoric asymptotic state is independent of the initial state.",
                   "the OC critical states against lines through the NC ones in ln(1+e)–ln p "
                   "and ψ_σ–ln p: reproduced if every OC state is within 0.01 of ln(1+e) and "
                   "2° of ψ_σ, partly if within 0.02 and 4°, else not reproduced");
  std::vector<State> nc, oc;
  for (const State& s : study.Detected(TableKind::kCsl)) {
    if (!s.data) continue;
    const std::string kind = study.StartOf(*s.data).kind;
    if (kind == "NC") nc.push_back(s);
    if (kind == "OC") oc.push_back(s);
  }
  if (nc.size() < 2 || oc.empty())
    return NotTested(f,
                     fmt::format("{} NC and {} OC critical states detected", nc.size(), oc.size()));
  const LineFit volume = VolumeLine(nc), psi = PsiLine(nc);
  std::vector<double> dv, dpsi;
  for (const State& s : oc) {
    const double x = std::log(s.row->p_kpa);
    dv.push_back(s.row->ln_1_plus_e - volume.At(x));
    dpsi.push_back(s.row->psi_sigma_deg - psi.At(x));
  }
  const double worst_v = MaxAbs(dv), worst_psi = MaxAbs(dpsi);
  f.verdict = worst_v <= 0.01 && worst_psi <= 2   ? Verdict::kReproduced
              : worst_v <= 0.02 && worst_psi <= 4 ? Verdict::kPartly
                                                  : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{} OC states against the lines through {} NC states: ln(1+e) off by {} (RMS), {} "
      "(largest); ψ_σ off by {}° (RMS), {}° (largest)",
      oc.size(), nc.size(), Num(Rms(dv), 2), Num(worst_v, 2), Num(Rms(dpsi), 2), Num(worst_psi, 2));
  return f;
}

// Peak ψ_σ of the OC isochoric paths against their start's OCR.
Finding PeakGrowsWithOcr(const Study& study) {
  Finding f = Make("peak_grows_with_ocr", "Fig. 11, Sec. 4.2",
                   "The peak ψ_σ of isochoric tests grows with the OCR of the start, while the "
                   "critical-state ψ_σ does not.",
                   "slopes of the peak and of the end-state ψ_σ against ln OCR of the start "
                   "(OC isochoric paths): reproduced if the peak's slope is positive beyond its "
                   "95 % interval and the end state's is below a third of it in magnitude, "
                   "partly if only the first holds, else not reproduced");
  std::vector<double> ln_ocr, peak, end;
  for (const CaseData* c : study.PathsAt(90)) {
    if (study.StartOf(*c).kind != "OC") continue;
    const NclLine ncl = study.Ncl(c->replicate);
    if (!ncl.valid()) continue;
    const Start start = study.StartOf(*c);
    ln_ocr.push_back(std::log(ncl.EquivalentPressure(start.ln_v) / start.p_kpa));
    peak.push_back(*std::max_element(c->path.psi_sigma.begin(), c->path.psi_sigma.end()));
    end.push_back(c->path.psi_sigma.back());
  }
  if (ln_ocr.size() < 3) return NotTested(f, fmt::format("{} OC isochoric paths", ln_ocr.size()));
  const Estimate peak_slope = SlopeOf(FitLine(ln_ocr, peak)),
                 end_slope = SlopeOf(FitLine(ln_ocr, end));
  const bool grows = peak_slope.mean - peak_slope.half_width > 0;
  const bool flat = std::abs(end_slope.mean) < peak_slope.mean / 3;
  f.verdict = grows && flat ? Verdict::kReproduced
              : grows       ? Verdict::kPartly
                            : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{} OC paths, OCR {}–{}: peak ψ_σ {}–{}°, slope {}° per unit ln OCR; end-state ψ_σ slope {}",
      ln_ocr.size(), Num(std::exp(*std::min_element(ln_ocr.begin(), ln_ocr.end()))),
      Num(std::exp(*std::max_element(ln_ocr.begin(), ln_ocr.end()))),
      Num(*std::min_element(peak.begin(), peak.end())),
      Num(*std::max_element(peak.begin(), peak.end())), WithInterval(peak_slope),
      WithInterval(end_slope));
  return f;
}

// Drained NC and OC tests per σ_r, and against the isochoric states.
Finding DrainedConverge(const Study& study) {
  Finding f = Make("drained_converge", "Figs. 12–13, Sec. 4.2",
                   "Drained (constant σ_r) tests from NC and OC states reach one state per σ_r, "
                   "close to the isochoric (ψ_ε = 90°) asymptotic states.",
                   "per replicate and σ_r, the NC and OC end states (detected triaxial rows): "
                   "one state if within 0.01 of ln(1+e) and 2° of ψ_σ; close to the ψ_ε = 90° "
                   "states if within 0.02 of ln(1+e) and 3° of ψ_σ of lines through the "
                   "critical states; reproduced if both hold for all, partly if one, else not "
                   "reproduced");
  std::map<std::pair<int, double>, std::map<std::string, const StateRow*>> by_sigma;
  std::vector<const StateRow*> drained;
  for (const State& s : study.Detected(TableKind::kTriaxial)) {
    const std::optional<double> sigma = study.RadialStress(s.data);
    if (!sigma) continue;
    by_sigma[{s.data->replicate, *sigma}][study.StartOf(*s.data).kind] = s.row;
    drained.push_back(s.row);
  }
  const std::vector<State> csl = study.Detected(TableKind::kCsl);
  if (drained.empty() || csl.size() < 2)
    return NotTested(f, fmt::format("{} detected drained states, {} critical states",
                                    drained.size(), csl.size()));
  std::vector<double> pair_dv, pair_dpsi;
  std::string pairs;
  for (const auto& [key, starts] : by_sigma) {
    if (!starts.count("NC") || !starts.count("OC")) continue;
    pair_dv.push_back(starts.at("OC")->ln_1_plus_e - starts.at("NC")->ln_1_plus_e);
    pair_dpsi.push_back(starts.at("OC")->psi_sigma_deg - starts.at("NC")->psi_sigma_deg);
    pairs += fmt::format("{}σ_r = {} kPa (r{}): Δln(1+e) {:+.4f}, Δψ_σ {:+.2f}°",
                         pairs.empty() ? "" : "; ", Num(key.second), key.first, pair_dv.back(),
                         pair_dpsi.back());
  }
  const LineFit volume = VolumeLine(csl), psi = PsiLine(csl);
  std::vector<double> dv, dpsi;
  for (const StateRow* row : drained) {
    const double x = std::log(row->p_kpa);
    dv.push_back(row->ln_1_plus_e - volume.At(x));
    dpsi.push_back(row->psi_sigma_deg - psi.At(x));
  }
  const bool one = !pair_dv.empty() && MaxAbs(pair_dv) <= 0.01 && MaxAbs(pair_dpsi) <= 2;
  const bool close = MaxAbs(dv) <= 0.02 && MaxAbs(dpsi) <= 3;
  f.verdict = one && close   ? Verdict::kReproduced
              : one || close ? Verdict::kPartly
                             : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{}; {} drained states against the critical-state lines: ln(1+e) off by {} (largest), ψ_σ "
      "by {}° (largest, mean {:+.2f}°)",
      pairs.empty() ? "no σ_r with both an NC and an OC state" : pairs, drained.size(),
      Num(MaxAbs(dv), 2), Num(MaxAbs(dpsi), 2), Mean(dpsi));
  return f;
}

// Path convergence counts of a kind per ψ_ε (the table's joined rows).
std::map<double, int> JoinedByPsi(const Study& study, TableKind kind) {
  std::map<double, int> joined;
  for (const StateRow& row : study.ctx().states) {
    if (row.stage == study::table::kStageJoined && row.kind == kind)
      ++joined[std::round(row.psi_epsilon_deg)];
  }
  return joined;
}

// Mean ψ_σ and ln OCR of the detected states of a kind, per ψ_ε.
struct ByDirection {
  std::vector<double> psi_epsilon, psi_sigma, ln_ocr;
  std::map<double, int> states;
};
ByDirection MeansByDirection(const std::vector<State>& states) {
  std::map<double, std::vector<const StateRow*>> groups;
  for (const State& s : states) groups[std::round(s.row->psi_epsilon_deg)].push_back(s.row);
  ByDirection out;
  for (const auto& [psi, rows] : groups) {
    std::vector<double> sigma, ocr;
    for (const StateRow* r : rows) {
      sigma.push_back(r->psi_sigma_deg);
      if (r->ocr > 0) ocr.push_back(std::log(r->ocr));
    }
    out.psi_epsilon.push_back(psi);
    out.psi_sigma.push_back(Mean(sigma));
    out.ln_ocr.push_back(ocr.empty() ? kNaN : Mean(ocr));
    out.states[psi] = static_cast<int>(rows.size());
  }
  return out;
}
std::string DirectionTable(const ByDirection& d) {
  std::string text;
  for (size_t k = 0; k < d.psi_epsilon.size(); ++k) {
    text +=
        fmt::format("{}{}°: {} state(s), ψ_σ {}°, OCR {}", k ? "; " : "", Num(d.psi_epsilon[k]),
                    d.states.at(d.psi_epsilon[k]), Num(d.psi_sigma[k]), Num(std::exp(d.ln_ocr[k])));
  }
  return text;
}

Finding CompressionConverge(const Study& study) {
  Finding f = Make("compression_converge", "Fig. 14, Sec. 4.3",
                   "Compression paths (0° < ψ_ε < 90°) of one ψ_ε from different starts converge "
                   "to one asymptote; ψ_σ and the OCR of the asymptote grow with ψ_ε.",
                   "three tests: paths of every ψ_ε join (path convergence, at least one pair "
                   "per ψ_ε); the mean ψ_σ, and the mean OCR, of the stage-end states (detected "
                   "or drifting, at the paths' common end p) rise with ψ_ε; reproduced if all "
                   "three hold, partly if one or two, else not reproduced");
  // The stage ends (detected or drifting) at the paths' common end p: at the
  // paper's rate ψ_σ still falls with p there (a rate effect, Sec. 5.3), so
  // states at different p are not compared.
  std::vector<State> ends;
  for (const State& s : study.main()) {
    if (s.row->kind == TableKind::kCompression && figures::UsableState(*s.row)) ends.push_back(s);
  }
  const ByDirection d = MeansByDirection(ends);
  const std::map<double, int> joined = JoinedByPsi(study, TableKind::kCompression);
  std::set<double> directions;
  for (const State& s : study.main()) {
    if (s.row->kind == TableKind::kCompression)
      directions.insert(std::round(s.row->psi_epsilon_deg));
  }
  if (directions.empty()) return NotTested(f, "no compression paths");
  int directions_joined = 0;
  std::string joins;
  for (double psi : directions) {
    const int n = joined.count(psi) ? joined.at(psi) : 0;
    directions_joined += n > 0;
    joins += fmt::format("{}{}° {}", joins.empty() ? "" : ", ", Num(psi), n);
  }
  const bool converge = directions_joined == static_cast<int>(directions.size());
  const bool enough = d.psi_epsilon.size() >= 2;
  const int holds =
      converge + (enough && Increasing(d.psi_sigma)) + (enough && Increasing(d.ln_ocr));
  f.verdict = holds == 3  ? Verdict::kReproduced
              : holds > 0 ? Verdict::kPartly
                          : Verdict::kNotReproduced;
  f.numbers = fmt::format("joined pairs per ψ_ε: {}; stage ends at {}: {}", joins, PRange(ends),
                          d.psi_epsilon.empty() ? "none" : DirectionTable(d));
  return f;
}

Finding ExtensionLines(const Study& study) {
  Finding f = Make("normal_extension_lines", "Fig. 15, Sec. 4.4",
                   "Extension paths (ψ_ε = 95–110°) reach extension asymptotic states on normal "
                   "extension lines; the OCR of the line grows with ψ_ε.",
                   "reproduced if states are detected for at least three of ψ_ε = 95, 100, 105, "
                   "110°, paths of at least two of them join (path convergence), and the mean "
                   "OCR rises with ψ_ε; partly if states are detected for two or more of them "
                   "or paths of one join; else not reproduced");
  const ByDirection d = MeansByDirection(study.Detected(TableKind::kExtension));
  const std::map<double, int> joined = JoinedByPsi(study, TableKind::kExtension);
  bool any = false;
  for (const State& s : study.main()) any = any || s.row->kind == TableKind::kExtension;
  if (!any) return NotTested(f, "no extension paths");
  int detected = 0, joined_directions = 0;
  std::vector<double> ocr;
  for (double psi : {95.0, 100.0, 105.0, 110.0}) {
    detected += d.states.count(psi) > 0;
    joined_directions += joined.count(psi) > 0;
  }
  for (size_t k = 0; k < d.psi_epsilon.size(); ++k) {
    if (d.psi_epsilon[k] <= 110) ocr.push_back(d.ln_ocr[k]);
  }
  const bool rising = ocr.size() >= 2 && Increasing(ocr);
  f.verdict = detected >= 3 && joined_directions >= 2 && rising ? Verdict::kReproduced
              : detected >= 2 || joined_directions >= 1         ? Verdict::kPartly
                                                                : Verdict::kNotReproduced;
  std::string joins;
  for (const auto& [psi, n] : joined)
    joins += fmt::format("{}{}° {}", joins.empty() ? "" : ", ", Num(psi), n);
  f.numbers = fmt::format("detected: {}; joined pairs: {}",
                          d.psi_epsilon.empty() ? "none" : DirectionTable(d),
                          joins.empty() ? "none" : joins);
  return f;
}

Finding ExtensionPsiIndependent(const Study& study) {
  Finding f = Make("extension_psi_at_high_e", "Fig. 15, Sec. 4.4",
                   "At high void ratios the asymptotic ψ_σ is independent of ψ_ε > 90°; it grows "
                   "with ψ_ε at lower void ratios only.",
                   "the detected extension states split at the median ln(1+e): reproduced if "
                   "the per-ψ_ε mean ψ_σ spreads by ≤ 3° in the upper half and by more in the "
                   "lower; partly if only the first; not reproduced if the upper half spreads "
                   "by more than 3°; not tested with fewer than two ψ_ε in the upper half");
  const std::vector<State> states = study.Detected(TableKind::kExtension);
  std::vector<double> levels;
  for (const State& s : states) levels.push_back(s.row->ln_1_plus_e);
  if (levels.size() < 3)
    return NotTested(f, fmt::format("{} detected extension states", levels.size()));
  std::sort(levels.begin(), levels.end());
  const double median = levels[levels.size() / 2];
  auto spread = [&](bool upper, int* directions) {
    std::map<double, std::vector<double>> by_psi;
    for (const State& s : states) {
      if ((s.row->ln_1_plus_e >= median) == upper)
        by_psi[std::round(s.row->psi_epsilon_deg)].push_back(s.row->psi_sigma_deg);
    }
    std::vector<double> means;
    for (const auto& [psi, v] : by_psi) means.push_back(Mean(v));
    *directions = static_cast<int>(means.size());
    if (means.size() < 2) return kNaN;
    return *std::max_element(means.begin(), means.end()) -
           *std::min_element(means.begin(), means.end());
  };
  int upper_n = 0, lower_n = 0;
  const double upper = spread(true, &upper_n), lower = spread(false, &lower_n);
  if (upper_n < 2)
    return NotTested(
        f, fmt::format("{} ψ_ε with detected states above ln(1+e) = {}", upper_n, Num(median, 4)));
  f.verdict = upper > 3                               ? Verdict::kNotReproduced
              : std::isfinite(lower) && lower > upper ? Verdict::kReproduced
                                                      : Verdict::kPartly;
  f.numbers = fmt::format(
      "spread of the per-ψ_ε mean ψ_σ above ln(1+e) = {}: {}° over {} ψ_ε; below: {}° over {}",
      Num(median, 4), Num(upper), upper_n, Num(lower), lower_n);
  return f;
}

Finding LimitD(const Study& study) {
  Finding f = Make("limit_d", "Fig. 15, Sec. 4.4",
                   "The limit d (σ_r = 0, ψ_σ = 54.7°) could not be confirmed: beyond "
                   "ψ_ε = 110° the asymptotic states lie below 0.5 kPa.",
                   "reproduced if no path with ψ_ε > 110° has a detected state above the floor "
                   "and every detected extension state keeps σ_r/p > 0.05; not reproduced if "
                   "one reaches σ_r/p ≤ 0.05 (the limit d found) or a path beyond 110° has a "
                   "state; not tested without paths beyond 110°");
  bool beyond = false;
  int beyond_detected = 0;
  double smallest = kNaN, at_psi = kNaN;
  for (const State& s : study.main()) {
    if (s.row->kind != TableKind::kExtension) continue;
    if (s.row->psi_epsilon_deg > 110.5) {
      beyond = true;
      beyond_detected += s.row->status == TableStatus::kDetected;
    }
    if (s.row->status != TableStatus::kDetected) continue;
    const double ratio = RadialOverMean(s.row->psi_sigma_deg);
    if (!(ratio >= smallest)) {
      smallest = ratio;
      at_psi = s.row->psi_epsilon_deg;
    }
  }
  if (!beyond) return NotTested(f, "no extension path beyond ψ_ε = 110°");
  const bool d_found = smallest <= 0.05;
  f.verdict = !d_found && beyond_detected == 0 ? Verdict::kReproduced : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "smallest σ_r/p of a detected extension state {} (ψ_ε = {}°); states detected beyond "
      "110°: {}",
      Num(smallest), Num(at_psi), beyond_detected);
  return f;
}

// A drained triaxial state at the critical state: its measured ψ_ε within
// this of 90° (the critical state under stress control).
constexpr double kDrainedCriticalPsiTolerance = 1.5;

// The normalised states: p/p_e* = 1/OCR, q/p_e* = (q/p)/OCR. In a rate
// study, the states of its quasi-static set only (the section of one rate),
// whose critical states may come from drained tests alone.
Finding AsbsShape(const Study& study) {
  Finding f = Make("asbs_shape", "Fig. 17, Sec. 4.5",
                   "Constant-e cross-sections of the ASBS change shape with e, and the critical "
                   "state lies far to the left of their apex (unlike in the models).",
                   "p/p_e* (1/OCR) of the detected critical states (ψ_ε = 90°; without them, "
                   "drained triaxial states at ψ_ε = 90 ± 1.5°): left of the apex if below "
                   "0.7 of the apex's p/p_e* (the other detected state of largest q/p_e*, of "
                   "those with OCR ≥ 1; none when a critical state reaches higher); shape "
                   "changing with e if ln OCR of the critical states has a slope against "
                   "ln(1+e) beyond its 95 % interval; reproduced if both, partly if one; in a "
                   "rate study, the states of its quasi-static set only");
  std::optional<QuasiStaticSelection> quasi_static;
  if (const std::optional<RateStudy> rate = ReadRateStudy(study.ctx().directory)) {
    QuasiStaticSelection selection = SelectQuasiStatic(*rate);
    if (selection.valid()) quasi_static = std::move(selection);
  }
  std::set<std::string> set_cases;
  if (quasi_static) {
    for (const std::string& name : quasi_static->AllCases()) set_cases.insert(name);
  }
  std::vector<State> all;
  bool isochoric = false;
  for (const State& s : study.main()) {
    if (quasi_static && !set_cases.count(s.row->case_name)) continue;
    if (s.row->status == TableStatus::kDetected && s.row->ocr > 0) {
      all.push_back(s);
      isochoric = isochoric || s.row->kind == TableKind::kCsl;
    }
  }
  // The critical states: the isochoric ones; without them, the drained ones.
  const auto critical = [isochoric](const StateRow& row) {
    if (isochoric) return row.kind == TableKind::kCsl;
    return row.kind == TableKind::kTriaxial &&
           std::abs(row.psi_epsilon_deg - 90) <= kDrainedCriticalPsiTolerance;
  };
  int denser_than_ncl = 0;  // OCR < 1: outside the NCL's reach, not on the ASBS
  std::vector<double> csl_ratio, csl_lnv, csl_lnocr;
  // The apex: the other states' largest q/p_e*, unless a critical state
  // reaches higher (then the critical states are the apex).
  const auto q_over_pe = [](const StateRow& row) { return row.q_over_p / row.ocr; };
  const StateRow* apex = nullptr;
  double critical_q_over_pe = -std::numeric_limits<double>::infinity();
  for (const State& s : all) {
    if (s.row->ocr < 1) {
      ++denser_than_ncl;
      continue;
    }
    if (critical(*s.row)) {
      csl_ratio.push_back(1 / s.row->ocr);
      csl_lnv.push_back(s.row->ln_1_plus_e);
      csl_lnocr.push_back(std::log(s.row->ocr));
      critical_q_over_pe = std::max(critical_q_over_pe, q_over_pe(*s.row));
    } else if (!apex || q_over_pe(*s.row) > q_over_pe(*apex)) {
      apex = s.row;
    }
  }
  if (csl_ratio.size() < 3 || !apex) {
    return NotTested(
        f, fmt::format(
               "{} {}critical states with an OCR{}", csl_ratio.size(), isochoric ? "" : "drained ",
               quasi_static ? "; the quasi-static set: " + SelectionText(*quasi_static) : ""));
  }
  const Estimate ratio = Estimate::Of(csl_ratio);
  const Estimate slope = SlopeOf(FitLine(csl_lnv, csl_lnocr));
  const bool critical_apex = critical_q_over_pe >= q_over_pe(*apex);
  const bool left = !critical_apex && ratio.mean < 0.7 / apex->ocr;
  const bool changes = slope.has_interval() && std::abs(slope.mean) > slope.half_width;
  f.verdict = left && changes   ? Verdict::kReproduced
              : left || changes ? Verdict::kPartly
                                : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{}critical states p/p_e* = {} (range {}–{}); {} at ψ_ε = {}° ({}) with p/p_e* = {}, "
      "q/p_e* = {}; d ln OCR(CSL) / d ln(1+e) = {}; {} detected state(s) with OCR < 1 left "
      "out{}",
      isochoric ? "" : "drained ", WithInterval(ratio),
      Num(*std::min_element(csl_ratio.begin(), csl_ratio.end())),
      Num(*std::max_element(csl_ratio.begin(), csl_ratio.end())),
      critical_apex ? fmt::format("the critical states are the apex (q/p_e* up to {}); the "
                                  "other states' largest q/p_e* is",
                                  Num(critical_q_over_pe))
                    : "apex",
      Num(apex->psi_epsilon_deg), ToString(apex->kind), Num(1 / apex->ocr), Num(q_over_pe(*apex)),
      WithInterval(slope), denser_than_ncl,
      quasi_static ? "; the quasi-static set: " + SelectionText(*quasi_static) : "");
  return f;
}

// The isochoric paths against the ASBS at their own void ratio: the
// detected states moved to the path's ln(1+e) along their asymptotic lines
// (ProjectToLevel, as Figs. 17–18 draw them) give the cross-section's
// p/p_e* as a function of ψ_σ; each path point's p/p_e* is compared with it
// at the point's ψ_σ.
Finding PathsBoundedByAsbs(const Study& study) {
  Finding f = Make("asbs_bounds_paths", "Fig. 18, Sec. 4.5",
                   "Isochoric (ψ_ε = 90°) paths from NC and OC states are bounded by the ASBS.",
                   "the detected states projected to each path's ln(1+e) along their asymptotic "
                   "lines give the section's p/p_e* against ψ_σ (interpolated, within the range "
                   "of their ψ_σ); reproduced if at most 5 % of the path points lie more than "
                   "10 % outside it, partly if at most 20 %, else not reproduced");
  int judged = 0, outside = 0, paths = 0, beyond = 0;
  for (const CaseData* c : study.PathsAt(90)) {
    const NclLine ncl = study.Ncl(c->replicate);
    if (!ncl.valid()) continue;
    const double level = c->path.ln_v.front();
    std::vector<std::pair<double, double>> section;  // (ψ_σ, p/p_e*)
    for (const State& s : study.main()) {
      SectionPoint point;
      if (s.row->status == TableStatus::kDetected &&
          ProjectToLevel(*s.row, level, ncl, study.ctx().options.max_projection_lnp, &point))
        section.emplace_back(s.row->psi_sigma_deg, point.p_over_pe);
    }
    if (section.size() < 4) continue;
    std::sort(section.begin(), section.end());
    ++paths;
    const double pe = ncl.EquivalentPressure(level);
    for (size_t k = 0; k < c->path.p.size(); ++k) {
      const double psi = c->path.psi_sigma[k];
      if (!(psi >= section.front().first && psi <= section.back().first)) {
        ++beyond;
        continue;
      }
      const auto it = std::lower_bound(section.begin(), section.end(), std::make_pair(psi, -1.0));
      double bound = it->second;
      if (it != section.begin() && it->first > (it - 1)->first) {
        const auto& [x0, y0] = *(it - 1);
        bound = y0 + (it->second - y0) * (psi - x0) / (it->first - x0);
      }
      ++judged;
      outside += c->path.p[k] / pe > 1.1 * bound;
    }
  }
  if (judged == 0)
    return NotTested(f, "no isochoric path with four detected states projectable to its level");
  const double fraction = static_cast<double>(outside) / judged;
  f.verdict = fraction <= 0.05  ? Verdict::kReproduced
              : fraction <= 0.2 ? Verdict::kPartly
                                : Verdict::kNotReproduced;
  f.numbers = fmt::format(
      "{} isochoric paths, {} points judged: {} ({:.1f} %) more than 10 % outside the section at "
      "their level; {} points at ψ_σ outside the projected states' range not judged",
      paths, judged, outside, 100 * fraction, beyond);
  return f;
}

// Where a path's ψ_ε crosses each target near its peak (ψ_σ at least 0.8 of
// the path's largest), the crossing of highest ψ_σ: the paper picks the
// states near the drained test's peak, and ψ_ε scatters about the targets at
// the start of loading. A target not crossed near the peak has no pick.
std::vector<StretchingPick> PicksNearPeak(const figures::Path& path,
                                          const std::vector<double>& targets) {
  std::vector<StretchingPick> picks;
  if (path.psi_sigma.empty()) return picks;
  const double peak = *std::max_element(path.psi_sigma.begin(), path.psi_sigma.end());
  for (double target : targets) {
    std::optional<StretchingPick> best;
    for (size_t from = 0; from + 1 < path.p.size();) {
      auto slice = [&](const std::vector<double>& v) {
        return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(from), v.end());
      };
      const std::vector<StretchingPick> found =
          PickStretchingDirections(slice(path.psi_epsilon), slice(path.p), slice(path.ln_v),
                                   slice(path.psi_sigma), {target});
      if (found.empty()) break;
      const bool near_peak = found.front().psi_sigma_deg >= 0.8 * peak;
      if (near_peak && (!best || found.front().psi_sigma_deg > best->psi_sigma_deg))
        best = found.front();
      from += static_cast<size_t>(found.front().row) + 1;
    }
    if (best) picks.push_back(*best);
  }
  return picks;
}

Finding DrainedPeakOnExtension(const Study& study) {
  Finding f = Make("oc_drained_peak_extension", "Fig. 19, Sec. 4.5",
                   "Near the peak of a drained test on a heavily OC state (unloaded from 1000 to "
                   "2 and 5 kPa), the states with ψ_ε = 95° and 100° lie close to the extension "
                   "asymptotes of ψ_ε = 95° and 100°.",
                   "where the drained path's ψ_ε crosses 95° and 100°, its ψ_σ and ln OCR "
                   "against the mean of the detected extension states of that ψ_ε: close if "
                   "within 3° and 0.5; reproduced if every pick is close, partly if one is "
                   "within 3° of ψ_σ, else not reproduced");
  const ByDirection ext = MeansByDirection(study.Detected(TableKind::kExtension));
  auto asymptote = [&](double psi, double* psi_sigma, double* ln_ocr) {
    for (size_t k = 0; k < ext.psi_epsilon.size(); ++k) {
      if (ext.psi_epsilon[k] == psi) {
        *psi_sigma = ext.psi_sigma[k];
        *ln_ocr = ext.ln_ocr[k];
        return true;
      }
    }
    return false;
  };
  int picks = 0, close = 0, close_psi = 0;
  std::string text;
  for (const auto& [c, sigma] : study.Drained()) {
    if (sigma > 10 || study.StartOf(*c).kind != "OC") continue;
    const NclLine ncl = study.Ncl(c->replicate);
    if (!ncl.valid()) continue;
    for (const StretchingPick& pick : PicksNearPeak(c->path, {95.0, 100.0})) {
      double psi_sigma = kNaN, ln_ocr = kNaN;
      if (!asymptote(pick.psi_epsilon_deg, &psi_sigma, &ln_ocr)) continue;
      const double d_psi = pick.psi_sigma_deg - psi_sigma;
      const double d_ocr = std::log(ncl.EquivalentPressure(pick.ln_1_plus_e) / pick.p_kpa) - ln_ocr;
      ++picks;
      close_psi += std::abs(d_psi) <= 3;
      close += std::abs(d_psi) <= 3 && std::abs(d_ocr) <= 0.5;
      text += fmt::format("{}r{} σ_r = {} kPa at ψ_ε = {}°: Δψ_σ {:+.1f}°, Δln OCR {:+.2f}",
                          text.empty() ? "" : "; ", c->replicate, Num(sigma),
                          Num(pick.psi_epsilon_deg), d_psi, d_ocr);
    }
  }
  if (picks == 0)
    return NotTested(f,
                     "no drained test from an OC state at σ_r ≤ 10 kPa crossing ψ_ε = 95° or "
                     "100° with a detected extension state of that ψ_ε");
  f.verdict = close == picks  ? Verdict::kReproduced
              : close_psi > 0 ? Verdict::kPartly
                              : Verdict::kNotReproduced;
  f.numbers = text;
  return f;
}

// "phi0_nc100_psi90" → "nc100_psi90".
std::string WithoutPrefix(const std::string& name) {
  const size_t underscore = name.find('_');
  return underscore == std::string::npos ? name : name.substr(underscore + 1);
}
// The detected critical states of another sample paired with the study's own
// of the same replicate and case name without the other sample's tag.
std::vector<std::pair<const StateRow*, const StateRow*>> Pairs(const Study& study,
                                                               const std::vector<State>& other) {
  std::vector<std::pair<const StateRow*, const StateRow*>> pairs;
  for (const State& o : other) {
    if (o.row->kind != TableKind::kCsl || o.row->status != TableStatus::kDetected) continue;
    const std::string name = WithoutPrefix(o.row->case_name);
    for (const State& m : study.Detected(TableKind::kCsl)) {
      if (m.row->replicate == o.row->replicate && m.row->case_name == name)
        pairs.emplace_back(m.row, o.row);
    }
  }
  return pairs;
}

Finding FrictionZero(const Study& study) {
  Finding f = Make("frictionless_alike", "Fig. 20, Sec. 5.1",
                   "Frictionless spheres (φ = 0) behave alike — an NCL and a critical state — "
                   "with lower strength.",
                   "the φ = 0 sample has a fitted NCL and detected critical states, each with "
                   "ψ_σ lower than the φ = 0.5 rad state from the same start: reproduced if "
                   "all are lower by more than 2°, partly if some are, else not reproduced");
  if (study.frictionless().empty()) return NotTested(f, "no frictionless cases");
  bool ncl = false;
  for (const auto& [key, line] : study.ctx().ncl_fits) {
    const CaseData* c = study.Case(key.first, key.second);
    ncl = ncl || (c && c->friction == 0 && line.valid());
  }
  const auto pairs = Pairs(study, study.frictionless());
  if (pairs.empty()) return NotTested(f, "no detected φ = 0 critical state with a φ = 0.5 pair");
  int lower = 0;
  std::string text;
  for (const auto& [m, o] : pairs) {
    lower += o->psi_sigma_deg < m->psi_sigma_deg - 2;
    text += fmt::format("{}{} r{}: ψ_σ {:.1f}° (φ = 0) against {:.1f}°", text.empty() ? "" : "; ",
                        m->case_name, m->replicate, o->psi_sigma_deg, m->psi_sigma_deg);
  }
  f.verdict = ncl && lower == static_cast<int>(pairs.size()) ? Verdict::kReproduced
              : lower > 0                                    ? Verdict::kPartly
                                                             : Verdict::kNotReproduced;
  f.numbers = fmt::format("φ = 0 NCL fitted: {}; {}", ncl ? "yes" : "no", text);
  return f;
}

Finding TimeStep(const Study& study) {
  Finding f =
      Make("time_step_independent", "Sec. 5.2", "Repeating a test with Δt/5 gives the same result.",
           "the critical state of the Δt/5 sample against the same case at the "
           "programme's Δt: reproduced if within 1° of ψ_σ, 0.005 of ln(1+e) and 0.1 of "
           "ln p; partly if within 2°, 0.01 and 0.2; else not reproduced");
  if (study.fine_step().empty()) return NotTested(f, "no case with a smaller time step");
  const auto pairs = Pairs(study, study.fine_step());
  if (pairs.empty()) return NotTested(f, "no detected Δt/5 critical state with a pair");
  double psi = 0, v = 0, lnp = 0;
  std::string text;
  for (const auto& [m, o] : pairs) {
    psi = std::max(psi, std::abs(o->psi_sigma_deg - m->psi_sigma_deg));
    v = std::max(v, std::abs(o->ln_1_plus_e - m->ln_1_plus_e));
    lnp = std::max(lnp, std::abs(std::log(o->p_kpa / m->p_kpa)));
    text += fmt::format("{}{} r{}: Δψ_σ {:+.2f}°, Δln(1+e) {:+.4f}, Δln p {:+.3f}",
                        text.empty() ? "" : "; ", m->case_name, m->replicate,
                        o->psi_sigma_deg - m->psi_sigma_deg, o->ln_1_plus_e - m->ln_1_plus_e,
                        std::log(o->p_kpa / m->p_kpa));
  }
  f.verdict = psi <= 1 && v <= 0.005 && lnp <= 0.1  ? Verdict::kReproduced
              : psi <= 2 && v <= 0.01 && lnp <= 0.2 ? Verdict::kPartly
                                                    : Verdict::kNotReproduced;
  f.numbers = text;
  return f;
}

Finding RateEffect(const Study& study) {
  Finding f = Make("csl_psi_falls_with_p", "Figs. 10, 22, Sec. 5.3",
                   "The critical-state ψ_σ falls with p, where the inertial number I(d_max) "
                   "exceeds 1e-2 (a rate effect).",
                   "slope of ψ_σ against ln p through the detected critical states: reproduced "
                   "if negative beyond its 95 % interval with the median I(d_max) above 1e-2; "
                   "partly if negative within its interval; not reproduced if it is not "
                   "negative");
  const std::vector<State> csl = study.Detected(TableKind::kCsl);
  if (csl.size() < 3) return NotTested(f, fmt::format("{} detected critical states", csl.size()));
  const Estimate slope = SlopeOf(PsiLine(csl));
  std::vector<double> inertial;
  for (const State& s : csl) inertial.push_back(s.row->inertial_number_dmax);
  std::sort(inertial.begin(), inertial.end());
  const double median = inertial[inertial.size() / 2];
  const bool falls = slope.mean + slope.half_width < 0;
  f.verdict = falls && median > 1e-2 ? Verdict::kReproduced
              : slope.mean < 0       ? Verdict::kPartly
                                     : Verdict::kNotReproduced;
  f.numbers = fmt::format("dψ_σ/d ln p = {}° through {} states ({}); I(d_max) {}–{} (median {})",
                          WithInterval(slope), csl.size(), PRange(csl), Num(inertial.front(), 2),
                          Num(inertial.back(), 2), Num(median, 2));
  return f;
}

}  // namespace

std::vector<Finding> ComputeFindings(const figures::Context& context) {
  const Study study(context);
  return {NclLinear(study),
          CyclesRejoin(study),
          CslParallel(study),
          OneCsl(study),
          PeakGrowsWithOcr(study),
          DrainedConverge(study),
          CompressionConverge(study),
          ExtensionLines(study),
          ExtensionPsiIndependent(study),
          LimitD(study),
          AsbsShape(study),
          PathsBoundedByAsbs(study),
          DrainedPeakOnExtension(study),
          FrictionZero(study),
          TimeStep(study),
          RateEffect(study)};
}

void WriteFindings(const std::string& directory, const std::vector<Finding>& findings) {
  using study::CsvText;
  std::string csv = "id,source,claim,verdict,numbers,rule\n";
  for (const Finding& f : findings) {
    csv += CsvText(f.id) + "," + CsvText(f.source) + "," + CsvText(f.claim) + "," +
           ToString(f.verdict) + "," + CsvText(f.numbers) + "," + CsvText(f.rule) + "\n";
  }
  WriteTextFileAtomically(directory + "/" + kFindingsFile, csv);
}

std::vector<Finding> WriteStudyFindings(const std::string& directory) {
  const std::vector<Finding> findings =
      ComputeFindings(figures::ReadContext(directory, FigureDataOptions{}));
  WriteFindings(directory, findings);
  return findings;
}

std::string FindingsLine(const std::vector<Finding>& findings) {
  std::map<Verdict, int> counts;
  for (const Finding& f : findings) ++counts[f.verdict];
  std::string text = "findings (" + std::string(kFindingsFile) + "):";
  for (Verdict v :
       {Verdict::kReproduced, Verdict::kPartly, Verdict::kNotReproduced, Verdict::kNotTested}) {
    text += fmt::format(" {} {}{}", counts[v], ToString(v), v == Verdict::kNotTested ? "" : ",");
  }
  return text + "\n";
}

}  // namespace granasym::analysis
