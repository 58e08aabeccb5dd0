#include "analysis/study_compare_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "analysis/figure_context.h"
#include "common/error.h"
#include "common/provenance.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;
using figures::Set;
using figures::Spec;
using study::CsvNumber;
using study::CsvText;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Decimals of a quantity in the summary and the labels.
int Decimals(StateQuantity quantity) { return quantity == StateQuantity::kPsiSigma ? 2 : 4; }

std::string Unit(StateQuantity quantity) { return quantity == StateQuantity::kPsiSigma ? "°" : ""; }

std::string Differs(const MeanDifference& d) {
  return !d.has_interval() ? "" : d.excludes_zero() ? "yes" : "no";
}

// Whether `inner` is `outer` or lies below it (both made absolute, links resolved).
bool Inside(const fs::path& inner, const fs::path& outer) {
  const fs::path relative = inner.lexically_relative(outer);
  return !relative.empty() && *relative.begin() != "..";
}

std::string CsvLine(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t k = 0; k < fields.size(); ++k) line += (k ? "," : "") + fields[k];
  return line + "\n";
}

std::string Comments(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += "# " + line + "\n";
  return text;
}

std::string KindTitle(TableKind kind) {
  switch (kind) {
    case TableKind::kNcl:
      return "NCL (ψ_ε = 0°)";
    case TableKind::kCsl:
      return "critical states (ψ_ε = 90°)";
    case TableKind::kCompression:
      return "compression (0° < ψ_ε < 90°)";
    case TableKind::kExtension:
      return "extension (ψ_ε > 90°)";
    case TableKind::kTriaxial:
      return "drained triaxial";
    case TableKind::kNone:
      return "no result";
  }
  return "";
}

// A data file for gnuplot whose rows end in a text column (the hover label):
// blocks two blank lines apart, each with a header of the column names and
// its title. Text fields lose tabs, line breaks and quotes (gnuplot and the
// SVG's script would take them as syntax).
class LabelledFile {
 public:
  explicit LabelledFile(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  void Block(const std::string& title) {
    if (!text_.empty()) text_ += "\n\n";
    for (const std::string& c : columns_) text_ += c + "\t";
    text_ += Clean(title) + "\n";
  }
  // A row; non-finite numbers are written as NaN (gnuplot skips the point).
  void Row(const std::vector<double>& values, const std::string& label) {
    for (double v : values) text_ += std::isfinite(v) ? fmt::format("{:.8g}\t", v) : "NaN\t";
    text_ += Clean(label) + "\n";
    ++rows_;
  }
  int rows() const { return rows_; }
  void Write(const std::string& path) const { WriteTextFileAtomically(path, text_); }
  static std::string Clean(std::string s) {
    for (char& c : s) {
      if (c == '\t' || c == '\n' || c == '\r') c = ' ';
      if (c == '"') c = ' ';
      if (c == '\'') c = ' ';
    }
    return s;
  }

 private:
  std::vector<std::string> columns_;
  std::string text_;
  int rows_ = 0;
};

// "s35 (small, 3000 spheres × 3)".
std::string StudyTitle(const CompareStudy& study) {
  return fmt::format("{} ({}, {} spheres × {})", study.name,
                     study.scale.empty() ? "?" : study.scale, study.count, study.replicates);
}
// "A: s35 (small, 3000 spheres × 3)".
std::string StudyTitle(const char* side, const CompareStudy& study) {
  return std::string(side) + ": " + StudyTitle(study);
}

// A side's mean with its interval; `single` says why there is none.
std::string MeanText(const Estimate& e, int decimals, const std::string& unit,
                     const char* single = "one replicate") {
  if (!std::isfinite(e.mean)) return "–";
  if (!e.has_interval()) return fmt::format("{:.{}f}{} ({})", e.mean, decimals, unit, single);
  return fmt::format("{:.{}f} ± {:.{}f}{}", e.mean, decimals, e.half_width, decimals, unit);
}

// A line's parameter: "0.0249 ± 0.0015 (n = 3)", "0.0262 (n = 1, no interval)".
std::string LineText(const Estimate& e, int decimals) {
  if (!std::isfinite(e.mean)) return "–";
  if (!e.has_interval()) return fmt::format("{:.{}f} (n = {}, no interval)", e.mean, decimals, e.n);
  return fmt::format("{:.{}f} ± {:.{}f} (n = {})", e.mean, decimals, e.half_width, decimals, e.n);
}

std::string DifferenceText(const MeanDifference& d, int decimals, const std::string& unit) {
  if (!std::isfinite(d.difference)) return "–";
  if (!d.has_interval())
    return fmt::format("{:+.{}f}{} (no interval)", d.difference, decimals, unit);
  return fmt::format("{:+.{}f} ± {:.{}f}{}{}", d.difference, decimals, d.half_width, decimals, unit,
                     d.excludes_zero() ? " (differs)" : "");
}

// The hover text of one side's mean state.
std::string SideLabel(const char* side, const CompareStudy& study, const StateMatch& m,
                      const SideState& s) {
  std::string text =
      fmt::format("{} {}: {} {} ({}), {} replicate{}", side, study.name, m.case_name, m.stage,
                  ToString(m.kind), s.replicates, s.replicates == 1 ? "" : "s");
  for (size_t q = 0; q < kStateQuantities.size(); ++q) {
    const StateQuantity quantity = kStateQuantities[q];
    if (quantity == StateQuantity::kLnP) {
      text += fmt::format("; p = {:.3g} kPa", std::exp(s.mean[q].mean));
      continue;
    }
    text += fmt::format("; {} = {}", QuantitySymbol(quantity),
                        MeanText(s.mean[q], Decimals(quantity), Unit(quantity)));
  }
  return text;
}

// The range of bars [low, high] (padded by `pad` of its span, a span of at
// least `least`) that reaches at most `reach` times the span of the bars'
// midpoints beyond them: a bar much longer than the scatter of the means is
// cut at the border rather than squeezing every point into a corner.
std::pair<double, double> Range(const std::vector<double>& low, const std::vector<double>& high,
                                double pad, double least, double reach = 0.5) {
  const double inf = std::numeric_limits<double>::infinity();
  double lo = inf, hi = -inf, mid_lo = inf, mid_hi = -inf;
  for (size_t k = 0; k < low.size() && k < high.size(); ++k) {
    if (!std::isfinite(low[k]) || !std::isfinite(high[k])) continue;
    lo = std::min(lo, low[k]);
    hi = std::max(hi, high[k]);
    mid_lo = std::min(mid_lo, 0.5 * (low[k] + high[k]));
    mid_hi = std::max(mid_hi, 0.5 * (low[k] + high[k]));
  }
  if (!(hi >= lo)) return {0, 1};
  const double beyond = reach * std::max(mid_hi - mid_lo, least);
  lo = std::max(lo, mid_lo - beyond);
  hi = std::min(hi, mid_hi + beyond);
  const double span = std::max(hi - lo, least);
  const double middle = 0.5 * (lo + hi);
  lo = std::min(lo, middle - 0.5 * span);
  hi = std::max(hi, middle + 0.5 * span);
  return {lo - pad * span, hi + pad * span};
}

std::string Fixed(double v) { return fmt::format("{:.6g}", v); }

void SetNumber(FigureSpec* spec, const std::string& name, double value) {
  spec->variables.emplace_back(name, Fixed(value));
}

// Figures (a) and (b), in that order, into `specs`.
void StatesFigures(const std::string& data, const StudyComparison& c,
                   std::vector<FigureSpec>* specs) {
  // The matched states of the study's own sample, A then B.
  LabelledFile file({"psi_epsilon_deg", "psi_sigma_deg", "psi_sigma_ci95", "p_kpa", "p_low_kpa",
                     "p_high_kpa", "ln_1_plus_e", "ln_1_plus_e_ci95"});
  std::vector<double> x, y_low, y_high, p_low, p_high, v_low, v_high;
  int shown = 0;
  for (int side = 0; side < 2; ++side) {
    const CompareStudy& study = side == 0 ? c.a : c.b;
    file.Block(StudyTitle(side == 0 ? "A" : "B", study));
    for (const StateMatch& m : c.matches) {
      if (m.sample != kSampleMain) continue;
      const SideState& s = side == 0 ? m.a : m.b;
      const Estimate& psi = s.mean[0];
      const Estimate& lnv = s.mean[1];
      const Estimate& lnp = s.mean[2];
      const double psi_hw = psi.has_interval() ? psi.half_width : 0;
      const double lnv_hw = lnv.has_interval() ? lnv.half_width : 0;
      const double lnp_hw = lnp.has_interval() ? lnp.half_width : 0;
      file.Row({s.psi_epsilon.mean, psi.mean, psi_hw, std::exp(lnp.mean),
                std::exp(lnp.mean - lnp_hw), std::exp(lnp.mean + lnp_hw), lnv.mean, lnv_hw},
               SideLabel(side == 0 ? "A" : "B", study, m, s));
      x.push_back(s.psi_epsilon.mean);
      y_low.push_back(psi.mean - psi_hw);
      y_high.push_back(psi.mean + psi_hw);
      p_low.push_back(std::exp(lnp.mean - lnp_hw));
      p_high.push_back(std::exp(lnp.mean + lnp_hw));
      v_low.push_back(lnv.mean - lnv_hw);
      v_high.push_back(lnv.mean + lnv_hw);
      if (side == 0) ++shown;
    }
  }
  const std::string sample_text = fmt::format(
      "The matched asymptotic states of each study's own sample (A: {}; B: {}), detected or "
      "drifting at the stage end: the mean over the replicates with its 95 % Student-t interval "
      "(bars; none for a single replicate). A filled, B open, a thin grey line from A's to B's "
      "mean of one state; hover over a point in the SVG for its case, stage, kind, study and "
      "means.",
      c.a.DescribeSample(), c.b.DescribeSample());

  FigureSpec a =
      Spec("compare_psi_sigma", "compare (a)", "ψ_σ against ψ_ε of the matched states, A and B",
           sample_text, "compare_psi_sigma.gp");
  FigureSpec b = Spec("compare_ln_v", "compare (b)",
                      "ln(1+e) against p of the matched states with each study's NCL",
                      sample_text +
                          " Lines: each study's NCL ln(1+e) = N − λ* ln p with N and λ* the "
                          "means of its replicates' fits (compare_ncl.csv).",
                      "compare_ln_v.gp");
  if (shown == 0) {
    specs->push_back(figures::NotDrawn(a, "no state of the studies' own samples matched"));
    specs->push_back(figures::NotDrawn(b, "no state of the studies' own samples matched"));
    return;
  }
  file.Write(data + "/compare_states.tsv");
  // B sits a little to the right of A so that both bars stay visible.
  auto [x_min, x_max] = Range(x, x, 0.0, 10.0);
  const double dx = std::max(0.6, 0.012 * (x_max - x_min));
  // A thin line joins the two means of each state (A's rows come first in x).
  std::string pairs = "psi_epsilon_deg\tpsi_sigma_deg\tp_kpa\tln_1_plus_e\n";
  const size_t n = x.size() / 2;
  for (size_t k = 0; k < n; ++k) {
    for (size_t side : {k, k + n}) {
      const double p_mid = std::sqrt(p_low[side] * p_high[side]);
      pairs += fmt::format("{:.8g}\t{:.8g}\t{:.8g}\t{:.8g}\n", x[side] + (side >= n ? dx : 0),
                           0.5 * (y_low[side] + y_high[side]), p_mid,
                           0.5 * (v_low[side] + v_high[side]));
    }
    pairs += "\n";
  }
  WriteTextFileAtomically(data + "/compare_pairs.tsv", pairs);
  a.caption +=
      fmt::format(" B is drawn {:.2g}° to the right of its ψ_ε so that both are seen.", dx);
  x_min -= 4 * dx;
  x_max += 5 * dx;
  auto [y_min, y_max] = Range(y_low, y_high, 0.06, 2.0);
  Set(&a, "title_a", StudyTitle("A", c.a));
  Set(&a, "title_b", StudyTitle("B", c.b));
  SetNumber(&a, "dx", dx);
  SetNumber(&a, "x_min", x_min);
  SetNumber(&a, "x_max", x_max);
  SetNumber(&a, "y_min", y_min);
  SetNumber(&a, "y_max", y_max);
  specs->push_back(a);

  std::vector<double> lp_lo, lp_hi;
  for (double p : p_low) lp_lo.push_back(std::log10(p));
  for (double p : p_high) lp_hi.push_back(std::log10(p));
  const auto [l_min, l_max] = Range(lp_lo, lp_hi, 0.04, 0.5);
  // Each study's NCL over the plotted range of p.
  for (int side = 0; side < 2; ++side) {
    const char* name = side == 0 ? "A" : "B";
    const LineComparison* n = c.Line(kSampleMain, "ncl", "N");
    const LineComparison* lambda = c.Line(kSampleMain, "ncl", "lambda_star");
    const std::string ncl_case = side == 0 ? c.a.study_ncl : c.b.study_ncl;
    const LineComparison* n_own = c.Line(kSampleMain, "ncl", "N", ncl_case);
    const LineComparison* lambda_own = c.Line(kSampleMain, "ncl", "lambda_star", ncl_case);
    if (n_own && lambda_own) {
      n = n_own;
      lambda = lambda_own;
    }
    const Estimate* en = n ? (side == 0 ? &n->a : &n->b) : nullptr;
    const Estimate* el = lambda ? (side == 0 ? &lambda->a : &lambda->b) : nullptr;
    const bool has = en && el && std::isfinite(en->mean) && std::isfinite(el->mean);
    Set(&b, fmt::format("has_ncl_{}", side == 0 ? "a" : "b"), has ? 1 : 0);
    if (!has) continue;
    LabelledFile line({"p_kpa", "ln_1_plus_e"});
    line.Block(fmt::format("{} NCL: N = {}, λ* = {}", name, LineText(*en, 3), LineText(*el, 4)));
    for (int k = 0; k <= 40; ++k) {
      const double log10_p = l_min + (l_max - l_min) * k / 40.0;
      const double ln_p = log10_p * std::log(10.0);
      line.Row({std::pow(10.0, log10_p), en->mean - el->mean * ln_p}, "");
    }
    line.Write(data + fmt::format("/compare_ncl_{}.tsv", side == 0 ? "a" : "b"));
    Set(&b, fmt::format("ncl_title_{}", side == 0 ? "a" : "b"),
        fmt::format("{} NCL: λ* = {}", name, LineText(*el, 4)));
  }
  auto [v_min, v_max] = Range(v_low, v_high, 0.06, 0.02);
  Set(&b, "title_a", StudyTitle("A", c.a));
  Set(&b, "title_b", StudyTitle("B", c.b));
  SetNumber(&b, "x_min", std::pow(10.0, l_min));
  SetNumber(&b, "x_max", std::pow(10.0, l_max));
  SetNumber(&b, "y_min", v_min);
  SetNumber(&b, "y_max", v_max);
  specs->push_back(b);
}

FigureSpec DifferencesFigure(const std::string& data, const StudyComparison& c) {
  FigureSpec spec = Spec(
      "compare_differences", "compare (c)",
      "Differences B − A of ψ_σ and ln(1+e) per matched state",
      "The difference B − A of the replicates' means of ψ_σ (left) and ln(1+e) (right) of every "
      "matched asymptotic state, grouped by sample and kind, with its 95 % Welch interval "
      "(Welch–Satterthwaite degrees of freedom; with one replicate on a side the other side's "
      "variance stands for both). Filled red: the interval leaves out 0 (the studies differ); "
      "open: it contains 0; crosses: no interval (one replicate on each side). Hover over a "
      "point in the SVG for the state and both means.",
      "compare_differences.gp");
  if (c.matches.empty()) return figures::NotDrawn(spec, "no state matched");
  LabelledFile file({"y", "d_psi_sigma", "d_psi_sigma_ci95", "psi_class", "d_ln_1_plus_e",
                     "d_ln_1_plus_e_ci95", "lnv_class"});
  file.Block("differences");
  // Tic labels: the states' names; a bold header per group of (sample, kind)
  // and a line between groups. Rows run down from y = -1.
  std::string tics, groups, headers, header_y;
  std::vector<double> psi_low, psi_high, lnv_low, lnv_high;
  double y = -1;
  std::string group;
  auto klass = [](const MeanDifference& d) {
    return !d.has_interval() ? 2.0 : d.excludes_zero() ? 0.0 : 1.0;
  };
  for (const StateMatch& m : c.matches) {
    const std::string title = (m.sample == kSampleMain            ? ""
                               : m.sample == kSampleOtherFriction ? "other friction: "
                                                                  : "finer time step: ") +
                              KindTitle(m.kind);
    if (title != group) {
      if (!group.empty()) {
        groups += Fixed(y) + " ";
        y -= 1;
      }
      group = title;
      headers += "\"" + title + "\" ";
      header_y += Fixed(y) + " ";
      y -= 1;
    }
    const MeanDifference& dp = m.difference[0];
    const MeanDifference& dv = m.difference[1];
    const std::string label = fmt::format(
        "{} {} ({}, {} sample): B − A ψ_σ = {}, ln(1+e) = {}; A ψ_σ = {}, B ψ_σ = {}; A ln(1+e) "
        "= {}, B ln(1+e) = {}",
        m.case_name, m.stage, ToString(m.kind), m.sample, DifferenceText(dp, 2, "°"),
        DifferenceText(dv, 4, ""), MeanText(m.a.mean[0], 2, "°"), MeanText(m.b.mean[0], 2, "°"),
        MeanText(m.a.mean[1], 4, ""), MeanText(m.b.mean[1], 4, ""));
    const double hp = dp.has_interval() ? dp.half_width : 0;
    const double hv = dv.has_interval() ? dv.half_width : 0;
    file.Row({y, dp.difference, hp, klass(dp), dv.difference, hv, klass(dv)}, label);
    tics += fmt::format("{}\"{}\" {}", tics.empty() ? "" : ", ", m.Label(), Fixed(y));
    psi_low.push_back(dp.difference - hp);
    psi_high.push_back(dp.difference + hp);
    lnv_low.push_back(dv.difference - hv);
    lnv_high.push_back(dv.difference + hv);
    y -= 1;
  }
  file.Write(data + "/compare_differences.tsv");
  psi_low.push_back(0);
  psi_high.push_back(0);
  lnv_low.push_back(0);
  lnv_high.push_back(0);
  const auto [psi_min, psi_max] = Range(psi_low, psi_high, 0.06, 1.0, 1.0);
  const auto [lnv_min, lnv_max] = Range(lnv_low, lnv_high, 0.06, 0.005, 1.0);
  const int rows = static_cast<int>(-y);
  SetNumber(&spec, "height", std::max(4.0, 1.3 + 0.15 * rows));
  SetNumber(&spec, "y_min", y + 0.5);
  SetNumber(&spec, "y_max", -0.5);
  SetNumber(&spec, "psi_min", psi_min);
  SetNumber(&spec, "psi_max", psi_max);
  SetNumber(&spec, "lnv_min", lnv_min);
  SetNumber(&spec, "lnv_max", lnv_max);
  Set(&spec, "tics", "(" + tics + ")");
  Set(&spec, "group_lines", groups);
  Set(&spec, "headers", headers);
  Set(&spec, "header_y", header_y);
  Set(&spec, "title",
      fmt::format("B − A, where B = {} and A = {}", StudyTitle(c.b), StudyTitle(c.a)));
  int none = 0;
  for (const StateMatch& m : c.matches) {
    none += m.difference[0].has_interval() && m.difference[1].has_interval() ? 0 : 1;
  }
  Set(&spec, "n_none", none);
  return spec;
}

}  // namespace

std::string DefaultCompareFolder(const std::string& a, const std::string& b) {
  auto name = [](const std::string& dir) {
    std::string n = fs::path(dir).lexically_normal().filename().string();
    if (n.empty() || n == "." || n == "..") {
      n = fs::absolute(dir).lexically_normal().parent_path().filename().string();
    }
    return n.empty() ? std::string("study") : n;
  };
  return "compare-" + name(a) + "-vs-" + name(b);
}

void CheckCompareFolder(const std::string& out, const std::string& a, const std::string& b) {
  const fs::path pa = fs::weakly_canonical(fs::absolute(a));
  const fs::path pb = fs::weakly_canonical(fs::absolute(b));
  const fs::path po = fs::weakly_canonical(fs::absolute(out));
  if (pa == pb) {
    throw InputError("A and B are the same folder (" + a + "): give two different study folders");
  }
  for (const auto& [side, path, given] : {std::tuple{"A", pa, a}, std::tuple{"B", pb, b}}) {
    if (Inside(po, path)) {
      throw InputError("--out " + out + ": is " + (po == path ? "" : "inside ") + "study " + side +
                       " (" + given +
                       "); a comparison never writes into the studies it reads: give a folder "
                       "outside both");
    }
  }
  if (!fs::exists(po)) return;
  if (!fs::is_directory(po)) {
    throw InputError("--out " + out + ": is a file, not a folder: give a new or empty folder");
  }
  if (fs::is_empty(po) || fs::exists(po / kCompareRecord)) return;
  throw InputError("--out " + out + ": is not empty and holds no earlier comparison (no " +
                   kCompareRecord +
                   "): give a new or empty folder, or one that `granasym "
                   "study compare` wrote");
}

void WriteComparisonTables(const std::string& out, const StudyComparison& c) {
  fs::create_directories(out);
  WriteTextFileAtomically(
      out + "/" + kCompareRecord,
      fmt::format("# written by granasym study compare: the two studies of this folder's "
                  "comparison; `study compare` may write this folder again\na = {}\nb = {}\n"
                  "program_version = {}\n",
                  TomlQuoted(fs::absolute(c.a.directory).lexically_normal().string()),
                  TomlQuoted(fs::absolute(c.b.directory).lexically_normal().string()),
                  TomlQuoted(ProgramVersion())));

  // compare_states.csv
  std::vector<std::string> header = {"sample",
                                     "kind",
                                     "case_name",
                                     "stage",
                                     "a_replicates",
                                     "a_status",
                                     "b_replicates",
                                     "b_status",
                                     "a_psi_epsilon_deg",
                                     "b_psi_epsilon_deg"};
  for (StateQuantity q : kStateQuantities) {
    const std::string n = QuantityColumn(q);
    for (const std::string& column :
         {"a_" + n + "_mean", "a_" + n + "_ci95", "b_" + n + "_mean", "b_" + n + "_ci95",
          "diff_" + n, "diff_" + n + "_ci95", "diff_" + n + "_dof", n + "_differs"}) {
      header.push_back(column);
    }
  }
  header.push_back("difference_interval");
  header.push_back("note");
  std::string text = Comments({
      fmt::format("Asymptotic states of A = {} and B = {} matched by sample, case name and stage "
                  "(granasym study compare).",
                  c.a.name, c.b.name),
      "A state is usable when detected or drifting with p > 0 (gas, invalid, not reached and "
      "no-result rows are left out); ensemble and joined rows are left out.",
      "sample: main (the study's own), other_friction, fine_step; states are matched only within "
      "one sample. kind: ncl, csl, compression, extension, triaxial.",
      "a_replicates, b_replicates: usable replicate rows; a_status, b_status: every replicate "
      "row's status with its count.",
      "a_<q>_mean, a_<q>_ci95: mean over A's replicates and the half-width of its 95 % Student-t "
      "interval (empty: one replicate); b_ likewise. q: psi_sigma_deg (deg), ln_1_plus_e, ln_p "
      "(ln of p in kPa), q_over_p.",
      "diff_<q>: B − A of the means; diff_<q>_ci95: half-width of its 95 % interval (Welch, "
      "Welch–Satterthwaite degrees of freedom diff_<q>_dof, rounded down; with one replicate on "
      "a side the other side's variance stands for both; empty: no interval); <q>_differs: yes "
      "when the interval leaves out 0, no when it holds 0, empty without an interval.",
      "difference_interval: welch, variance_of_a, variance_of_b or none.",
  });
  text += CsvLine(header);
  for (const StateMatch& m : c.matches) {
    std::vector<std::string> f = {m.sample,
                                  ToString(m.kind),
                                  CsvText(m.case_name),
                                  CsvText(m.stage),
                                  std::to_string(m.a.replicates),
                                  CsvText(m.a.StatusText()),
                                  std::to_string(m.b.replicates),
                                  CsvText(m.b.StatusText()),
                                  CsvNumber(m.a.psi_epsilon.mean),
                                  CsvNumber(m.b.psi_epsilon.mean)};
    for (size_t q = 0; q < kStateQuantities.size(); ++q) {
      const MeanDifference& d = m.difference[q];
      for (const std::string& field :
           {CsvNumber(m.a.mean[q].mean), CsvNumber(m.a.mean[q].half_width),
            CsvNumber(m.b.mean[q].mean), CsvNumber(m.b.mean[q].half_width), CsvNumber(d.difference),
            CsvNumber(d.half_width), d.has_interval() ? fmt::format("{:g}", d.dof) : std::string(),
            Differs(d)}) {
        f.push_back(field);
      }
    }
    f.push_back(ToString(m.difference[0].interval));
    f.push_back(CsvText(m.note));
    text += CsvLine(f);
  }
  WriteTextFileAtomically(out + "/compare_states.csv", text);

  // compare_unmatched.csv
  text = Comments({
      fmt::format("States of A = {} or B = {} without a match: absent on one side, or without a "
                  "usable (detected or drifting, p > 0) replicate row on one side or both.",
                  c.a.name, c.b.name),
      "where: only in A, only in B, in both, usable in A only / B only / neither; a_status, "
      "b_status: the replicate rows' statuses with their counts (absent: no row).",
  });
  text += CsvLine({"sample", "kind", "case_name", "stage", "where", "a_status", "b_status"});
  for (const UnmatchedState& u : c.unmatched) {
    text += CsvLine({u.sample, ToString(u.kind), CsvText(u.case_name), CsvText(u.stage),
                     CsvText(u.where), CsvText(u.status_a), CsvText(u.status_b)});
  }
  WriteTextFileAtomically(out + "/compare_unmatched.csv", text);

  // compare_ncl.csv
  text = Comments({
      fmt::format("Lines of A = {} and B = {}: the isotropic NCL ln(1+e) = N − lambda_star ln(p / "
                  "1 kPa) of each NCL case (N and lambda_star over the replicates' fits of "
                  "ncl_fit.csv; the ensemble fit, replicate 0, left out), and the critical "
                  "states' M = q/p (line csl: over the detected csl states of the sample).",
                  c.a.name, c.b.name),
      "a_n, b_n: fits (or states); a_mean, a_ci95: mean and half-width of its 95 % Student-t "
      "interval (empty: one value); difference = B − A with its 95 % interval (as in "
      "compare_states.csv); differs: yes, no, or empty without an interval.",
  });
  text += CsvLine({"sample", "line", "case_name", "quantity", "a_n", "a_mean", "a_ci95", "b_n",
                   "b_mean", "b_ci95", "difference", "difference_ci95", "difference_dof",
                   "difference_interval", "differs"});
  for (const LineComparison& l : c.lines) {
    const MeanDifference& d = l.difference;
    text += CsvLine({l.sample, l.line, CsvText(l.case_name), l.quantity, std::to_string(l.a.n),
                     CsvNumber(l.a.mean), CsvNumber(l.a.half_width), std::to_string(l.b.n),
                     CsvNumber(l.b.mean), CsvNumber(l.b.half_width), CsvNumber(d.difference),
                     CsvNumber(d.half_width),
                     d.has_interval() ? fmt::format("{:g}", d.dof) : std::string(),
                     ToString(d.interval), Differs(d)});
  }
  WriteTextFileAtomically(out + "/compare_ncl.csv", text);
}

std::vector<FigureSpec> WriteComparisonFigureData(const std::string& out,
                                                  const StudyComparison& c) {
  const std::string data = out + "/figures/data";
  fs::create_directories(data);
  for (const auto& entry : fs::directory_iterator(data)) {
    if (entry.path().extension() == ".tsv") fs::remove(entry.path());
  }
  std::vector<FigureSpec> specs;
  StatesFigures(data, c, &specs);
  specs.push_back(DifferencesFigure(data, c));
  return specs;
}

void WriteComparisonSummary(const std::string& out, const StudyComparison& c,
                            const std::vector<FigureSpec>& figures) {
  std::string md = fmt::format("# Comparison of two studies: B − A\n\n");
  md += "| | A | B |\n|---|---|---|\n";
  md += fmt::format("| study | {} | {} |\n", c.a.name, c.b.name);
  md += fmt::format("| folder | `{}` | `{}` |\n", c.a.directory, c.b.directory);
  md += fmt::format("| programme | {} | {} |\n", c.a.programme, c.b.programme);
  md += fmt::format("| scale | {} | {} |\n", c.a.scale, c.b.scale);
  md += fmt::format("| spheres | {} | {} |\n", c.a.count, c.b.count);
  md += fmt::format("| replicates | {} | {} |\n", c.a.replicates, c.b.replicates);
  md += fmt::format("| own sample | {} | {} |\n\n", c.a.DescribeSample(), c.b.DescribeSample());

  std::string samples;
  for (const char* sample : {kSampleMain, kSampleOtherFriction, kSampleFineStep}) {
    const auto n = std::count_if(c.matches.begin(), c.matches.end(),
                                 [&](const StateMatch& m) { return m.sample == sample; });
    if (n > 0) {
      samples += fmt::format("{}{} of {}", samples.empty() ? "" : ", ", n, SampleTitle(sample));
    }
  }
  md += fmt::format(
      "## Matched asymptotic states\n\n{} states matched by sample, case name and stage ({}); "
      "{} without a match (below). A state is the mean over its study's replicates that are "
      "detected or drifting with p > 0; B − A is significant when its 95 % interval (Welch, "
      "Welch–Satterthwaite degrees of freedom; with one replicate on a side the other side's "
      "variance stands for both) leaves out 0. All numbers: `compare_states.csv`.\n\n",
      c.matches.size(), samples.empty() ? "none" : samples, c.unmatched.size());
  md +=
      "| kind | matched | ψ_σ differs | ln(1+e) differs | ln p differs | q/p differs | no "
      "interval |\n|---|---|---|---|---|---|---|\n";
  for (TableKind kind : {TableKind::kNcl, TableKind::kCsl, TableKind::kCompression,
                         TableKind::kExtension, TableKind::kTriaxial}) {
    int matched = 0, none = 0;
    for (const StateMatch& m : c.matches) {
      if (m.kind != kind) continue;
      ++matched;
      if (!m.difference[0].has_interval()) ++none;
    }
    if (matched == 0) continue;
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", KindTitle(kind), matched,
                      c.Differing(StateQuantity::kPsiSigma, kind),
                      c.Differing(StateQuantity::kLnVolume, kind),
                      c.Differing(StateQuantity::kLnP, kind),
                      c.Differing(StateQuantity::kStressRatio, kind), none);
  }
  int none = 0;
  for (const StateMatch& m : c.matches) none += m.difference[0].has_interval() ? 0 : 1;
  md +=
      fmt::format("| all | {} | {} | {} | {} | {} | {} |\n\n", c.matches.size(),
                  c.Differing(StateQuantity::kPsiSigma), c.Differing(StateQuantity::kLnVolume),
                  c.Differing(StateQuantity::kLnP), c.Differing(StateQuantity::kStressRatio), none);

  md +=
      "## NCL and critical state line\n\n| sample | line | quantity | A | B | B − A |\n"
      "|---|---|---|---|---|---|\n";
  for (const LineComparison& l : c.lines) {
    const int decimals = l.quantity == "lambda_star" ? 4 : 3;
    const std::string quantity = l.quantity == "lambda_star" ? "λ*" : l.quantity;
    const std::string line =
        l.line == "csl" ? "CSL (detected critical states)" : "NCL of case " + l.case_name;
    md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", l.sample, line, quantity,
                      LineText(l.a, decimals), LineText(l.b, decimals),
                      DifferenceText(l.difference, decimals, ""));
  }
  md += "\n";

  md += "## Largest differences\n\n";
  for (StateQuantity q : {StateQuantity::kPsiSigma, StateQuantity::kLnVolume}) {
    const size_t k = static_cast<size_t>(q);
    std::vector<const StateMatch*> order;
    for (const StateMatch& m : c.matches) {
      if (std::isfinite(m.difference[k].difference)) order.push_back(&m);
    }
    std::sort(order.begin(), order.end(), [k](const StateMatch* x, const StateMatch* y) {
      return std::abs(x->difference[k].difference) > std::abs(y->difference[k].difference);
    });
    if (order.size() > 5) order.resize(5);
    md += fmt::format("{} (B − A):\n\n", QuantitySymbol(q));
    for (const StateMatch* m : order) {
      md += fmt::format("- {} ({}, {} sample): {}; A {}, B {}\n", m->Label(), ToString(m->kind),
                        m->sample, DifferenceText(m->difference[k], Decimals(q), Unit(q)),
                        MeanText(m->a.mean[k], Decimals(q), Unit(q)),
                        MeanText(m->b.mean[k], Decimals(q), Unit(q)));
    }
    md += "\n";
  }

  md += "## Without a match\n\n";
  if (c.unmatched.empty()) {
    md += "Every state of each study has a usable match in the other.\n\n";
  } else {
    md += "| sample | kind | case | stage | where | A | B |\n|---|---|---|---|---|---|---|\n";
    for (const UnmatchedState& u : c.unmatched) {
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", u.sample, ToString(u.kind),
                        u.case_name, u.stage, u.where, u.status_a, u.status_b);
    }
    md += "\n";
  }

  md += "## Figures\n\n";
  for (const FigureSpec& f : figures) {
    md += fmt::format("**{}** ({}). {}\n\n", f.title, f.stem, f.caption);
    if (f.not_drawn.empty()) md += fmt::format("![{}](figures/{}.png)\n\n", f.title, f.stem);
  }
  md +=
      "Files: `compare_states.csv`, `compare_unmatched.csv`, `compare_ncl.csv`, "
      "`figures/index.tsv` (each figure's PNG, PDF and SVG with hover labels, and its "
      "gnuplot wrapper `figures/<stem>.plt`).\n";
  WriteTextFileAtomically(out + "/compare.md", md);
}

}  // namespace granasym::analysis
