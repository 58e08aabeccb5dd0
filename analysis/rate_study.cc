#include "analysis/rate_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "common/config.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/statistics.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "study/case_record.h"

namespace granasym::analysis {
using study::CaseRecord;
using study::FigureSet;
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool HasFlag(const std::string& flags, const std::string& flag) {
  std::stringstream in(flags);
  std::string item;
  while (std::getline(in, item, ';')) {
    if (Trimmed(item) == flag) return true;
  }
  return false;
}

// Whether a state's status is one of `statuses` and it carries none of the
// options' excluded flags (the part of usability that proportional and
// drained states share).
bool PassesFilters(TableStatus status, const std::string& flags,
                   const std::vector<TableStatus>& statuses, const RateStudyOptions& options) {
  if (std::find(statuses.begin(), statuses.end(), status) == statuses.end()) return false;
  for (const std::string& flag : options.excluded_flags) {
    if (HasFlag(flags, flag)) return false;
  }
  return true;
}

// The verdict of named comparisons: rate_dependent when one differs (the
// reason names each that does), rate_independent when all agree, else
// undetermined (the reason: `missing`, what lacks an interval).
std::string VerdictOf(const std::vector<std::pair<const char*, const Comparison*>>& comparisons,
                      const std::vector<std::string>& missing, std::string* reason,
                      const std::string& subject = "rate") {
  bool differs = false, agree = true;
  std::vector<std::string> reasons;
  for (const auto& [name, c] : comparisons) {
    agree = agree && c->agreement == Agreement::kAgree;
    if (c->agreement == Agreement::kDiffer) {
      differs = true;
      reasons.push_back(fmt::format("{} differs by {:.4g} (95 % interval +-{:.2g})", name,
                                    c->difference, c->half_width));
    }
  }
  if (!differs && !agree) reasons = missing;
  for (const std::string& r : reasons) *reason += (reason->empty() ? "" : "; ") + r;
  return differs ? subject + "_dependent" : agree ? subject + "_independent" : "undetermined";
}

// The mean with its interval of one member over the finite values of `used`.
template <typename State>
Estimate MeanOver(const std::vector<const State*>& used, double State::*member) {
  std::vector<double> values;
  for (const State* s : used) {
    if (std::isfinite(s->*member)) values.push_back(s->*member);
  }
  return Estimate::Of(values);
}

// A state that liquefied: a gas (status or flag), no asymptotic state.
bool IsLiquefied(TableStatus status, const std::string& flags) {
  return status == TableStatus::kGas || HasFlag(flags, "gas");
}

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

// ---------------------------------------------------------------- reading

// The `key = value` lines of a canonical scene (common/canonical_text.h);
// string values keep their quotes.
std::map<std::string, std::string> CanonicalLines(const std::string& text) {
  std::map<std::string, std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find(" = ");
    if (eq != std::string::npos) lines[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return lines;
}

std::optional<double> CanonicalNumber(const std::map<std::string, std::string>& lines,
                                      const std::string& key) {
  const auto it = lines.find(key);
  if (it == lines.end()) return std::nullopt;
  try {
    size_t used = 0;
    const double value = std::stod(it->second, &used);
    if (used == it->second.size()) return value;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// The p target of stage `stage` of the run in `result` (its canonical scene),
// or the stage's final p when it has none.
double StartStress(const std::string& result, const std::string& stage) {
  if (!fs::exists(result)) return kNaN;  // a parent computed again since: its start is unknown
  const Hdf5File file = Hdf5File::OpenRead(result);
  const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
  const auto canonical = CanonicalLines(dem::ReadProvenance(file).scene_canonical);
  size_t index = stages.size();
  for (size_t k = 0; k < stages.size(); ++k) {
    if (stage.empty() ? k + 1 == stages.size() : stages[k].name == stage) index = k;
  }
  if (index == stages.size()) return kNaN;
  const std::optional<double> target =
      CanonicalNumber(canonical, fmt::format("stage[{}].stop.mean_stress_kpa", index));
  return target ? *target : stages[index].validity.final_mean_stress_kpa;
}

// ---------------------------------------------------------------- writing

using Columns = std::vector<std::pair<std::string, std::string>>;  // name, field

std::string CsvLine(const Columns& fields, bool header) {
  std::string line;
  for (size_t k = 0; k < fields.size(); ++k) {
    line += (k ? "," : "") + (header ? fields[k].first : fields[k].second);
  }
  return line + "\n";
}

// Rows of (column, field) pairs into CSV text with a header and comments.
class CsvWriter {
 public:
  explicit CsvWriter(std::vector<std::string> comments) : comments_(std::move(comments)) {}
  void Add(const Columns& fields) {
    if (header_.empty()) header_ = CsvLine(fields, true);
    body_ += CsvLine(fields, false);
  }
  // The header of a table without rows.
  void SetHeader(const Columns& fields) {
    if (header_.empty()) header_ = CsvLine(fields, true);
  }
  // Every row through `fields` (a default row gives the header of an empty
  // table), then the file.
  template <typename Row, typename Fields>
  void WriteRows(const std::vector<Row>& rows, Fields fields, const std::string& path) {
    for (const Row& row : rows) Add(fields(row));
    SetHeader(fields(Row{}));
    Write(path);
  }
  void Write(const std::string& path) const {
    std::string text;
    for (const std::string& comment : comments_) text += "# " + comment + "\n";
    WriteTextFileAtomically(path, text + header_ + body_);
  }

 private:
  std::vector<std::string> comments_;
  std::string header_, body_;
};

void AddEstimate(Columns* fields, const std::string& name, const Estimate& estimate) {
  fields->emplace_back(name + "_mean", CsvNumber(estimate.mean));
  fields->emplace_back(name + "_ci95", CsvNumber(estimate.half_width));
}

// A comparison's difference, its 95 % half-width and the agreement.
void AddDifference(Columns* fields, const std::string& name, const Comparison& c) {
  fields->emplace_back(name + "_difference", CsvNumber(c.difference));
  fields->emplace_back(name + "_difference_ci95", CsvNumber(c.half_width));
  fields->emplace_back(name + "_agreement", ToString(c.agreement));
}

// Two estimates, NAME + suffix_a / suffix_b, and their comparison (b − a).
void AddComparison(Columns* fields, const std::string& name, const std::string& suffix_a,
                   const std::string& suffix_b, const Estimate& a, const Estimate& b,
                   const Comparison& c) {
  AddEstimate(fields, name + suffix_a, a);
  AddEstimate(fields, name + suffix_b, b);
  AddDifference(fields, name, c);
}

Columns KeyFields(const RateKey& key) {
  return {
      {"youngs_modulus_mpa", CsvNumber(key.youngs_modulus_mpa)},
      {"psi_epsilon_deg", CsvNumber(key.psi_epsilon_deg)},
      {"start_p_kpa", CsvNumber(key.start_p_kpa)},
      {"rate_rule", ToString(key.rule)},
      {"inertial_number_target", CsvNumber(key.rule == dem::RateRule::kInertial ? key.rate : kNaN)},
      {"stretching_rate_per_s", CsvNumber(key.rule == dem::RateRule::kConstant ? key.rate : kNaN)}};
}

Columns StateFields(const RateState& s) {
  return {{"replicate", std::to_string(s.replicate)},
          {"case_name", CsvText(s.case_name)},
          {"stage", CsvText(s.stage)},
          {"kind", ToString(s.kind)},
          {"status", ToString(s.status)},
          {"youngs_modulus_mpa", CsvNumber(s.youngs_modulus_mpa)},
          {"psi_epsilon_deg", CsvNumber(s.psi_epsilon_deg)},
          {"start_p_kpa", CsvNumber(s.start_p_kpa)},
          {"rate_rule", ToString(s.rule)},
          {"inertial_number_target", CsvNumber(s.inertial_number)},
          {"stretching_rate_per_s", CsvNumber(s.stretching_rate)},
          {"p_kpa", CsvNumber(s.p_kpa)},
          {"e", CsvNumber(s.e)},
          {"ln_1_plus_e", CsvNumber(s.ln_1_plus_e)},
          {"psi_sigma_deg", CsvNumber(s.psi_sigma_deg)},
          {"q_over_p", CsvNumber(s.q_over_p)},
          {"ocr", CsvNumber(s.ocr)},
          {"ocr_same_rate", CsvNumber(s.ocr_same_rate)},
          {"inertial_number_dmin", CsvNumber(s.inertial_number_dmin)},
          {"inertial_number_dmax", CsvNumber(s.inertial_number_dmax)},
          {"stiffness_number", CsvNumber(s.stiffness_number)},
          {"path_N", CsvNumber(s.path_n)},
          {"path_lambda", CsvNumber(s.path_lambda)},
          {"path_p_min_kpa", CsvNumber(s.path_p_min_kpa)},
          {"path_p_max_kpa", CsvNumber(s.path_p_max_kpa)},
          {"flags", CsvText(s.flags)}};
}

Columns DrainedStateFields(const DrainedState& s) {
  return {{"replicate", std::to_string(s.replicate)},
          {"case_name", CsvText(s.case_name)},
          {"stage", CsvText(s.stage)},
          {"status", ToString(s.status)},
          {"youngs_modulus_mpa", CsvNumber(s.youngs_modulus_mpa)},
          {"radial_stress_kpa", CsvNumber(s.radial_stress_kpa)},
          {"axial_strain_rate_per_s", CsvNumber(s.axial_strain_rate)},
          {"p_kpa", CsvNumber(s.p_kpa)},
          {"e", CsvNumber(s.e)},
          {"ln_1_plus_e", CsvNumber(s.ln_1_plus_e)},
          {"psi_sigma_deg", CsvNumber(s.psi_sigma_deg)},
          {"q_over_p", CsvNumber(s.q_over_p)},
          {"inertial_number_dmin", CsvNumber(s.inertial_number_dmin)},
          {"inertial_number_dmax", CsvNumber(s.inertial_number_dmax)},
          {"flags", CsvText(s.flags)}};
}

// The four drained files (rate_drained*.csv).
void WriteDrainedFiles(const std::string& directory, const DrainedStudy& d,
                       const RateStudyOptions& o, const std::string& usable) {
  CsvWriter states(
      {"the asymptotic states of the drained triaxial rate cases (constant sigma_r, "
       "constant axial rate), one row per case and detector stage"});
  states.WriteRows(d.states, DrainedStateFields, directory + "/" + kRateDrainedStatesFile);

  CsvWriter groups(
      {"per (E, sigma_r, axial rate): the mean over the replicates' usable states "
       "and the half-width of its 95 % interval (Student t, n - 1 degrees of "
       "freedom); q_over_p is the critical-state ratio M",
       usable});
  auto group_fields = [](const DrainedGroup& g) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(g.youngs_modulus_mpa)},
                      {"radial_stress_kpa", CsvNumber(g.radial_stress_kpa)},
                      {"axial_strain_rate_per_s", CsvNumber(g.axial_strain_rate)},
                      {"states", std::to_string(g.states)},
                      {"used", std::to_string(g.used)}};
    AddEstimate(&fields, "p_kpa", g.p_kpa);
    AddEstimate(&fields, "e", g.e);
    AddEstimate(&fields, "ln_1_plus_e", g.ln_1_plus_e);
    AddEstimate(&fields, "psi_sigma_deg", g.psi_sigma_deg);
    AddEstimate(&fields, "q_over_p", g.q_over_p);
    AddEstimate(&fields, "inertial_number_dmax", g.inertial_number_dmax);
    return fields;
  };
  groups.WriteRows(d.groups, group_fields, directory + "/" + kRateDrainedFile);

  CsvWriter limits(
      {"per (E, sigma_r): y = a + b I(d_max) by least squares through the usable "
       "states of every axial rate (I(d_max) as measured over each asymptote's "
       "window): the limits as I -> 0 of M = q/p, ln(1+e) and ln p with 95 % "
       "intervals (Student t, points - 2 degrees of freedom); the two slowest "
       "rates compared in M and ln(1+e): rate_independent when both agree within "
       "the 95 % interval of their difference",
       usable});
  auto limit_fields = [](const DrainedLimit& l) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(l.youngs_modulus_mpa)},
                      {"radial_stress_kpa", CsvNumber(l.radial_stress_kpa)},
                      {"rates", std::to_string(l.rates)},
                      {"points", std::to_string(l.points)},
                      {"i_min", CsvNumber(l.i_min)},
                      {"i_max", CsvNumber(l.i_max)}};
    AddEstimate(&fields, "m", l.m);
    AddEstimate(&fields, "m_slope", l.m_slope);
    AddEstimate(&fields, "ln_1_plus_e", l.ln_1_plus_e);
    AddEstimate(&fields, "ln_p_kpa", l.ln_p_kpa);
    fields.emplace_back("slowest_rate_per_s", CsvNumber(l.slowest));
    fields.emplace_back("next_rate_per_s", CsvNumber(l.next));
    AddDifference(&fields, "m", l.m_change);
    AddDifference(&fields, "ln_1_plus_e", l.ln_1_plus_e_change);
    fields.emplace_back("verdict", l.verdict);
    fields.emplace_back("reason", CsvText(l.reason));
    return fields;
  };
  limits.WriteRows(d.limits, limit_fields, directory + "/" + kRateDrainedLimitFile);

  CsvWriter critical(
      {fmt::format("per E: the quasi-static critical state from the limits of every sigma_r: M "
                   "the mean of their M (Student t, starts - 1 degrees of freedom), phi_c = "
                   "asin(3M/(6+M)) (interval by the delta method), dM/d ln p the least-squares "
                   "slope of their M against ln p (zero within its interval: M independent of "
                   "p), and the CSL ln(1+e) = Gamma - lambda ln(p / 1 kPa) through their (ln p, "
                   "ln(1+e)) with its position at p = {:g} kPa (Student t, starts - 2 degrees "
                   "of freedom; from the scatter of the limits, not their own intervals)",
                   o.reference_p_kpa),
       usable});
  auto critical_fields = [&o](const DrainedCriticalState& c) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(c.youngs_modulus_mpa)},
                      {"starts", std::to_string(c.starts)}};
    AddEstimate(&fields, "m", c.m);
    AddEstimate(&fields, "phi_c_deg", c.phi_c_deg);
    AddEstimate(&fields, "m_per_ln_p", c.m_per_ln_p);
    AddEstimate(&fields, "lambda", c.lambda);
    fields.emplace_back("gamma", CsvNumber(c.gamma));
    fields.emplace_back("reference_p_kpa", CsvNumber(o.reference_p_kpa));
    AddEstimate(&fields, "position", c.position);
    return fields;
  };
  critical.WriteRows(d.critical, critical_fields, directory + "/" + kRateDrainedCriticalFile);
}

}  // namespace

// ---------------------------------------------------------------- analysis

bool RateStudyOptions::IsValid(std::string* why) const {
  if (statuses.empty()) {
    *why = "statuses: give at least one detector status";
    return false;
  }
  if (fit_rates < 2) {
    *why = fmt::format("fit_rates = {}: a line needs at least 2 rates", fit_rates);
    return false;
  }
  if (!(reference_p_kpa > 0) || !std::isfinite(reference_p_kpa)) {
    *why = "reference_p_kpa: must be a positive mean stress (kPa)";
    return false;
  }
  return true;
}

Estimate Estimate::Of(const std::vector<double>& values) {
  Estimate estimate;
  estimate.n = static_cast<int>(values.size());
  if (values.empty()) return estimate;
  double sum = 0;
  for (double v : values) sum += v;
  estimate.mean = sum / static_cast<double>(values.size());
  if (values.size() < 2) return estimate;
  double squares = 0;
  for (double v : values) squares += (v - estimate.mean) * (v - estimate.mean);
  const double variance = squares / static_cast<double>(values.size() - 1);
  estimate.dof = estimate.n - 1;
  estimate.standard_error = std::sqrt(variance / static_cast<double>(values.size()));
  estimate.half_width = StudentT95(estimate.dof) * estimate.standard_error;
  return estimate;
}

Estimate Estimate::Fitted(double value, double standard_error, int points) {
  Estimate estimate;
  estimate.mean = value;
  estimate.n = points;
  if (points >= 3 && std::isfinite(standard_error)) {
    estimate.dof = points - 2;
    estimate.standard_error = standard_error;
    estimate.half_width = StudentT95(estimate.dof) * standard_error;
  }
  return estimate;
}

Comparison Compare(const Estimate& a, const Estimate& b) {
  Comparison c;
  c.difference = b.mean - a.mean;
  if (!std::isfinite(c.difference) || !a.has_interval() || !b.has_interval()) return c;
  const double va = a.standard_error * a.standard_error, vb = b.standard_error * b.standard_error;
  const double denominator = va * va / a.dof + vb * vb / b.dof;
  double dof = denominator > 0 ? (va + vb) * (va + vb) / denominator : a.dof + b.dof;
  dof = std::max(1.0, std::floor(dof));
  c.half_width = StudentT95(static_cast<int>(std::min(dof, 1e6))) * std::sqrt(va + vb);
  c.agreement = std::abs(c.difference) <= c.half_width ? Agreement::kAgree : Agreement::kDiffer;
  return c;
}

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

static void AnalyseExtension(RateStudy* study);  // §3: extension_steps and extension_limits
static void AnalyseStiffness(RateStudy* study);  // §1: stiffness

RateStudy RateStudy::Analyse(std::vector<RateState> states, const RateStudyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("rate study options: " + why);
  RateStudy study;
  study.options = options;
  study.states = std::move(states);

  // Lines per (E, ψ_ε, rate) through the usable states of every start.
  using LineKey = std::tuple<double, double, dem::RateRule, double>;
  std::map<LineKey, std::vector<const RateState*>> line_members;
  for (const RateState& s : study.states) {
    if (study.Usable(s)) {
      line_members[{s.youngs_modulus_mpa, s.psi_epsilon_deg, s.rule, s.rate()}].push_back(&s);
    }
  }
  const double ln_reference = std::log(options.reference_p_kpa);
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
        if (s->path_p_min_kpa <= options.reference_p_kpa &&
            options.reference_p_kpa <= s->path_p_max_kpa) {
          positions.push_back(s->path_n - s->path_lambda * ln_reference);
        }
      }
      line.points = static_cast<int>(ns.size());
      line.n = Estimate::Of(ns).mean;
      line.lambda = Estimate::Of(lambdas).mean;
      line.position = Estimate::Of(positions);
      study.lines.push_back(line);
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
    study.lines.push_back(line);
  }
  // OCR against the NCL of the same E and rate (the ψ_ε = 0° line of that
  // rate): p_e*/p with ln(1+e) = N − λ ln(p_e* / 1 kPa) at the state's
  // ln(1+e), where p_e* lies in the line's p range (the NCL of frictional
  // spheres is curved: the line is no NCL outside it).
  for (RateState& s : study.states) {
    s.ocr_same_rate = kNaN;
    const RateLine* l = FindLine(study.lines, s.youngs_modulus_mpa, 0, s.rule, s.rate());
    if (l && l->valid() && l->lambda > 0 && s.p_kpa > 0) {
      const double p_e = std::exp((l->n - s.ln_1_plus_e) / l->lambda);
      if (p_e >= l->p_min_kpa && p_e <= l->p_max_kpa) s.ocr_same_rate = p_e / s.p_kpa;
    }
  }

  // Groups: the replicates of one (E, ψ_ε, p_0, rate).
  std::map<RateKey, std::vector<const RateState*>> members;
  for (const RateState& s : study.states) members[KeyOf(s)].push_back(&s);
  for (const auto& [key, list] : members) {
    RateGroup group;
    group.key = key;
    group.states = static_cast<int>(list.size());
    std::vector<const RateState*> used;
    for (const RateState* s : list) {
      if (study.Usable(*s)) used.push_back(s);
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
    study.groups.push_back(group);
  }

  // Per (E, ψ_ε, p_0): the inertial groups in ascending I*.
  using StartKey = std::tuple<double, double, double>;
  std::map<StartKey, std::vector<const RateGroup*>> by_start;
  for (const RateGroup& g : study.groups) {
    if (g.key.rule != dem::RateRule::kInertial) continue;
    by_start[{g.key.youngs_modulus_mpa, g.key.psi_epsilon_deg, g.key.start_p_kpa}].push_back(&g);
  }
  for (const auto& [start, groups] : by_start) {
    const auto& [e_mpa, psi, p0] = start;
    // Quasi-static limits: the smallest I* with usable states.
    std::vector<const RateGroup*> fitted;
    for (const RateGroup* g : groups) {
      if (g->used > 0 && static_cast<int>(fitted.size()) < options.fit_rates) fitted.push_back(g);
    }
    for (const char* quantity : {"psi_sigma_deg", "q_over_p", "ln_1_plus_e"}) {
      const std::string name = quantity;
      double RateState::*member = name == "psi_sigma_deg" ? &RateState::psi_sigma_deg
                                  : name == "q_over_p"    ? &RateState::q_over_p
                                                          : &RateState::ln_1_plus_e;
      QuasiStaticFit fit;
      fit.youngs_modulus_mpa = e_mpa;
      fit.psi_epsilon_deg = psi;
      fit.start_p_kpa = p0;
      fit.quantity = name;
      std::vector<double> x, y;
      for (const RateGroup* g : fitted) {
        fit.rates.push_back(g->key.rate);
        for (const RateState& s : study.states) {
          if (!(KeyOf(s) == g->key) || !study.Usable(s)) continue;
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
      study.quasi_static.push_back(fit);
    }
    // Rate independence: the two smallest I* of the programme, whatever they reached.
    if (groups.size() < 2) continue;
    RateVerdict v;
    v.youngs_modulus_mpa = e_mpa;
    v.psi_epsilon_deg = psi;
    v.start_p_kpa = p0;
    const RateGroup& a = *groups[0];
    const RateGroup& b = *groups[1];
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
    const RateLine* csl_a =
        FindLine(study.lines, e_mpa, 90.0, dem::RateRule::kInertial, a.key.rate);
    const RateLine* csl_b =
        FindLine(study.lines, e_mpa, 90.0, dem::RateRule::kInertial, b.key.rate);
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
    study.verdicts.push_back(v);
  }
  AnalyseExtension(&study);
  AnalyseStiffness(&study);
  return study;
}

std::string RateGroup::UsableText() const {
  return fmt::format("{} usable of {} states{}", used, states,
                     liquefied > 0 ? fmt::format(" ({} liquefied)", liquefied) : std::string());
}

static void AnalyseStiffness(RateStudy* study) {
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

static void AnalyseExtension(RateStudy* study) {
  // Per (E, rule, rate, p_0): the groups at ψ_ε ≥ 90° (map order: ψ_ε ascending).
  using SweepKey = std::tuple<double, int, double, double>;
  std::map<SweepKey, std::map<double, const RateGroup*>> sweeps;
  for (const RateGroup& g : study->groups) {
    if (g.key.psi_epsilon_deg < 90.0) continue;
    sweeps[{g.key.youngs_modulus_mpa, static_cast<int>(g.key.rule), g.key.rate, g.key.start_p_kpa}]
          [g.key.psi_epsilon_deg] = &g;
  }
  auto sigma_r = [](const Estimate& q_over_p) {
    Estimate e = q_over_p;
    e.mean = 1.0 - q_over_p.mean / 3.0;
    e.standard_error = q_over_p.standard_error / 3.0;
    e.half_width = q_over_p.half_width / 3.0;
    return e;
  };
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
      ExtensionStep step;
      step.youngs_modulus_mpa = limit.youngs_modulus_mpa;
      step.start_p_kpa = limit.start_p_kpa;
      step.psi_epsilon_deg = psi;
      step.rule = limit.rule;
      step.rate = limit.rate;
      step.states = g->states;
      step.used = g->used;
      step.liquefied = g->liquefied;
      step.sigma_r_over_p = sigma_r(g->q_over_p);
      step.psi_sigma_deg = g->psi_sigma_deg;
      step.p_kpa = g->p_kpa;
      step.ln_1_plus_e = g->ln_1_plus_e;
      const Estimate& r = step.sigma_r_over_p;
      if (2 * step.liquefied > step.states) {
        step.status = "liquefied";
      } else if (step.used >= 2 && r.has_interval()) {
        step.status = r.mean - r.half_width > 0 ? "asymptote" : "limit_d";
      } else {
        step.status = "undetermined";
      }
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
        // The line through this step and the last two asymptote steps,
        // x centred on the points' mean (so that a and b are uncorrelated).
        std::vector<double> through = {psi};
        for (size_t k = asymptote_steps.size(); k-- > 0 && through.size() < 3;) {
          through.push_back(asymptote_steps[k]);
        }
        std::vector<double> x, y;
        for (const RateState& s : study->states) {
          const bool in_step = std::any_of(through.begin(), through.end(), [&](double step_psi) {
            return KeyOf(s) == RateKey{limit.youngs_modulus_mpa, step_psi, limit.start_p_kpa,
                                       limit.rule, limit.rate};
          });
          if (!in_step || !study->Usable(s) || !std::isfinite(s.q_over_p)) continue;
          x.push_back(s.psi_epsilon_deg);
          y.push_back(1.0 - s.q_over_p / 3.0);
        }
        double centre = 0;
        for (double v : x) centre += v / static_cast<double>(std::max<size_t>(x.size(), 1));
        for (double& v : x) v -= centre;
        const LineFit fit = FitLine(x, y);
        if (fit.valid() && fit.slope < 0) {
          const double offset = -fit.intercept / fit.slope;
          const double se = std::sqrt(fit.intercept_error * fit.intercept_error +
                                      offset * offset * fit.slope_error * fit.slope_error) /
                            std::abs(fit.slope);
          limit.psi_d_deg = Estimate::Fitted(centre + offset, se, fit.points);
        }
      }
    }
    if (limit.result.empty()) {
      const std::string last = study->extension_steps.back().status;
      limit.result = last == "asymptote" ? "not_reached" : "undetermined";
    }
    study->extension_limits.push_back(limit);
  }
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

// ---------------------------------------------------------------- drained triaxial cases

namespace {

bool DrainedUsable(const DrainedState& s, const RateStudyOptions& options) {
  return PassesFilters(s.status, s.flags, options.statuses, options) && s.p_kpa > 0 &&
         std::isfinite(s.ln_1_plus_e) && std::isfinite(s.q_over_p);
}

// φ_c of a triaxial-compression stress ratio M: sin φ = 3M / (6 + M).
double FrictionAngleDeg(double m) { return std::asin(3 * m / (6 + m)) / kDegree; }

}  // namespace

bool RateStudy::Usable(const DrainedState& s) const { return DrainedUsable(s, options); }

DrainedStudy DrainedStudy::Analyse(std::vector<DrainedState> states,
                                   const RateStudyOptions& options) {
  DrainedStudy study;
  study.states = std::move(states);
  using GroupKey = std::tuple<double, double, double>;  // E, σ_r, ε̇_a
  std::map<GroupKey, std::vector<const DrainedState*>> members;
  for (const DrainedState& s : study.states) {
    members[{s.youngs_modulus_mpa, s.radial_stress_kpa, s.axial_strain_rate}].push_back(&s);
  }
  for (const auto& [key, list] : members) {
    DrainedGroup g;
    std::tie(g.youngs_modulus_mpa, g.radial_stress_kpa, g.axial_strain_rate) = key;
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
    study.groups.push_back(g);
  }

  // Per (E, σ_r): the groups in ascending ε̇_a (map order).
  std::map<std::pair<double, double>, std::vector<const DrainedGroup*>> by_start;
  for (const DrainedGroup& g : study.groups) {
    by_start[{g.youngs_modulus_mpa, g.radial_stress_kpa}].push_back(&g);
  }
  for (const auto& [start, groups] : by_start) {
    DrainedLimit l;
    std::tie(l.youngs_modulus_mpa, l.radial_stress_kpa) = start;
    std::vector<double> x, m, lnv, lnp;
    for (const DrainedGroup* g : groups) {
      if (g->used > 0) ++l.rates;
      for (const DrainedState& s : study.states) {
        if (s.youngs_modulus_mpa != g->youngs_modulus_mpa ||
            s.radial_stress_kpa != g->radial_stress_kpa ||
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
    if (groups.size() >= 2) {
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
    } else {
      l.verdict = "undetermined";
      l.reason = "fewer than two axial rates";
    }
    study.limits.push_back(l);
  }

  // Per E: the quasi-static critical state through the limits.
  std::map<double, std::vector<const DrainedLimit*>> by_modulus;
  for (const DrainedLimit& l : study.limits) {
    if (l.valid() && std::isfinite(l.ln_p_kpa.mean) && std::isfinite(l.ln_1_plus_e.mean)) {
      by_modulus[l.youngs_modulus_mpa].push_back(&l);
    }
  }
  const double ln_reference = std::log(options.reference_p_kpa);
  for (const auto& [modulus, limits] : by_modulus) {
    DrainedCriticalState c;
    c.youngs_modulus_mpa = modulus;
    c.starts = static_cast<int>(limits.size());
    std::vector<double> ms, x, y;
    for (const DrainedLimit* l : limits) {
      ms.push_back(l->m.mean);
      x.push_back(l->ln_p_kpa.mean - ln_reference);
      y.push_back(l->ln_1_plus_e.mean);
    }
    c.m = Estimate::Of(ms);
    if (std::isfinite(c.m.mean)) {
      // dφ/dM = 18 / ((6 + M)² cos φ).
      const double phi = FrictionAngleDeg(c.m.mean);
      const double derivative =
          18.0 / ((6 + c.m.mean) * (6 + c.m.mean) * std::cos(phi * kDegree)) / kDegree;
      c.phi_c_deg = c.m;
      c.phi_c_deg.mean = phi;
      c.phi_c_deg.standard_error = derivative * c.m.standard_error;
      c.phi_c_deg.half_width = derivative * c.m.half_width;
    }
    const LineFit fm = FitLine(x, ms);
    if (fm.valid()) c.m_per_ln_p = Estimate::Fitted(fm.slope, fm.slope_error, fm.points);
    const LineFit csl = FitLine(x, y);
    if (csl.valid()) {
      c.lambda = Estimate::Fitted(-csl.slope, csl.slope_error, csl.points);
      c.gamma = csl.intercept - csl.slope * ln_reference;
      c.position = Estimate::Fitted(csl.intercept, csl.intercept_error, csl.points);
    }
    study.critical.push_back(c);
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

std::vector<std::string> RateStudy::Answers() const {
  std::vector<std::string> answers;
  auto pm = [](const Estimate& e, int digits) {
    return e.has_interval() ? fmt::format("{:.{}f} ± {:.{}f}", e.mean, digits, e.half_width, digits)
                            : fmt::format("{:.{}f} (no interval)", e.mean, digits);
  };
  for (const DrainedCriticalState& c : drained.critical) {
    answers.push_back(fmt::format(
        "Quasi-static critical state (drained triaxial compression extrapolated to I → 0 at {} "
        "radial stresses, E = {:g} MPa): M = {}, φ_c = {}°{}.",
        c.starts, c.youngs_modulus_mpa, pm(c.m, 3), pm(c.phi_c_deg, 1),
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
    text += fmt::format("  drained critical state as I -> 0, E {:g} MPa: {}\n",
                        c.youngs_modulus_mpa, c.Text(options.reference_p_kpa));
  }
  return text;
}

void WriteRateFiles(const std::string& directory, const RateStudy& study) {
  const RateStudyOptions& o = study.options;
  auto join = [](const auto& list) {
    std::string text;
    for (const auto& item : list) {
      if constexpr (std::is_same_v<std::decay_t<decltype(item)>, std::string>) {
        text += (text.empty() ? "" : "/") + item;
      } else {
        text += std::string(text.empty() ? "" : "/") + ToString(item);
      }
    }
    return text;
  };
  const std::string usable =
      fmt::format("usable states: status {} ({} at psi_epsilon = 0), none flagged {}",
                  join(o.statuses), join(o.ncl_statuses), join(o.excluded_flags));

  CsvWriter states(
      {"the asymptotic states of the rate cases (figures key 'rate'), one row per "
       "case and detector stage; start_p_kpa: the p target of the state the case "
       "started from; stiffness_number: kappa of the contact law at p; ocr: against the "
       "study's NCL, ocr_same_rate: against the NCL of the same E and rate (its psi_epsilon "
       "= 0 line in rate_lines.csv; empty where p_e* falls outside the line's p range); "
       "path_N, path_lambda: a psi_epsilon = 0 path's own NCL past its first unit of ln p, "
       "over [path_p_min_kpa, path_p_max_kpa]"});
  states.WriteRows(study.states, StateFields, directory + "/" + kRateStatesFile);

  CsvWriter summary(
      {"per (E, psi_epsilon, start p, rate): the mean over the replicates' usable "
       "states and the half-width of its 95 % interval (Student t, n - 1 degrees "
       "of freedom; empty below two states)",
       usable});
  auto group_fields = [](const RateGroup& g) {
    Columns fields = KeyFields(g.key);
    fields.emplace_back("states", std::to_string(g.states));
    fields.emplace_back("used", std::to_string(g.used));
    fields.emplace_back("liquefied", std::to_string(g.liquefied));
    AddEstimate(&fields, "p_kpa", g.p_kpa);
    AddEstimate(&fields, "e", g.e);
    AddEstimate(&fields, "ln_1_plus_e", g.ln_1_plus_e);
    AddEstimate(&fields, "psi_sigma_deg", g.psi_sigma_deg);
    AddEstimate(&fields, "q_over_p", g.q_over_p);
    AddEstimate(&fields, "ocr", g.ocr);
    AddEstimate(&fields, "ocr_same_rate", g.ocr_same_rate);
    AddEstimate(&fields, "inertial_number_dmin", g.inertial_number_dmin);
    AddEstimate(&fields, "inertial_number_dmax", g.inertial_number_dmax);
    AddEstimate(&fields, "stiffness_number", g.stiffness_number);
    return fields;
  };
  summary.WriteRows(study.groups, group_fields, directory + "/" + kRateSummaryFile);

  CsvWriter lines({fmt::format("per (E, psi_epsilon, rate): ln(1+e) = N - lambda ln(p / 1 kPa) "
                               "by least squares through the usable states of every start and "
                               "replicate (at least two starts); position: ln(1+e) on the line "
                               "at p = {:g} kPa with the 95 % interval of the prediction "
                               "(Student t, points - 2 degrees of freedom)",
                               o.reference_p_kpa),
                   "psi_epsilon = 0 (whose states all lie at the stress cap): N and lambda the "
                   "means of the paths' own lines (rate_states.csv path_N, path_lambda: each path "
                   "past its first unit of ln p), points the paths, position the mean of their "
                   "ln(1+e) at the reference p over the paths that reach it (Student t, n - 1 "
                   "degrees of freedom)",
                   usable});
  auto line_fields = [&o](const RateLine& l) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(l.youngs_modulus_mpa)},
                      {"psi_epsilon_deg", CsvNumber(l.psi_epsilon_deg)},
                      {"rate_rule", ToString(l.rule)},
                      {"rate", CsvNumber(l.rate)},
                      {"points", std::to_string(l.points)},
                      {"N", CsvNumber(l.n)},
                      {"lambda", CsvNumber(l.lambda)},
                      {"reference_p_kpa", CsvNumber(o.reference_p_kpa)}};
    AddEstimate(&fields, "position", l.position);
    fields.emplace_back("p_min_kpa", CsvNumber(l.p_min_kpa));
    fields.emplace_back("p_max_kpa", CsvNumber(l.p_max_kpa));
    return fields;
  };
  lines.WriteRows(study.lines, line_fields, directory + "/" + kRateLinesFile);

  CsvWriter quasi({fmt::format("the quasi-static limit per (E, psi_epsilon, start p): y = a + b "
                               "I(d_max) by least squares through the usable states of the {} "
                               "smallest I* (I(d_max) as measured over each asymptote's window; "
                               "the small-I form of the mu(I) laws of da Cruz et al. 2005 and "
                               "Jop et al. 2006); a, b with "
                               "95 % intervals (Student t, points - 2 degrees of freedom)",
                               o.fit_rates),
                   usable});
  auto quasi_fields = [](const QuasiStaticFit& f) {
    std::string rates;
    for (double r : f.rates) rates += (rates.empty() ? "" : ";") + CsvNumber(r);
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(f.youngs_modulus_mpa)},
                      {"psi_epsilon_deg", CsvNumber(f.psi_epsilon_deg)},
                      {"start_p_kpa", CsvNumber(f.start_p_kpa)},
                      {"quantity", f.quantity},
                      {"rates", rates},
                      {"points", std::to_string(f.points)},
                      {"i_min", CsvNumber(f.i_min)},
                      {"i_max", CsvNumber(f.i_max)}};
    AddEstimate(&fields, "limit", f.limit);
    AddEstimate(&fields, "slope", f.slope);
    return fields;
  };
  quasi.WriteRows(study.quasi_static, quasi_fields, directory + "/" + kRateQuasiStaticFile);

  CsvWriter verdicts(
      {fmt::format("rate independence (SPEC 8.2) per (E, psi_epsilon, start p): the two "
                   "smallest I* agree when the difference of their means is inside its 95 % "
                   "interval (Welch: t with Welch-Satterthwaite degrees of freedom, rounded "
                   "down) in ln(1+e), psi_sigma and the CSL's ln(1+e) at {:g} kPa",
                   o.reference_p_kpa),
       usable});
  auto verdict_fields = [](const RateVerdict& v) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(v.youngs_modulus_mpa)},
                      {"psi_epsilon_deg", CsvNumber(v.psi_epsilon_deg)},
                      {"start_p_kpa", CsvNumber(v.start_p_kpa)},
                      {"i_smallest", CsvNumber(v.smallest)},
                      {"i_next", CsvNumber(v.next)}};
    auto add = [&fields](const std::string& name, const Estimate& a, const Estimate& b,
                         const Comparison& c) {
      AddComparison(&fields, name, "_smallest", "_next", a, b, c);
    };
    add("ln_1_plus_e", v.ln_v_smallest, v.ln_v_next, v.ln_1_plus_e);
    add("psi_sigma_deg", v.psi_smallest, v.psi_next, v.psi_sigma);
    add("csl_position", v.csl_smallest, v.csl_next, v.csl_position);
    fields.emplace_back("verdict", v.verdict);
    fields.emplace_back("reason", CsvText(v.reason));
    return fields;
  };
  verdicts.WriteRows(study.verdicts, verdict_fields, directory + "/" + kRateIndependenceFile);

  CsvWriter stiffness(
      {fmt::format("stiffness scaling (issue 10): per (E, psi_epsilon, start p, rate) with groups "
                   "at the main modulus (reference) and at E, E against the reference in psi_sigma "
                   "and in the position of the CSL of that rate (ln(1+e) at {:g} kPa); they agree "
                   "when the difference is inside its 95 % interval (Welch); kappa: the stiffness "
                   "numbers at the asymptotes",
                   o.reference_p_kpa),
       usable});
  auto stiffness_fields = [](const StiffnessComparison& c) {
    Columns fields = {{"youngs_modulus_mpa", CsvNumber(c.youngs_modulus_mpa)},
                      {"reference_modulus_mpa", CsvNumber(c.reference_modulus_mpa)},
                      {"psi_epsilon_deg", CsvNumber(c.psi_epsilon_deg)},
                      {"start_p_kpa", CsvNumber(c.start_p_kpa)},
                      {"rate_rule", ToString(c.rule)},
                      {"rate", CsvNumber(c.rate)}};
    AddEstimate(&fields, "kappa_reference", c.kappa_reference);
    AddEstimate(&fields, "kappa", c.kappa_other);
    AddComparison(&fields, "psi_sigma_deg", "_reference", "", c.psi_reference, c.psi_other,
                  c.psi_sigma);
    AddComparison(&fields, "csl_position", "_reference", "", c.csl_reference, c.csl_other,
                  c.csl_position);
    fields.emplace_back("verdict", c.verdict);
    fields.emplace_back("reason", CsvText(c.reason));
    return fields;
  };
  stiffness.WriteRows(study.stiffness, stiffness_fields, directory + "/" + kRateStiffnessFile);

  auto sweep_fields = [](double e_mpa, dem::RateRule rule, double rate, double p0) {
    return Columns{
        {"youngs_modulus_mpa", CsvNumber(e_mpa)},
        {"rate_rule", ToString(rule)},
        {"inertial_number_target", CsvNumber(rule == dem::RateRule::kInertial ? rate : kNaN)},
        {"stretching_rate_per_s", CsvNumber(rule == dem::RateRule::kConstant ? rate : kNaN)},
        {"start_p_kpa", CsvNumber(p0)}};
  };
  CsvWriter steps(
      {"the extension sweep (issue 10 section 3): per (E, rate, start p) and psi_epsilon >= 90 "
       "deg, the asymptotic sigma_r/p = 1 - (q/p)/3 (zero at the limit d, psi_sigma = 54.74 deg) "
       "over the usable states, with 95 % intervals; liquefied: replicates with status or flag "
       "gas",
       usable,
       "status: asymptote (sigma_r/p > 0 outside its interval), limit_d (zero within it), "
       "liquefied (most replicates), undetermined (fewer than two usable states)"});
  auto step_fields = [&](const ExtensionStep& x) {
    Columns fields = sweep_fields(x.youngs_modulus_mpa, x.rule, x.rate, x.start_p_kpa);
    fields.emplace_back("psi_epsilon_deg", CsvNumber(x.psi_epsilon_deg));
    fields.emplace_back("states", std::to_string(x.states));
    fields.emplace_back("used", std::to_string(x.used));
    fields.emplace_back("liquefied", std::to_string(x.liquefied));
    AddEstimate(&fields, "sigma_r_over_p", x.sigma_r_over_p);
    AddEstimate(&fields, "psi_sigma_deg", x.psi_sigma_deg);
    AddEstimate(&fields, "p_kpa", x.p_kpa);
    AddEstimate(&fields, "ln_1_plus_e", x.ln_1_plus_e);
    fields.emplace_back("status", x.status);
    return fields;
  };
  steps.WriteRows(study.extension_steps, step_fields, directory + "/" + kRateExtensionFile);

  CsvWriter limits(
      {"the end of each extension sweep: limit_d (psi_epsilon(d), where sigma_r/p is zero within "
       "its interval; psi_d from the least-squares line of sigma_r/p against psi_epsilon through "
       "the limit step and the two asymptote steps before it, 95 % delta-method interval), "
       "liquefied (the first psi_epsilon at which most replicates liquefied), not_reached or "
       "undetermined"});
  auto limit_fields = [&](const ExtensionLimit& l) {
    Columns fields = sweep_fields(l.youngs_modulus_mpa, l.rule, l.rate, l.start_p_kpa);
    fields.emplace_back("steps", std::to_string(l.steps));
    fields.emplace_back("psi_max_deg", CsvNumber(l.psi_max_deg));
    fields.emplace_back("result", l.result);
    fields.emplace_back("last_asymptote_deg", CsvNumber(l.last_asymptote_deg));
    fields.emplace_back("liquefied_at_deg", CsvNumber(l.liquefied_at_deg));
    fields.emplace_back("limit_step_deg", CsvNumber(l.limit_step_deg));
    AddEstimate(&fields, "psi_d_deg", l.psi_d_deg);
    fields.emplace_back("text", CsvText(l.result.empty() ? std::string() : l.Text()));
    return fields;
  };
  limits.WriteRows(study.extension_limits, limit_fields, directory + "/" + kRateExtensionLimitFile);
  WriteDrainedFiles(directory, study.drained, o, usable);
}

QuasiStaticSelection SelectQuasiStatic(const RateStudy& study,
                                       std::optional<double> inertial_number) {
  QuasiStaticSelection selection;
  selection.youngs_modulus_mpa = study.ReferenceModulus();
  const double e_mpa = selection.youngs_modulus_mpa;
  // I* → the starts with usable ψ_ε = 90° states at the reference modulus.
  std::map<double, std::set<double>> csl_starts;
  std::set<double> rates;
  for (const RateState& s : study.states) {
    if (s.rule != dem::RateRule::kInertial || s.youngs_modulus_mpa != e_mpa) continue;
    rates.insert(s.inertial_number);
    if (std::abs(s.psi_epsilon_deg - 90) < 1e-6 && study.Usable(s)) {
      csl_starts[s.inertial_number].insert(s.start_p_kpa);
    }
  }
  if (inertial_number) {
    if (!rates.count(*inertial_number)) {
      std::string known;
      for (double r : rates) known += (known.empty() ? "" : ", ") + fmt::format("{:g}", r);
      selection.reason =
          fmt::format("no rate case runs at I* = {:g} (E = {:g} MPa): the study has {}",
                      *inertial_number, e_mpa, known.empty() ? "none" : known);
      return selection;
    }
    selection.inertial_number = *inertial_number;
  } else {
    for (const auto& [rate, starts] : csl_starts) {  // ascending I*
      if (starts.size() >= 2) {
        selection.inertial_number = rate;
        break;
      }
    }
    if (std::isnan(selection.inertial_number)) {
      selection.reason = fmt::format(
          "no I* has usable psi_epsilon = 90 deg states from two starts at E = {:g} MPa", e_mpa);
      return selection;
    }
  }
  std::set<std::string> seen;
  for (const RateState& s : study.states) {
    if (s.rule == dem::RateRule::kInertial && s.youngs_modulus_mpa == e_mpa &&
        s.inertial_number == selection.inertial_number && seen.insert(s.case_name).second) {
      selection.cases.push_back(s.case_name);
    }
  }
  // The drained cases at the slowest axial rate of each σ_r with usable states.
  std::map<double, double> slowest;  // σ_r → ε̇_a
  for (const DrainedState& s : study.drained.states) {
    if (s.youngs_modulus_mpa != e_mpa || !DrainedUsable(s, study.options)) continue;
    auto [it, added] = slowest.emplace(s.radial_stress_kpa, s.axial_strain_rate);
    if (!added) it->second = std::min(it->second, s.axial_strain_rate);
  }
  for (const DrainedState& s : study.drained.states) {
    const auto it = slowest.find(s.radial_stress_kpa);
    if (s.youngs_modulus_mpa == e_mpa && it != slowest.end() && s.axial_strain_rate == it->second &&
        seen.insert(s.case_name).second) {
      selection.drained_cases.push_back(s.case_name);
    }
  }
  return selection;
}

void WriteQuasiStaticSelection(const std::string& directory, const QuasiStaticSelection& s) {
  std::string text = fmt::format(
      "# the rate study's quasi-static states that the calibrations in this folder were fitted "
      "to (written by granasym study calibrate; analysis/rate_study.h)\n"
      "inertial_number = {}\nyoungs_modulus_mpa = {}\ncases = [",
      CsvNumber(s.inertial_number), CsvNumber(s.youngs_modulus_mpa));
  for (size_t k = 0; k < s.cases.size(); ++k) text += (k ? ", " : "") + TomlQuoted(s.cases[k]);
  text +=
      "]\n# the drained triaxial cases at the slowest axial rate of each sigma_r\ndrained_cases = "
      "[";
  for (size_t k = 0; k < s.drained_cases.size(); ++k) {
    text += (k ? ", " : "") + TomlQuoted(s.drained_cases[k]);
  }
  fs::create_directories(fs::path(directory) / "calibration");
  WriteTextFileAtomically((fs::path(directory) / kQuasiStaticSelectionFile).string(), text + "]\n");
}

std::optional<QuasiStaticSelection> ReadQuasiStaticSelection(const std::string& directory) {
  const fs::path path = fs::path(directory) / kQuasiStaticSelectionFile;
  if (!fs::exists(path)) return std::nullopt;
  const ConfigTable table = ConfigTable::ParseFile(path.string());
  QuasiStaticSelection s;
  s.inertial_number = table.GetDouble("inertial_number", Range::Open(0, 10));
  s.youngs_modulus_mpa = table.GetDouble("youngs_modulus_mpa", Range::Open(0, 1e7));
  s.cases = table.GetStrings("cases");
  if (s.cases.empty()) table.Fail("cases", "is empty: expected the calibrated case names");
  if (table.Has("drained_cases")) s.drained_cases = table.GetStrings("drained_cases");
  return s;
}

std::optional<RateStudy> ReadRateStudy(const std::string& directory) {
  std::vector<RateState> states = ReadRateStates(directory);
  std::vector<DrainedState> drained = ReadDrainedStates(directory);
  if (states.empty() && drained.empty()) return std::nullopt;
  RateStudy study = RateStudy::Analyse(std::move(states));
  study.drained = DrainedStudy::Analyse(std::move(drained), study.options);
  return study;
}

bool ServesRateStudy(const std::string& figures) {
  return FigureSet::Parse(figures, "the state table", "figures").ServesRateStudy();
}

namespace {

// What a rate state (proportional or drained) takes from its row of the
// state table: the case, the detector's verdict and the asymptotic state.
template <typename State>
State FromRow(const StateRow& row) {
  State s;
  s.replicate = row.replicate;
  s.case_name = row.case_name;
  s.stage = row.stage;
  s.status = row.status;
  s.flags = row.flags;
  s.p_kpa = row.p_kpa;
  s.e = row.e;
  s.ln_1_plus_e = row.ln_1_plus_e;
  s.psi_sigma_deg = row.psi_sigma_deg;
  s.q_over_p = row.q_over_p;
  s.inertial_number_dmin = row.inertial_number_dmin;
  s.inertial_number_dmax = row.inertial_number_dmax;
  return s;
}

// A ψ_ε = 0° path's own NCL (RateState::path_n): its rows [first, last]
// once p exceeds e times the first row's.
void FitPathLine(const TimeSeries& series, int64_t first, int64_t last, RateState* s) {
  const std::vector<double>& p = series.Values(dem::record::kColumnMeanStress);
  const std::vector<double>& ln_v = series.Values(dem::record::kColumnLnVolume);
  first = std::max<int64_t>(first, 0);
  last = std::min<int64_t>(last, static_cast<int64_t>(p.size()) - 1);
  if (last <= first || !(p[first] > 0)) return;
  const double from = std::exp(1.0) * p[first];
  std::vector<double> x, y;
  for (int64_t k = first; k <= last; ++k) {
    if (p[k] >= from && std::isfinite(ln_v[k])) {
      x.push_back(std::log(p[k]));
      y.push_back(ln_v[k]);
    }
  }
  if (x.size() < 3) return;
  const LineFit fit = FitLine(x, y);
  if (!fit.valid()) return;
  s->path_n = fit.intercept;
  s->path_lambda = -fit.slope;
  s->path_p_min_kpa = std::exp(*std::min_element(x.begin(), x.end()));
  s->path_p_max_kpa = std::exp(*std::max_element(x.begin(), x.end()));
}

}  // namespace

std::optional<RateStudy> WriteRateStudy(const std::string& directory,
                                        const std::vector<StateRow>& rows,
                                        const RateStudyOptions& options) {
  std::vector<RateState> states;
  std::vector<DrainedState> drained;
  bool any = false;
  for (const StateRow& row : rows) {
    if (!ServesRateStudy(row.figures)) continue;
    any = true;
    if (row.status == TableStatus::kNoResult || row.stage.empty()) continue;
    const fs::path folder = fs::path(directory) / "cases" / row.case_id;
    const CaseRecord record = CaseRecord::Read(folder.string());
    const std::string& parent = record.parent;
    const std::string& parent_stage = record.parent_stage;
    const Hdf5File file = Hdf5File::OpenRead((folder / "result.h5").string());
    const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
    size_t index = stages.size();
    for (size_t k = 0; k < stages.size(); ++k) {
      if (stages[k].name == row.stage) index = k;
    }
    if (index == stages.size()) continue;
    const std::string group = dem::StageGroup(index);
    const auto canonical = CanonicalLines(dem::ReadProvenance(file).scene_canonical);
    const double modulus = CanonicalNumber(canonical, "material.youngs_modulus_mpa").value_or(kNaN);
    if (file.HasAttribute(group, dem::record::kStageAxialStrainRate)) {
      DrainedState d = FromRow<DrainedState>(row);  // a drained triaxial stage
      d.youngs_modulus_mpa = modulus;
      d.radial_stress_kpa = file.ReadDoubleAttribute(group, dem::record::kStageRadialStressKpa);
      d.axial_strain_rate = file.ReadDoubleAttribute(group, dem::record::kStageAxialStrainRate);
      drained.push_back(d);
      continue;
    }
    if (!file.HasAttribute(group, dem::record::kStageStretchingRate))
      continue;  // neither a strain path nor a drained triaxial stage
    RateState s = FromRow<RateState>(row);
    s.kind = row.kind;
    s.psi_epsilon_deg = file.ReadDoubleAttribute(group, dem::record::kStagePsiEpsilonDeg);
    s.stretching_rate = file.ReadDoubleAttribute(group, dem::record::kStageStretchingRate);
    const std::string rule = file.HasAttribute(group, dem::record::kStageRateRule)
                                 ? file.ReadStringAttribute(group, dem::record::kStageRateRule)
                                 : "constant";
    const std::optional<dem::RateRule> parsed = FromString<dem::RateRule>(rule);
    if (!parsed) {
      throw InputError((folder / "result.h5").string() + ": " + group + " has rate rule '" + rule +
                       "': expected " + AllowedNames<dem::RateRule>());
    }
    s.rule = *parsed;
    if (s.rule == dem::RateRule::kInertial) {
      s.inertial_number = file.ReadDoubleAttribute(group, dem::record::kStageRateInertialNumber);
    }
    s.youngs_modulus_mpa = modulus;
    s.start_p_kpa =
        parent.empty()
            ? kNaN
            : StartStress((fs::path(directory) / "cases" / parent / "result.h5").string(),
                          parent_stage);
    s.ocr = row.ocr;
    // κ as the DEM's rows define it (dem/material.h), at the state's p.
    s.stiffness_number = row.p_kpa > 0 ? dem::ReadMaterial(file).StiffnessNumber(row.p_kpa * 1e3)
                                       : kNaN;  // none at p = 0
    if (s.kind == TableKind::kNcl) {
      FitPathLine(TimeSeries::Read(file, dem::record::kSeries), stages[index].first_row,
                  stages[index].last_row, &s);
    }
    states.push_back(s);
  }
  const std::vector<const char*> files = {
      kRateStatesFile,        kRateSummaryFile,   kRateLinesFile,        kRateQuasiStaticFile,
      kRateIndependenceFile,  kRateStiffnessFile, kRateExtensionFile,    kRateExtensionLimitFile,
      kRateDrainedStatesFile, kRateDrainedFile,   kRateDrainedLimitFile, kRateDrainedCriticalFile};
  if (!any) {
    for (const char* name : files) fs::remove(fs::path(directory) / name);
    return std::nullopt;
  }
  RateStudy study = RateStudy::Analyse(std::move(states), options);
  study.drained = DrainedStudy::Analyse(std::move(drained), options);
  WriteRateFiles(directory, study);
  return study;
}

namespace {

// A number column of a rate file's row (empty: NaN), or an InputError naming
// the file, the line, the column and the text.
// A kind or status cell of a rate file (InputError naming the file, line and value).
template <typename E>
E CsvName(const CsvTextTable& table, const std::string& path, const std::vector<std::string>& row,
          size_t r, const char* column) {
  const std::string& text = row[table.Column(column)];
  const std::optional<E> value = FromString<E>(text);
  if (!value) {
    throw InputError(fmt::format("{}: line {}: {} '{}': expected {}", path, table.line_numbers[r],
                                 column, text, AllowedNames<E>()));
  }
  return *value;
}

double CsvCell(const CsvTextTable& table, const std::string& path,
               const std::vector<std::string>& row, size_t r, const char* column) {
  const std::string& text = row[table.Column(column)];
  if (text.empty()) return kNaN;
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("{}: line {}: column {}: '{}' is not a number", path,
                               table.line_numbers[r], column, text));
}

}  // namespace

std::vector<DrainedState> ReadDrainedStates(const std::string& directory) {
  const std::string path = directory + "/" + kRateDrainedStatesFile;
  std::vector<DrainedState> states;
  if (!fs::exists(path)) return states;
  const CsvTextTable table = CsvTextTable::ReadFile(path);
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    auto number = [&](const char* column) { return CsvCell(table, path, row, r, column); };
    DrainedState s;
    s.replicate = static_cast<int>(number("replicate"));
    s.case_name = row[table.Column("case_name")];
    s.stage = row[table.Column("stage")];
    s.status = CsvName<TableStatus>(table, path, row, r, "status");
    s.flags = row[table.Column("flags")];
    s.youngs_modulus_mpa = number("youngs_modulus_mpa");
    s.radial_stress_kpa = number("radial_stress_kpa");
    s.axial_strain_rate = number("axial_strain_rate_per_s");
    s.p_kpa = number("p_kpa");
    s.e = number("e");
    s.ln_1_plus_e = number("ln_1_plus_e");
    s.psi_sigma_deg = number("psi_sigma_deg");
    s.q_over_p = number("q_over_p");
    s.inertial_number_dmin = number("inertial_number_dmin");
    s.inertial_number_dmax = number("inertial_number_dmax");
    states.push_back(s);
  }
  return states;
}

std::vector<RateState> ReadRateStates(const std::string& directory) {
  const std::string path = directory + "/" + kRateStatesFile;
  std::vector<RateState> states;
  if (!fs::exists(path)) return states;
  const CsvTextTable table = CsvTextTable::ReadFile(path);
  auto number = [&table, &path](const std::vector<std::string>& row, size_t r, const char* column) {
    return CsvCell(table, path, row, r, column);
  };
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    RateState s;
    s.replicate = static_cast<int>(number(row, r, "replicate"));
    s.case_name = row[table.Column("case_name")];
    s.stage = row[table.Column("stage")];
    s.kind = CsvName<TableKind>(table, path, row, r, "kind");
    s.status = CsvName<TableStatus>(table, path, row, r, "status");
    s.flags = row[table.Column("flags")];
    const std::string rule = row[table.Column("rate_rule")];
    const std::optional<dem::RateRule> parsed = FromString<dem::RateRule>(rule);
    if (!parsed) {
      throw InputError(fmt::format("{}: line {}: rate_rule '{}': expected {}", path,
                                   table.line_numbers[r], rule, AllowedNames<dem::RateRule>()));
    }
    s.rule = *parsed;
    s.youngs_modulus_mpa = number(row, r, "youngs_modulus_mpa");
    s.psi_epsilon_deg = number(row, r, "psi_epsilon_deg");
    s.start_p_kpa = number(row, r, "start_p_kpa");
    s.inertial_number = number(row, r, "inertial_number_target");
    s.stretching_rate = number(row, r, "stretching_rate_per_s");
    s.p_kpa = number(row, r, "p_kpa");
    s.e = number(row, r, "e");
    s.ln_1_plus_e = number(row, r, "ln_1_plus_e");
    s.psi_sigma_deg = number(row, r, "psi_sigma_deg");
    s.q_over_p = number(row, r, "q_over_p");
    s.ocr = number(row, r, "ocr");
    s.inertial_number_dmin = number(row, r, "inertial_number_dmin");
    s.inertial_number_dmax = number(row, r, "inertial_number_dmax");
    s.stiffness_number = number(row, r, "stiffness_number");
    if (table.Find("path_N") >= 0) {  // absent in the files of older versions
      s.path_n = number(row, r, "path_N");
      s.path_lambda = number(row, r, "path_lambda");
      s.path_p_min_kpa = number(row, r, "path_p_min_kpa");
      s.path_p_max_kpa = number(row, r, "path_p_max_kpa");
    }
    states.push_back(s);
  }
  return states;
}

}  // namespace granasym::analysis
