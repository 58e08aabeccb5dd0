#include "analysis/rate_files.h"

#include <fmt/format.h>

#include <filesystem>
#include <type_traits>
#include <variant>

#include "common/csv_table.h"
#include "common/error.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- columns

// The options' reference mean stress (kPa), a column of the files of lines.
struct ReferencePressure {};

// What a column holds: a member of the row (a number, a text, a kind, a
// status or a rate rule, read back by name; an estimate or a comparison,
// written as several columns), a field computed from the row, or the
// reference pressure of the options.
template <typename Row>
using Field = std::variant<int Row::*, double Row::*, std::string Row::*, TableKind Row::*,
                           TableStatus Row::*, dem::RateRule Row::*, Estimate Row::*,
                           Comparison Row::*, std::string (*)(const Row&), ReferencePressure>;

// One column of a rate file: one entry drives the header, the row's fields
// and, for the states' files, the reader.
template <typename Row>
struct Column {
  const char* name;
  Field<Row> field;
  // Absent in the files of older versions: the reader leaves the row's
  // default (the analysis derives it again where it needs it).
  bool optional = false;
};
template <typename Row>
using Columns = std::vector<Column<Row>>;

// The header names of a column: X_mean, X_ci95 for an estimate;
// X_difference, X_difference_ci95, X_agreement for a comparison.
template <typename Row>
void AddNames(const Column<Row>& column, std::vector<std::string>* names) {
  const std::string name = column.name;
  if (std::holds_alternative<Estimate Row::*>(column.field)) {
    names->insert(names->end(), {name + "_mean", name + "_ci95"});
  } else if (std::holds_alternative<Comparison Row::*>(column.field)) {
    names->insert(names->end(),
                  {name + "_difference", name + "_difference_ci95", name + "_agreement"});
  } else {
    names->push_back(name);
  }
}

template <typename Row>
void AddFields(const Row& row, const Column<Row>& column, const RateStudyOptions& options,
               std::vector<std::string>* fields) {
  std::visit(
      [&](auto field) {
        using F = decltype(field);
        if constexpr (std::is_same_v<F, ReferencePressure>) {
          fields->push_back(CsvNumber(options.reference_p_kpa));
        } else if constexpr (std::is_same_v<F, std::string (*)(const Row&)>) {
          fields->push_back(field(row));
        } else {
          using T = std::decay_t<decltype(row.*field)>;
          const T& value = row.*field;
          if constexpr (std::is_same_v<T, int>) {
            fields->push_back(std::to_string(value));
          } else if constexpr (std::is_same_v<T, double>) {
            fields->push_back(CsvNumber(value));
          } else if constexpr (std::is_same_v<T, std::string>) {
            fields->push_back(CsvText(value));
          } else if constexpr (std::is_same_v<T, Estimate>) {
            fields->insert(fields->end(), {CsvNumber(value.mean), CsvNumber(value.half_width)});
          } else if constexpr (std::is_same_v<T, Comparison>) {
            fields->insert(fields->end(), {CsvNumber(value.difference), CsvNumber(value.half_width),
                                           ToString(value.agreement)});
          } else {
            fields->push_back(ToString(value));
          }
        }
      },
      column.field);
}

std::string CsvLine(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t k = 0; k < fields.size(); ++k) line += (k ? "," : "") + fields[k];
  return line + "\n";
}

// Writes `rows` under `comments` (each a '#' line) and the columns' header.
template <typename Row>
void WriteTable(const std::string& path, const std::vector<std::string>& comments,
                const Columns<Row>& columns, const std::vector<Row>& rows,
                const RateStudyOptions& options) {
  std::string text;
  for (const std::string& comment : comments) text += "# " + comment + "\n";
  std::vector<std::string> header;
  for (const Column<Row>& column : columns) AddNames(column, &header);
  text += CsvLine(header);
  for (const Row& row : rows) {
    std::vector<std::string> fields;
    for (const Column<Row>& column : columns) AddFields(row, column, options, &fields);
    text += CsvLine(fields);
  }
  WriteTextFileAtomically(path, text);
}

// A number cell (empty: NaN), or an InputError naming the file, the line,
// the column and the text.
double Number(const CsvTextTable& table, const std::string& path, size_t r, const char* column) {
  const std::string& text = table.rows[r][table.Column(column)];
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

// One cell of a states file into its member; an InputError names the file,
// the line, the column and the text of a malformed number or name.
template <typename Row>
void ReadField(const CsvTextTable& table, const std::string& path, size_t r,
               const Column<Row>& column, Row* row) {
  const std::string& text = table.rows[r][table.Column(column.name)];
  std::visit(
      [&](auto field) {
        using F = decltype(field);
        if constexpr (std::is_same_v<F, ReferencePressure> ||
                      std::is_same_v<F, std::string (*)(const Row&)>) {
          GRANASYM_CHECK(false) << column.name << " is written, not read";
        } else {
          using T = std::decay_t<decltype(row->*field)>;
          if constexpr (std::is_same_v<T, std::string>) {
            row->*field = text;
          } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, double>) {
            row->*field = static_cast<T>(Number(table, path, r, column.name));
          } else if constexpr (std::is_same_v<T, Estimate> || std::is_same_v<T, Comparison>) {
            GRANASYM_CHECK(false) << column.name << " is written, not read";
          } else {
            const std::optional<T> value = FromString<T>(text);
            if (!value) {
              throw InputError(fmt::format("{}: line {}: {} '{}': expected {}", path,
                                           table.line_numbers[r], column.name, text,
                                           AllowedNames<T>()));
            }
            row->*field = *value;
          }
        }
      },
      column.field);
}

// The rows of DIR/`name`, empty without the file.
template <typename Row>
std::vector<Row> ReadTable(const std::string& directory, const char* name,
                           const Columns<Row>& columns) {
  const std::string path = directory + "/" + name;
  std::vector<Row> rows;
  if (!fs::exists(path)) return rows;
  const CsvTextTable table = CsvTextTable::ReadFile(path);
  for (size_t r = 0; r < table.rows.size(); ++r) {
    Row row;
    for (const Column<Row>& column : columns) {
      if (column.optional && table.Find(column.name) < 0) continue;
      ReadField(table, path, r, column, &row);
    }
    rows.push_back(row);
  }
  return rows;
}

// The rate of a row under its rule, in the column of that rule (NaN in the other).
template <typename Row>
std::string InertialTarget(const Row& row) {
  return CsvNumber(row.rule == dem::RateRule::kInertial ? row.rate : kNaN);
}
template <typename Row>
std::string ConstantRate(const Row& row) {
  return CsvNumber(row.rule == dem::RateRule::kConstant ? row.rate : kNaN);
}

// ---------------------------------------------------------------- the files' columns

const Columns<RateState> kStateColumns = {
    {"replicate", &RateState::replicate},
    {"case_name", &RateState::case_name},
    {"stage", &RateState::stage},
    {"kind", &RateState::kind},
    {"status", &RateState::status},
    {"youngs_modulus_mpa", &RateState::youngs_modulus_mpa},
    {"psi_epsilon_deg", &RateState::psi_epsilon_deg},
    {"start_p_kpa", &RateState::start_p_kpa},
    {"rate_rule", &RateState::rule},
    {"inertial_number_target", &RateState::inertial_number},
    {"stretching_rate_per_s", &RateState::stretching_rate},
    {"p_kpa", &RateState::p_kpa},
    {"e", &RateState::e},
    {"ln_1_plus_e", &RateState::ln_1_plus_e},
    {"psi_sigma_deg", &RateState::psi_sigma_deg},
    {"q_over_p", &RateState::q_over_p},
    {"ocr", &RateState::ocr},
    {"ocr_same_rate", &RateState::ocr_same_rate, true},
    {"inertial_number_dmin", &RateState::inertial_number_dmin},
    {"inertial_number_dmax", &RateState::inertial_number_dmax},
    {"stiffness_number", &RateState::stiffness_number},
    {"path_N", &RateState::path_n, true},
    {"path_lambda", &RateState::path_lambda, true},
    {"path_p_min_kpa", &RateState::path_p_min_kpa, true},
    {"path_p_max_kpa", &RateState::path_p_max_kpa, true},
    {"flags", &RateState::flags},
};

const Columns<RateGroup> kSummaryColumns = {
    {"youngs_modulus_mpa", [](const RateGroup& g) { return CsvNumber(g.key.youngs_modulus_mpa); }},
    {"psi_epsilon_deg", [](const RateGroup& g) { return CsvNumber(g.key.psi_epsilon_deg); }},
    {"start_p_kpa", [](const RateGroup& g) { return CsvNumber(g.key.start_p_kpa); }},
    {"rate_rule", [](const RateGroup& g) { return std::string(ToString(g.key.rule)); }},
    {"inertial_number_target", [](const RateGroup& g) { return InertialTarget(g.key); }},
    {"stretching_rate_per_s", [](const RateGroup& g) { return ConstantRate(g.key); }},
    {"states", &RateGroup::states},
    {"used", &RateGroup::used},
    {"liquefied", &RateGroup::liquefied},
    {"p_kpa", &RateGroup::p_kpa},
    {"e", &RateGroup::e},
    {"ln_1_plus_e", &RateGroup::ln_1_plus_e},
    {"psi_sigma_deg", &RateGroup::psi_sigma_deg},
    {"q_over_p", &RateGroup::q_over_p},
    {"ocr", &RateGroup::ocr},
    {"ocr_same_rate", &RateGroup::ocr_same_rate},
    {"inertial_number_dmin", &RateGroup::inertial_number_dmin},
    {"inertial_number_dmax", &RateGroup::inertial_number_dmax},
    {"stiffness_number", &RateGroup::stiffness_number},
};

const Columns<RateLine> kLineColumns = {
    {"youngs_modulus_mpa", &RateLine::youngs_modulus_mpa},
    {"psi_epsilon_deg", &RateLine::psi_epsilon_deg},
    {"rate_rule", &RateLine::rule},
    {"rate", &RateLine::rate},
    {"points", &RateLine::points},
    {"N", &RateLine::n},
    {"lambda", &RateLine::lambda},
    {"reference_p_kpa", ReferencePressure{}},
    {"position", &RateLine::position},
    {"p_min_kpa", &RateLine::p_min_kpa},
    {"p_max_kpa", &RateLine::p_max_kpa},
};

const Columns<QuasiStaticFit> kQuasiStaticColumns = {
    {"youngs_modulus_mpa", &QuasiStaticFit::youngs_modulus_mpa},
    {"psi_epsilon_deg", &QuasiStaticFit::psi_epsilon_deg},
    {"start_p_kpa", &QuasiStaticFit::start_p_kpa},
    {"quantity", &QuasiStaticFit::quantity},
    {"rates",
     [](const QuasiStaticFit& f) {
       std::string rates;
       for (double r : f.rates) rates += (rates.empty() ? "" : ";") + CsvNumber(r);
       return rates;
     }},
    {"points", &QuasiStaticFit::points},
    {"i_min", &QuasiStaticFit::i_min},
    {"i_max", &QuasiStaticFit::i_max},
    {"limit", &QuasiStaticFit::limit},
    {"slope", &QuasiStaticFit::slope},
};

const Columns<RateVerdict> kVerdictColumns = {
    {"youngs_modulus_mpa", &RateVerdict::youngs_modulus_mpa},
    {"psi_epsilon_deg", &RateVerdict::psi_epsilon_deg},
    {"start_p_kpa", &RateVerdict::start_p_kpa},
    {"i_smallest", &RateVerdict::smallest},
    {"i_next", &RateVerdict::next},
    {"ln_1_plus_e_smallest", &RateVerdict::ln_v_smallest},
    {"ln_1_plus_e_next", &RateVerdict::ln_v_next},
    {"ln_1_plus_e", &RateVerdict::ln_1_plus_e},
    {"psi_sigma_deg_smallest", &RateVerdict::psi_smallest},
    {"psi_sigma_deg_next", &RateVerdict::psi_next},
    {"psi_sigma_deg", &RateVerdict::psi_sigma},
    {"csl_position_smallest", &RateVerdict::csl_smallest},
    {"csl_position_next", &RateVerdict::csl_next},
    {"csl_position", &RateVerdict::csl_position},
    {"verdict", &RateVerdict::verdict},
    {"reason", &RateVerdict::reason},
};

const Columns<StiffnessComparison> kStiffnessColumns = {
    {"youngs_modulus_mpa", &StiffnessComparison::youngs_modulus_mpa},
    {"reference_modulus_mpa", &StiffnessComparison::reference_modulus_mpa},
    {"psi_epsilon_deg", &StiffnessComparison::psi_epsilon_deg},
    {"start_p_kpa", &StiffnessComparison::start_p_kpa},
    {"rate_rule", &StiffnessComparison::rule},
    {"rate", &StiffnessComparison::rate},
    {"kappa_reference", &StiffnessComparison::kappa_reference},
    {"kappa", &StiffnessComparison::kappa_other},
    {"psi_sigma_deg_reference", &StiffnessComparison::psi_reference},
    {"psi_sigma_deg", &StiffnessComparison::psi_other},
    {"psi_sigma_deg", &StiffnessComparison::psi_sigma},
    {"csl_position_reference", &StiffnessComparison::csl_reference},
    {"csl_position", &StiffnessComparison::csl_other},
    {"csl_position", &StiffnessComparison::csl_position},
    {"verdict", &StiffnessComparison::verdict},
    {"reason", &StiffnessComparison::reason},
};

const Columns<ExtensionStep> kExtensionStepColumns = {
    {"youngs_modulus_mpa", &ExtensionStep::youngs_modulus_mpa},
    {"rate_rule", &ExtensionStep::rule},
    {"inertial_number_target", InertialTarget<ExtensionStep>},
    {"stretching_rate_per_s", ConstantRate<ExtensionStep>},
    {"start_p_kpa", &ExtensionStep::start_p_kpa},
    {"psi_epsilon_deg", &ExtensionStep::psi_epsilon_deg},
    {"states", &ExtensionStep::states},
    {"used", &ExtensionStep::used},
    {"liquefied", &ExtensionStep::liquefied},
    {"sigma_r_over_p", &ExtensionStep::sigma_r_over_p},
    {"psi_sigma_deg", &ExtensionStep::psi_sigma_deg},
    {"p_kpa", &ExtensionStep::p_kpa},
    {"ln_1_plus_e", &ExtensionStep::ln_1_plus_e},
    {"status", &ExtensionStep::status},
};

const Columns<ExtensionLimit> kExtensionLimitColumns = {
    {"youngs_modulus_mpa", &ExtensionLimit::youngs_modulus_mpa},
    {"rate_rule", &ExtensionLimit::rule},
    {"inertial_number_target", InertialTarget<ExtensionLimit>},
    {"stretching_rate_per_s", ConstantRate<ExtensionLimit>},
    {"start_p_kpa", &ExtensionLimit::start_p_kpa},
    {"steps", &ExtensionLimit::steps},
    {"psi_max_deg", &ExtensionLimit::psi_max_deg},
    {"result", &ExtensionLimit::result},
    {"last_asymptote_deg", &ExtensionLimit::last_asymptote_deg},
    {"liquefied_at_deg", &ExtensionLimit::liquefied_at_deg},
    {"limit_step_deg", &ExtensionLimit::limit_step_deg},
    {"psi_d_deg", &ExtensionLimit::psi_d_deg},
    {"text",
     [](const ExtensionLimit& l) { return CsvText(l.result.empty() ? std::string() : l.Text()); }},
};

const Columns<DrainedState> kDrainedStateColumns = {
    {"replicate", &DrainedState::replicate},
    {"case_name", &DrainedState::case_name},
    {"stage", &DrainedState::stage},
    {"status", &DrainedState::status},
    {"youngs_modulus_mpa", &DrainedState::youngs_modulus_mpa},
    {"local_damping", &DrainedState::local_damping, true},
    {"stiffness_ratio", &DrainedState::stiffness_ratio, true},
    {"time_step_fraction", &DrainedState::time_step_fraction, true},
    {"radial_stress_kpa", &DrainedState::radial_stress_kpa},
    {"axial_strain_rate_per_s", &DrainedState::axial_strain_rate},
    {"p_kpa", &DrainedState::p_kpa},
    {"e", &DrainedState::e},
    {"ln_1_plus_e", &DrainedState::ln_1_plus_e},
    {"psi_sigma_deg", &DrainedState::psi_sigma_deg},
    {"q_over_p", &DrainedState::q_over_p},
    {"inertial_number_dmin", &DrainedState::inertial_number_dmin},
    {"inertial_number_dmax", &DrainedState::inertial_number_dmax},
    {"flags", &DrainedState::flags},
};

const Columns<DrainedGroup> kDrainedGroupColumns = {
    {"youngs_modulus_mpa", &DrainedGroup::youngs_modulus_mpa},
    {"local_damping", &DrainedGroup::local_damping},
    {"stiffness_ratio", &DrainedGroup::stiffness_ratio},
    {"time_step_fraction", &DrainedGroup::time_step_fraction},
    {"radial_stress_kpa", &DrainedGroup::radial_stress_kpa},
    {"axial_strain_rate_per_s", &DrainedGroup::axial_strain_rate},
    {"states", &DrainedGroup::states},
    {"used", &DrainedGroup::used},
    {"p_kpa", &DrainedGroup::p_kpa},
    {"e", &DrainedGroup::e},
    {"ln_1_plus_e", &DrainedGroup::ln_1_plus_e},
    {"psi_sigma_deg", &DrainedGroup::psi_sigma_deg},
    {"q_over_p", &DrainedGroup::q_over_p},
    {"inertial_number_dmax", &DrainedGroup::inertial_number_dmax},
};

const Columns<DrainedLimit> kDrainedLimitColumns = {
    {"youngs_modulus_mpa", &DrainedLimit::youngs_modulus_mpa},
    {"local_damping", &DrainedLimit::local_damping},
    {"stiffness_ratio", &DrainedLimit::stiffness_ratio},
    {"time_step_fraction", &DrainedLimit::time_step_fraction},
    {"radial_stress_kpa", &DrainedLimit::radial_stress_kpa},
    {"rates", &DrainedLimit::rates},
    {"points", &DrainedLimit::points},
    {"i_min", &DrainedLimit::i_min},
    {"i_max", &DrainedLimit::i_max},
    {"m", &DrainedLimit::m},
    {"m_slope", &DrainedLimit::m_slope},
    {"ln_1_plus_e", &DrainedLimit::ln_1_plus_e},
    {"ln_p_kpa", &DrainedLimit::ln_p_kpa},
    {"slowest_rate_per_s", &DrainedLimit::slowest},
    {"next_rate_per_s", &DrainedLimit::next},
    {"m", &DrainedLimit::m_change},
    {"ln_1_plus_e", &DrainedLimit::ln_1_plus_e_change},
    {"verdict", &DrainedLimit::verdict},
    {"reason", &DrainedLimit::reason},
};

const Columns<DrainedCriticalState> kDrainedCriticalColumns = {
    {"youngs_modulus_mpa", &DrainedCriticalState::youngs_modulus_mpa},
    {"local_damping", &DrainedCriticalState::local_damping},
    {"stiffness_ratio", &DrainedCriticalState::stiffness_ratio},
    {"time_step_fraction", &DrainedCriticalState::time_step_fraction},
    {"starts", &DrainedCriticalState::starts},
    {"m", &DrainedCriticalState::m},
    {"phi_c_deg", &DrainedCriticalState::phi_c_deg},
    {"m_per_ln_p", &DrainedCriticalState::m_per_ln_p},
    {"lambda", &DrainedCriticalState::lambda},
    {"gamma", &DrainedCriticalState::gamma},
    {"reference_p_kpa", ReferencePressure{}},
    {"position", &DrainedCriticalState::position},
};

// ---------------------------------------------------------------- comments

// The rule for a usable state, as the files' comments state it.
std::string UsableComment(const RateStudyOptions& o) {
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
  return fmt::format("usable states: status {} ({} at psi_epsilon = 0), none flagged {}",
                     join(o.statuses), join(o.ncl_statuses), join(o.excluded_flags));
}

// The four drained files (rate_drained*.csv).
void WriteDrainedFiles(const std::string& directory, const DrainedStudy& d,
                       const RateStudyOptions& o) {
  const std::string usable = UsableComment(o);
  WriteTable(directory + "/" + kRateDrainedStatesFile,
             {"the asymptotic states of the drained triaxial rate cases (constant sigma_r, "
              "constant axial rate), one row per case and detector stage"},
             kDrainedStateColumns, d.states, o);
  WriteTable(directory + "/" + kRateDrainedFile,
             {"per (material: E, local damping, k_t/k_n, time-step fraction; sigma_r, axial rate): "
              "the mean over the replicates' usable states "
              "and the half-width of its 95 % interval (Student t, n - 1 degrees of "
              "freedom); q_over_p is the critical-state ratio M",
              usable},
             kDrainedGroupColumns, d.groups, o);
  WriteTable(directory + "/" + kRateDrainedLimitFile,
             {"per (material, sigma_r): y = a + b I(d_max) by least squares through the usable "
              "states of every axial rate (I(d_max) as measured over each asymptote's "
              "window): the limits as I -> 0 of M = q/p, ln(1+e) and ln p with 95 % "
              "intervals (Student t, points - 2 degrees of freedom); the two slowest "
              "rates compared in M and ln(1+e): rate_independent when both agree within "
              "the 95 % interval of their difference",
              usable},
             kDrainedLimitColumns, d.limits, o);
  WriteTable(
      directory + "/" + kRateDrainedCriticalFile,
      {fmt::format(
           "per material: the quasi-static critical state from the limits of every sigma_r: M "
           "the mean of their M (Student t, starts - 1 degrees of freedom), phi_c = "
           "asin(3M/(6+M)) (interval by the delta method), dM/d ln p the least-squares "
           "slope of their M against ln p (zero within its interval: M independent of "
           "p), and the CSL ln(1+e) = Gamma - lambda ln(p / 1 kPa) through their (ln p, "
           "ln(1+e)) with its position at p = {:g} kPa (Student t, starts - 2 degrees "
           "of freedom; from the scatter of the limits, not their own intervals)",
           o.reference_p_kpa),
       usable},
      kDrainedCriticalColumns, d.critical, o);
}

// The two files of the extension sweep (rate_extension*.csv).
void WriteExtensionFiles(const std::string& directory, const RateStudy& study) {
  WriteTable(directory + "/" + kRateExtensionFile,
             {"the extension sweep (issue 10 section 3): per (E, rate, start p) and psi_epsilon "
              ">= 90 deg, the asymptotic sigma_r/p = 1 - (q/p)/3 (zero at the limit d, psi_sigma "
              "= 54.74 deg) over the usable states, with 95 % intervals; liquefied: replicates "
              "with status or flag gas",
              UsableComment(study.options),
              "status: asymptote (sigma_r/p > 0 outside its interval), limit_d (zero within it), "
              "liquefied (most replicates), undetermined (fewer than two usable states)"},
             kExtensionStepColumns, study.extension_steps, study.options);
  WriteTable(directory + "/" + kRateExtensionLimitFile,
             {"the end of each extension sweep: limit_d (psi_epsilon(d), where sigma_r/p is zero "
              "within its interval; psi_d from the least-squares line of sigma_r/p against "
              "psi_epsilon through the limit step and the two asymptote steps before it, 95 % "
              "delta-method interval), liquefied (the first psi_epsilon at which most replicates "
              "liquefied), not_reached or undetermined"},
             kExtensionLimitColumns, study.extension_limits, study.options);
}

constexpr const char* kRateFiles[] = {
    kRateStatesFile,        kRateSummaryFile,   kRateLinesFile,        kRateQuasiStaticFile,
    kRateIndependenceFile,  kRateStiffnessFile, kRateExtensionFile,    kRateExtensionLimitFile,
    kRateDrainedStatesFile, kRateDrainedFile,   kRateDrainedLimitFile, kRateDrainedCriticalFile};

}  // namespace

void WriteRateFiles(const std::string& directory, const RateStudy& study) {
  const RateStudyOptions& o = study.options;
  const std::string usable = UsableComment(o);
  const std::string path = directory + "/";
  WriteTable(path + kRateStatesFile,
             {"the asymptotic states of the rate cases (figures key 'rate'), one row per "
              "case and detector stage; start_p_kpa: the p target of the state the case "
              "started from; stiffness_number: kappa of the contact law at p; ocr: against the "
              "study's NCL, ocr_same_rate: against the NCL of the same E and rate (its "
              "psi_epsilon = 0 line in rate_lines.csv; empty where p_e* falls outside the "
              "line's p range); path_N, path_lambda: a psi_epsilon = 0 path's own NCL past its "
              "first unit of ln p, over [path_p_min_kpa, path_p_max_kpa]"},
             kStateColumns, study.states, o);
  WriteTable(path + kRateSummaryFile,
             {"per (E, psi_epsilon, start p, rate): the mean over the replicates' usable "
              "states and the half-width of its 95 % interval (Student t, n - 1 degrees "
              "of freedom; empty below two states)",
              usable},
             kSummaryColumns, study.groups, o);
  WriteTable(path + kRateLinesFile,
             {fmt::format("per (E, psi_epsilon, rate): ln(1+e) = N - lambda ln(p / 1 kPa) "
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
              usable},
             kLineColumns, study.lines, o);
  WriteTable(path + kRateQuasiStaticFile,
             {fmt::format("the quasi-static limit per (E, psi_epsilon, start p): y = a + b "
                          "I(d_max) by least squares through the usable states of the {} "
                          "smallest I* (I(d_max) as measured over each asymptote's window; "
                          "the small-I form of the mu(I) laws of da Cruz et al. 2005 and "
                          "Jop et al. 2006); a, b with "
                          "95 % intervals (Student t, points - 2 degrees of freedom)",
                          o.fit_rates),
              usable},
             kQuasiStaticColumns, study.quasi_static, o);
  WriteTable(path + kRateIndependenceFile,
             {fmt::format("rate independence (SPEC 8.2) per (E, psi_epsilon, start p): the two "
                          "smallest I* agree when the difference of their means is inside its "
                          "95 % interval (Welch: t with Welch-Satterthwaite degrees of freedom, "
                          "rounded down) in ln(1+e), psi_sigma and the CSL's ln(1+e) at {:g} kPa",
                          o.reference_p_kpa),
              usable},
             kVerdictColumns, study.verdicts, o);
  WriteTable(path + kRateStiffnessFile,
             {fmt::format("stiffness scaling (issue 10): per (E, psi_epsilon, start p, rate) with "
                          "groups at the main modulus (reference) and at E, E against the "
                          "reference in psi_sigma and in the position of the CSL of that rate "
                          "(ln(1+e) at {:g} kPa); they agree when the difference is inside its "
                          "95 % interval (Welch); kappa: the stiffness numbers at the asymptotes",
                          o.reference_p_kpa),
              usable},
             kStiffnessColumns, study.stiffness, o);
  WriteExtensionFiles(directory, study);
  WriteDrainedFiles(directory, study.drained, o);
}

void RemoveRateFiles(const std::string& directory) {
  for (const char* name : kRateFiles) fs::remove(fs::path(directory) / name);
}

std::vector<RateState> ReadRateStates(const std::string& directory) {
  return ReadTable(directory, kRateStatesFile, kStateColumns);
}

std::vector<DrainedState> ReadDrainedStates(const std::string& directory) {
  return ReadTable(directory, kRateDrainedStatesFile, kDrainedStateColumns);
}

std::optional<RateStudy> ReadRateStudy(const std::string& directory) {
  std::vector<RateState> states = ReadRateStates(directory);
  std::vector<DrainedState> drained = ReadDrainedStates(directory);
  if (states.empty() && drained.empty()) return std::nullopt;
  RateStudy study = RateStudy::Analyse(std::move(states));
  study.drained = DrainedStudy::Analyse(std::move(drained), study.options);
  return study;
}

}  // namespace granasym::analysis
