#include "analysis/study_compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <tuple>

#include "analysis/figure_context.h"
#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/statistics.h"
#include "dem/run_record.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sample mean and variance (n − 1) of `values`.
void MeanVariance(const std::vector<double>& values, double* mean, double* variance) {
  *mean = Mean(values);
  *variance = kNaN;
  if (values.size() < 2) return;
  double squares = 0;
  for (double v : values) squares += (v - *mean) * (v - *mean);
  *variance = squares / static_cast<double>(values.size() - 1);
}

int SampleOrder(const std::string& sample) {
  return sample == kSampleMain ? 0 : sample == kSampleOtherFriction ? 1 : 2;
}

std::string SampleOfCase(figures::Sample sample) {
  switch (sample) {
    case figures::Sample::kMain:
      return kSampleMain;
    case figures::Sample::kOtherFriction:
      return kSampleOtherFriction;
    case figures::Sample::kFineStep:
      return kSampleFineStep;
  }
  return kSampleMain;
}

// The rows of one (sample, case name, stage) of one side.
struct Group {
  TableKind kind = TableKind::kNone;
  std::vector<const StateRow*> rows;
};
using Key = std::tuple<int, std::string, std::string, std::string>;  // order, sample, case, stage

std::map<Key, Group> GroupRows(const CompareStudy& study) {
  std::map<Key, Group> groups;
  for (const StateRow& row : study.states) {
    if (row.source != study::TableSource::kReplicate) continue;  // ensemble and joined rows
    const std::string sample = study.SampleOf(row);
    Group& group = groups[{SampleOrder(sample), sample, row.case_name, row.stage}];
    if (group.kind == TableKind::kNone) group.kind = row.kind;
    group.rows.push_back(&row);
  }
  return groups;
}

SideState Side(const Group* group) {
  SideState side;
  if (!group) return side;
  std::vector<double> psi_epsilon;
  for (const StateRow* row : group->rows) {
    ++side.statuses[ToString(row->status)];
    if (!figures::UsableState(*row)) continue;
    ++side.replicates;
    for (size_t q = 0; q < kStateQuantities.size(); ++q) {
      side.values[q].push_back(QuantityOf(*row, kStateQuantities[q]));
    }
    psi_epsilon.push_back(row->psi_epsilon_deg);
  }
  for (size_t q = 0; q < kStateQuantities.size(); ++q) side.mean[q] = Estimate::Of(side.values[q]);
  side.psi_epsilon = Estimate::Of(psi_epsilon);
  return side;
}

LineComparison Line(const std::string& sample, const std::string& line,
                    const std::string& case_name, const std::string& quantity,
                    std::vector<double> a, std::vector<double> b) {
  LineComparison c;
  c.sample = sample;
  c.line = line;
  c.case_name = case_name;
  c.quantity = quantity;
  c.a = Estimate::Of(a);
  c.b = Estimate::Of(b);
  c.difference = DifferenceOfMeans(a, b);
  c.values_a = std::move(a);
  c.values_b = std::move(b);
  return c;
}

// N and λ* of each NCL case over the replicates' fits; M of the detected
// critical states of each sample.
std::vector<LineComparison> CompareLines(const CompareStudy& a, const CompareStudy& b) {
  struct Fits {
    std::vector<double> n, lambda;
  };
  std::map<std::tuple<int, std::string, std::string>, std::pair<Fits, Fits>> ncl;
  auto add_fits = [&](const CompareStudy& study, bool first) {
    for (const auto& [key, fit] : study.ncl_fits) {
      if (key.first < 1) continue;  // replicate 0: the NCL through the ensemble rows
      StateRow probe;
      probe.replicate = key.first;
      probe.case_name = key.second;
      const std::string sample = study.SampleOf(probe);
      auto& pair = ncl[{SampleOrder(sample), sample, key.second}];
      Fits& fits = first ? pair.first : pair.second;
      fits.n.push_back(fit.first);
      fits.lambda.push_back(fit.second);
    }
  };
  add_fits(a, true);
  add_fits(b, false);
  std::vector<LineComparison> lines;
  for (const auto& [key, pair] : ncl) {
    const std::string& sample = std::get<1>(key);
    const std::string& name = std::get<2>(key);
    lines.push_back(Line(sample, "ncl", name, "N", pair.first.n, pair.second.n));
    lines.push_back(
        Line(sample, "ncl", name, "lambda_star", pair.first.lambda, pair.second.lambda));
  }
  std::map<std::pair<int, std::string>, std::pair<std::vector<double>, std::vector<double>>> csl;
  auto add_csl = [&](const CompareStudy& study, bool first) {
    for (const StateRow& row : study.states) {
      if (row.source != study::TableSource::kReplicate || row.kind != TableKind::kCsl ||
          row.status != TableStatus::kDetected || !figures::UsableState(row) ||
          !std::isfinite(row.q_over_p)) {
        continue;
      }
      const std::string sample = study.SampleOf(row);
      auto& pair = csl[{SampleOrder(sample), sample}];
      (first ? pair.first : pair.second).push_back(row.q_over_p);
    }
  };
  add_csl(a, true);
  add_csl(b, false);
  for (const auto& [key, pair] : csl) {
    lines.push_back(Line(key.second, "csl", "", "M", pair.first, pair.second));
  }
  std::stable_sort(lines.begin(), lines.end(), [](const auto& x, const auto& y) {
    return SampleOrder(x.sample) < SampleOrder(y.sample);
  });
  return lines;
}

CompareStudy Strip(CompareStudy study) {
  study.states.clear();
  study.samples.clear();
  return study;
}

// Names in the order a reader counts: digit runs by their value
// ("nc20_psi90" before "nc100_psi90"), the rest by character.
bool NaturalLess(const std::string& x, const std::string& y) {
  size_t i = 0, j = 0;
  while (i < x.size() && j < y.size()) {
    if (std::isdigit(static_cast<unsigned char>(x[i])) &&
        std::isdigit(static_cast<unsigned char>(y[j]))) {
      size_t ie = i, je = j;
      while (ie < x.size() && std::isdigit(static_cast<unsigned char>(x[ie]))) ++ie;
      while (je < y.size() && std::isdigit(static_cast<unsigned char>(y[je]))) ++je;
      const double vx = std::stod(x.substr(i, ie - i)), vy = std::stod(y.substr(j, je - j));
      if (vx != vy) return vx < vy;
      i = ie;
      j = je;
      continue;
    }
    if (x[i] != y[j]) return x[i] < y[j];
    ++i;
    ++j;
  }
  return x.size() - i < y.size() - j;
}

int KindOrder(TableKind kind) {
  switch (kind) {
    case TableKind::kNcl:
      return 0;
    case TableKind::kCsl:
      return 1;
    case TableKind::kCompression:
      return 2;
    case TableKind::kExtension:
      return 3;
    case TableKind::kTriaxial:
      return 4;
    case TableKind::kNone:
      return 5;
  }
  return 5;
}

}  // namespace

MeanDifference DifferenceOfMeans(const std::vector<double>& a, const std::vector<double>& b) {
  MeanDifference d;
  if (a.empty() || b.empty()) return d;
  double mean_a, var_a, mean_b, var_b;
  MeanVariance(a, &mean_a, &var_a);
  MeanVariance(b, &mean_b, &var_b);
  d.difference = mean_b - mean_a;
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  if (a.size() >= 2 && b.size() >= 2) {
    const double va = var_a / na, vb = var_b / nb;
    const double denominator = va * va / (na - 1) + vb * vb / (nb - 1);
    // Both variances zero: the replicates agree exactly, ν is that of the pooled count.
    d.dof = denominator > 0 ? std::floor((va + vb) * (va + vb) / denominator) : na + nb - 2;
    d.dof = std::max(1.0, d.dof);
    d.half_width = StudentT95(static_cast<int>(std::min(d.dof, 1e6))) * std::sqrt(va + vb);
    d.interval = DifferenceInterval::kWelch;
  } else if (a.size() >= 2 || b.size() >= 2) {
    const bool from_a = a.size() >= 2;
    const double n = from_a ? na : nb, variance = from_a ? var_a : var_b;
    d.dof = n - 1;
    d.half_width = StudentT95(static_cast<int>(d.dof)) * std::sqrt(variance * (1 / n + 1));
    d.interval = from_a ? DifferenceInterval::kVarianceOfA : DifferenceInterval::kVarianceOfB;
  }
  return d;
}

const char* QuantityColumn(StateQuantity quantity) {
  switch (quantity) {
    case StateQuantity::kPsiSigma:
      return "psi_sigma_deg";
    case StateQuantity::kLnVolume:
      return "ln_1_plus_e";
    case StateQuantity::kLnP:
      return "ln_p";
    case StateQuantity::kStressRatio:
      return "q_over_p";
  }
  return "";
}

const char* QuantitySymbol(StateQuantity quantity) {
  switch (quantity) {
    case StateQuantity::kPsiSigma:
      return "ψ_σ";
    case StateQuantity::kLnVolume:
      return "ln(1+e)";
    case StateQuantity::kLnP:
      return "ln p";
    case StateQuantity::kStressRatio:
      return "q/p";
  }
  return "";
}

double QuantityOf(const StateRow& row, StateQuantity quantity) {
  switch (quantity) {
    case StateQuantity::kPsiSigma:
      return row.psi_sigma_deg;
    case StateQuantity::kLnVolume:
      return row.ln_1_plus_e;
    case StateQuantity::kLnP:
      return row.p_kpa > 0 ? std::log(row.p_kpa) : kNaN;
    case StateQuantity::kStressRatio:
      return row.q_over_p;
  }
  return kNaN;
}

std::string SampleTitle(const std::string& sample) {
  if (sample == kSampleMain) return "the study's own sample";
  if (sample == kSampleOtherFriction) return "the sample of other contact friction";
  if (sample == kSampleFineStep) return "the sample of the finer time step";
  return sample;
}

std::string CompareStudy::SampleOf(const StateRow& row) const {
  const auto it = samples.find({row.replicate, row.case_name});
  return it == samples.end() ? kSampleMain : it->second;
}

std::string CompareStudy::Describe() const {
  return fmt::format("{}, {}: {} spheres × {} replicate{}", programme.empty() ? "?" : programme,
                     scale.empty() ? "?" : scale, count, replicates, replicates == 1 ? "" : "s");
}

std::string CompareStudy::DescribeSample() const {
  auto number = [](double v, const char* format) {
    return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string("?");
  };
  return fmt::format("φ = {} rad, E = {} MPa, Δt = {} s", number(friction_rad, "{:.3g}"),
                     number(youngs_modulus_mpa, "{:.4g}"), number(time_step_s, "{:.3g}"));
}

void RenameCases(CompareStudy* study, const std::string& rule, const std::string& flag) {
  const size_t eq = rule.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(flag + " '" + rule + "': expected REGEX=REPLACEMENT, e.g. " +
                     "'(nc\\d+_psi\\d+)_I0\\.001_E500=$1'");
  }
  std::regex pattern;
  try {
    pattern = std::regex(rule.substr(0, eq), std::regex::ECMAScript);
  } catch (const std::regex_error& error) {
    throw InputError(flag + " '" + rule + "': the regex is not valid (" + error.what() + ")");
  }
  const std::string replacement = rule.substr(eq + 1);
  std::set<std::string> names;
  for (const StateRow& row : study->states) names.insert(row.case_name);
  std::map<std::string, std::string> renamed;  // old → new
  std::map<std::string, std::string> origin;   // new → old
  for (const std::string& name : names) {
    const std::string now = std::regex_match(name, pattern)
                                ? std::regex_replace(name, pattern, replacement,
                                                     std::regex_constants::format_first_only)
                                : name;
    if (const auto it = origin.find(now); it != origin.end()) {
      throw InputError(flag + " '" + rule + "' gives '" + it->second + "' and '" + name +
                       "' one name, '" + now +
                       "': their replicates would be pooled; make the pattern match one of them");
    }
    origin[now] = name;
    if (now != name) renamed[name] = now;
  }
  if (renamed.empty()) {
    throw InputError(flag + " '" + rule + "' matches no case name of " + study->directory);
  }
  for (StateRow& row : study->states) {
    if (const auto it = renamed.find(row.case_name); it != renamed.end())
      row.case_name = it->second;
  }
  std::map<std::pair<int, std::string>, std::string> samples;
  for (const auto& [key, sample] : study->samples) {
    const auto it = renamed.find(key.second);
    samples[{key.first, it == renamed.end() ? key.second : it->second}] = sample;
  }
  study->samples = samples;
}

CompareStudy ReadCompareStudy(const std::string& directory) {
  if (!fs::is_directory(directory)) {
    throw InputError(directory + ": not a folder (give a study folder of `granasym study run`)");
  }
  if (!fs::exists(directory + "/study.toml")) {
    throw InputError(directory +
                     ": not a study folder (no study.toml; give a folder written by "
                     "`granasym study run` or `study merge`)");
  }
  if (!fs::exists(directory + "/asymptotic_states.h5")) {
    throw InputError(directory +
                     ": the study has no state table (asymptotic_states.h5): run `granasym "
                     "study run` (or `study merge`) on it first");
  }
  CompareStudy study;
  study.directory = directory;
  study.name = fs::path(directory).lexically_normal().filename().string();
  if (study.name.empty() || study.name == ".") {
    study.name = fs::absolute(directory).lexically_normal().parent_path().filename().string();
  }
  const ConfigTable record = ConfigTable::ParseFile(directory + "/study.toml");
  study.programme = record.GetString("programme", "");
  study.scale = record.GetString("scale", "");
  study.count = static_cast<int>(record.GetInt("count", 0, Range::Any()));
  study.replicates = static_cast<int>(record.GetInt("replicates", 0, Range::Any()));

  FigureDataOptions options;
  options.settings.models = std::vector<std::string>{};  // no model overlays are read
  const figures::Context ctx = figures::ReadContext(directory, options);
  study.states = study::ReadStateTable(directory);
  study.study_ncl = ctx.study_ncl;
  for (const figures::CaseData& c : ctx.cases) {
    study.samples[{c.replicate, c.name}] = SampleOfCase(c.sample);
  }
  for (const auto& [key, line] : ctx.ncl_fits) study.ncl_fits[key] = {line.n, line.lambda};
  study.friction_rad = ctx.main_friction;
  study.time_step_s = ctx.main_time_step > 0 ? ctx.main_time_step : kNaN;
  if (const figures::CaseData* ncl = ctx.Case(1, ctx.study_ncl); ncl && ncl->finished) {
    const Hdf5File file = Hdf5File::OpenRead(ncl->directory + "/result.h5");
    study.youngs_modulus_mpa = dem::ReadMaterial(file).youngs_modulus / 1e6;
  }
  return study;
}

std::string SideState::StatusText() const {
  if (statuses.empty()) return "absent";
  std::string text;
  for (const auto& [status, n] : statuses) {
    text += fmt::format("{}{} {}", text.empty() ? "" : ", ", status, n);
  }
  return text;
}

std::string StateMatch::Label() const {
  const std::string suffix = "_" + stage;
  if (stage.empty() ||
      (case_name.size() > suffix.size() &&
       case_name.compare(case_name.size() - suffix.size(), suffix.size(), suffix) == 0)) {
    return case_name;
  }
  return case_name + "@" + stage;
}

int StudyComparison::Differing(StateQuantity quantity, TableKind kind) const {
  const size_t q = static_cast<size_t>(quantity);
  int n = 0;
  for (const StateMatch& m : matches) {
    if ((kind == TableKind::kNone || m.kind == kind) && m.difference[q].excludes_zero()) ++n;
  }
  return n;
}

const LineComparison* StudyComparison::Line(const std::string& sample, const std::string& line,
                                            const std::string& quantity,
                                            const std::string& case_name) const {
  for (const LineComparison& c : lines) {
    if (c.sample == sample && c.line == line && c.quantity == quantity &&
        (case_name.empty() || c.case_name == case_name)) {
      return &c;
    }
  }
  return nullptr;
}

std::string WithInterval(double value, double half_width, int decimals, bool sign) {
  if (!std::isfinite(value)) return "–";
  const std::string v =
      sign ? fmt::format("{:+.{}f}", value, decimals) : fmt::format("{:.{}f}", value, decimals);
  if (!std::isfinite(half_width)) return v + " (no interval)";
  return v + fmt::format(" ± {:.{}f}", half_width, decimals);
}

std::string StudyComparison::Text() const {
  std::string text = fmt::format("A = {} ({}; {})\nB = {} ({}; {})\n", a.name, a.Describe(),
                                 a.DescribeSample(), b.name, b.Describe(), b.DescribeSample());
  int no_interval = 0;
  for (const StateMatch& m : matches) {
    if (!m.difference[0].has_interval()) ++no_interval;
  }
  std::string samples;
  for (const char* sample : {kSampleMain, kSampleOtherFriction, kSampleFineStep}) {
    const auto n = std::count_if(matches.begin(), matches.end(),
                                 [&](const StateMatch& m) { return m.sample == sample; });
    if (n > 0) samples += fmt::format("{}{} {}", samples.empty() ? "" : ", ", sample, n);
  }
  int only_a = 0, only_b = 0;
  for (const UnmatchedState& u : unmatched) {
    if (u.where == "only in A") ++only_a;
    if (u.where == "only in B") ++only_b;
  }
  text += fmt::format(
      "{} states matched ({}); {} unmatched ({} only in A, {} only in B, {} without usable "
      "states on one side or both)\n",
      matches.size(), samples.empty() ? "none" : samples, unmatched.size(), only_a, only_b,
      unmatched.size() - only_a - only_b);
  std::string differ;
  for (StateQuantity q : kStateQuantities) {
    differ += fmt::format("{}{} {}", differ.empty() ? "" : ", ", QuantitySymbol(q), Differing(q));
  }
  text += fmt::format("differing (95 % interval of B − A leaves out 0): {} of {}", differ,
                      matches.size());
  text += no_interval > 0 ? fmt::format("; {} without an interval\n", no_interval) : "\n";
  for (const LineComparison& c : lines) {
    if (c.sample != kSampleMain) continue;
    const int decimals = c.quantity == "lambda_star" ? 4 : 3;
    const std::string name = c.line == "csl"               ? "CSL M"
                             : c.quantity == "lambda_star" ? "NCL " + c.case_name + " λ*"
                                                           : "NCL " + c.case_name + " N";
    auto side = [&](const Estimate& e) {
      if (e.n == 0) return std::string("none");
      if (!e.has_interval()) return fmt::format("{:.{}f} (n = 1, no interval)", e.mean, decimals);
      return fmt::format("{:.{}f} ± {:.{}f} (n = {})", e.mean, decimals, e.half_width, decimals,
                         e.n);
    };
    text +=
        fmt::format("{}: A {}, B {}; B − A {}{}\n", name, side(c.a), side(c.b),
                    WithInterval(c.difference.difference, c.difference.half_width, decimals, true),
                    c.difference.excludes_zero() ? " (differs)" : "");
  }
  return text;
}

StudyComparison CompareStudies(const CompareStudy& a, const CompareStudy& b) {
  StudyComparison c;
  const std::map<Key, Group> groups_a = GroupRows(a), groups_b = GroupRows(b);
  std::set<Key> keys;
  for (const auto& [key, group] : groups_a) keys.insert(key);
  for (const auto& [key, group] : groups_b) keys.insert(key);
  for (const Key& key : keys) {
    const auto ia = groups_a.find(key), ib = groups_b.find(key);
    const Group* ga = ia == groups_a.end() ? nullptr : &ia->second;
    const Group* gb = ib == groups_b.end() ? nullptr : &ib->second;
    SideState sa = Side(ga), sb = Side(gb);
    const TableKind kind = ga ? ga->kind : gb->kind;
    if (sa.replicates > 0 && sb.replicates > 0) {
      StateMatch m;
      std::tie(std::ignore, m.sample, m.case_name, m.stage) = key;
      m.kind = kind;
      for (size_t q = 0; q < kStateQuantities.size(); ++q) {
        m.difference[q] = DifferenceOfMeans(sa.values[q], sb.values[q]);
      }
      std::vector<std::string> notes;
      if (sa.replicates == 1 && sb.replicates == 1) {
        notes.push_back("one replicate on each side: no interval");
      } else if (sa.replicates == 1 || sb.replicates == 1) {
        notes.push_back(
            fmt::format("{} has one replicate (no interval of its own): the variance "
                        "of {}'s {} replicates stands for both",
                        sa.replicates == 1 ? "A" : "B", sa.replicates == 1 ? "B" : "A",
                        std::max(sa.replicates, sb.replicates)));
      }
      if (gb->kind != ga->kind) {
        notes.push_back(
            fmt::format("kind {} in A, {} in B", ToString(ga->kind), ToString(gb->kind)));
      }
      for (const std::string& n : notes) m.note += (m.note.empty() ? "" : "; ") + n;
      m.a = std::move(sa);
      m.b = std::move(sb);
      c.matches.push_back(std::move(m));
      continue;
    }
    UnmatchedState u;
    std::tie(std::ignore, u.sample, u.case_name, u.stage) = key;
    u.kind = kind;
    u.status_a = sa.StatusText();
    u.status_b = sb.StatusText();
    u.where = !ga                 ? "only in B"
              : !gb               ? "only in A"
              : sa.replicates > 0 ? "in both, usable in A only"
              : sb.replicates > 0 ? "in both, usable in B only"
                                  : "in both, usable in neither";
    c.unmatched.push_back(std::move(u));
  }
  auto order = [](const auto& x, const auto& y) {
    if (SampleOrder(x.sample) != SampleOrder(y.sample)) {
      return SampleOrder(x.sample) < SampleOrder(y.sample);
    }
    if (KindOrder(x.kind) != KindOrder(y.kind)) return KindOrder(x.kind) < KindOrder(y.kind);
    if (x.case_name != y.case_name) return NaturalLess(x.case_name, y.case_name);
    return NaturalLess(x.stage, y.stage);
  };
  std::sort(c.matches.begin(), c.matches.end(), order);
  std::sort(c.unmatched.begin(), c.unmatched.end(), order);
  c.lines = CompareLines(a, b);
  c.a = Strip(a);
  c.b = Strip(b);
  return c;
}

}  // namespace granasym::analysis
