// CSV input of asymptotic states with units in the column names.
#include "calibration/csv_state_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>

#include "common/csv_table.h"
#include "common/error.h"
#include "common/quantity_names.h"
#include "common/state_measures.h"

namespace granasym::calibration {

namespace {

struct Quantity {
  const char* prefix;  // column name without units, with the separator
  std::vector<std::pair<const char*, double>> units;  // suffix, factor to the internal unit
};

// Internal units: kPa, rad.
const std::vector<Quantity>& Quantities() {
  static const std::vector<Quantity> quantities = {
      {"p_", {{"kpa", 1.0}, {"mpa", 1e3}, {"pa", 1e-3}}},
      {"q_", {{"kpa", 1.0}}},
      {"psi_sigma_", {{"deg", kDegree}, {"rad", 1.0}}},
      {"psi_epsilon_", {{"deg", kDegree}, {"rad", 1.0}}},
  };
  return quantities;
}

// |ln(1 + e) − ln_1_plus_e| allowed where a file gives both (rounding of a
// 17-digit file is ~1e-16; a file written with 6 digits stays within 1e-6).
constexpr double kVolumeMeasureTolerance = 1e-6;

const std::vector<std::string>& PlainColumns() {
  static const std::vector<std::string> plain = {quantity::kVoidRatio, quantity::kLnVolume,
                                                 "weight", "psi_sigma_uncertainty_deg",
                                                 "ln_1_plus_e_uncertainty"};
  return plain;
}

bool Ignored(const CsvReadOptions& options, const std::string& column) {
  return std::find(options.ignore_columns.begin(), options.ignore_columns.end(), column) !=
         options.ignore_columns.end();
}

// Index of a column that is read (not listed in ignore_columns).
std::optional<size_t> FindPlain(const CsvTable& table, const CsvReadOptions& options,
                                const std::string& name) {
  const int c = table.Find(name);
  if (c < 0 || Ignored(options, name)) return std::nullopt;
  return static_cast<size_t>(c);
}

// Index and factor of the column giving `prefix` in any known unit.
std::optional<std::pair<size_t, double>> FindQuantity(const CsvTable& table,
                                                      const CsvReadOptions& options,
                                                      const std::string& prefix) {
  for (const Quantity& quantity : Quantities()) {
    if (prefix != quantity.prefix) continue;
    for (const auto& unit : quantity.units) {
      if (const auto c = FindPlain(table, options, prefix + unit.first)) {
        return std::make_pair(*c, unit.second);
      }
    }
  }
  return std::nullopt;
}

// Every documented column name.
std::vector<std::string> KnownColumns() {
  std::vector<std::string> known;
  for (const Quantity& quantity : Quantities()) {
    for (const auto& unit : quantity.units)
      known.push_back(quantity.prefix + std::string(unit.first));
  }
  known.insert(known.end(), PlainColumns().begin(), PlainColumns().end());
  return known;
}

// Columns that give one quantity in different units or measures: at most one
// of each group may be read (ln_1_plus_e next to e is checked row by row).
const std::vector<std::pair<const char*, std::vector<std::string>>>& AlternativeColumns() {
  static const std::vector<std::pair<const char*, std::vector<std::string>>> groups = {
      {"the mean stress", {"p_kpa", "p_mpa", "p_pa"}},
      {"the stress direction", {"psi_sigma_deg", "psi_sigma_rad", "q_kpa"}},
      {"the stretching direction", {"psi_epsilon_deg", "psi_epsilon_rad"}},
  };
  return groups;
}

void CheckColumns(const CsvTable& table, const CsvReadOptions& options) {
  // A known quantity in unknown units first: the message can say which units exist.
  for (const std::string& column : table.columns) {
    if (Ignored(options, column)) continue;
    if (std::find(PlainColumns().begin(), PlainColumns().end(), column) != PlainColumns().end()) {
      continue;
    }
    for (const Quantity& quantity : Quantities()) {
      const std::string prefix = quantity.prefix;
      if (column.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string suffix = column.substr(prefix.size());
      bool known = false;
      std::string valid;
      for (const auto& unit : quantity.units) {
        if (suffix == unit.first) known = true;
        valid += (valid.empty() ? "" : ", ") + prefix + unit.first;
      }
      if (!known) {
        throw InputError(fmt::format("{}: line {}: column '{}': unknown units '{}' (valid: {})",
                                     table.origin, table.header_line, column, suffix, valid));
      }
    }
  }
  std::vector<std::string> allowed = KnownColumns();
  allowed.insert(allowed.end(), options.ignore_columns.begin(), options.ignore_columns.end());
  try {
    table.RequireOnlyColumns(allowed);
  } catch (const InputError& error) {
    throw InputError(std::string(error.what()) + "; list other columns in ignore_columns");
  }
  for (const auto& [what, names] : AlternativeColumns()) {
    std::optional<size_t> first;
    for (const std::string& name : names) {
      const auto c = FindPlain(table, options, name);
      if (!c) continue;
      if (first) {
        throw InputError(fmt::format(
            "{}: line {}: columns '{}' (column {}) and '{}' (column {}) both give {}: give one "
            "of them (or list the other in ignore_columns)",
            table.origin, table.header_line, table.columns[*first], *first + 1, name, *c + 1,
            what));
      }
      first = c;
    }
  }
}

[[noreturn]] void Missing(const CsvTable& table, const std::string& what) {
  std::string present;
  for (const std::string& c : table.columns) present += (present.empty() ? "" : ", ") + c;
  throw InputError(
      fmt::format("{}: missing column: {} (columns present: {})", table.origin, what, present));
}

}  // namespace

bool CsvReadOptions::IsValid(std::string* why) const {
  StateKind parsed;
  if (kind != "auto" && !FromString(kind, &parsed)) {
    *why = fmt::format("kind = '{}' must be auto, {}", kind, AllowedNames<StateKind>());
    return false;
  }
  return ValidReaderSettings(kind_tolerance_deg, psi_sigma_uncertainty_deg, ln_volume_uncertainty,
                             weight, why);
}

StateDataset ParseStatesCsv(const std::string& text, const std::string& origin,
                            const std::string& name, const CsvReadOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  const CsvTable table = CsvTable::Parse(text, origin);
  CheckColumns(table, options);
  StateKind forced = StateKind::kNcl;
  const bool automatic = options.kind == "auto";
  if (!automatic) FromString(options.kind, &forced);

  const auto p = FindQuantity(table, options, "p_");
  if (!p) Missing(table, "mean stress (p_kpa, p_mpa or p_pa)");
  const auto e = FindPlain(table, options, quantity::kVoidRatio);
  const auto ln_v = FindPlain(table, options, quantity::kLnVolume);
  if (!e && !ln_v) Missing(table, "void ratio (e or ln_1_plus_e)");
  const auto psi_s = FindQuantity(table, options, "psi_sigma_");
  const auto q = FindQuantity(table, options, "q_");
  if (!psi_s && !q) Missing(table, "stress direction (psi_sigma_deg, psi_sigma_rad or q_kpa)");
  const auto psi_e = FindQuantity(table, options, "psi_epsilon_");
  if (!psi_e && (automatic || forced != StateKind::kAsbs)) {
    Missing(table,
            "stretching direction (psi_epsilon_deg or psi_epsilon_rad; only kind = \"asbs\" "
            "datasets may omit it)");
  }
  const auto weight = FindPlain(table, options, "weight");
  const auto u_psi = FindPlain(table, options, "psi_sigma_uncertainty_deg");
  const auto u_v = FindPlain(table, options, "ln_1_plus_e_uncertainty");

  StateDataset dataset;
  dataset.name = name;
  dataset.origin = origin;
  if (table.rows.empty()) {
    throw InputError(fmt::format("{}: no data rows (dataset '{}' is empty)", origin, name));
  }
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<double>& row = table.rows[r];
    AsymptoticStatePoint point;
    point.source = fmt::format("{}:{}", origin, table.line_numbers[r]);
    point.mean_stress = row[p->first] * p->second;
    point.void_ratio = e ? row[*e] : std::exp(row[*ln_v]) - 1.0;
    // Both measures of the volume (WriteStatesCsv writes both): they must agree.
    if (e && ln_v && !(std::abs(std::log1p(row[*e]) - row[*ln_v]) <= kVolumeMeasureTolerance)) {
      throw InputError(fmt::format(
          "{}: columns 'e' = {} and 'ln_1_plus_e' = {} disagree (ln(1 + e) = {:.7g}, tolerance "
          "{}): "
          "give one of them",
          point.source, row[*e], row[*ln_v], std::log1p(row[*e]), kVolumeMeasureTolerance));
    }
    point.psi_sigma = psi_s ? row[psi_s->first] * psi_s->second
                            : std::atan2(std::sqrt(2.0) * row[q->first], 3.0 * point.mean_stress);
    point.psi_epsilon =
        psi_e ? row[psi_e->first] * psi_e->second : std::numeric_limits<double>::quiet_NaN();
    if (automatic) {
      if (!std::isfinite(point.psi_epsilon)) {
        throw InputError(fmt::format("{}: column '{}' is {}: not a number", point.source,
                                     table.columns[psi_e->first], row[psi_e->first]));
      }
      point.kind = KindFromStretching(point.psi_epsilon, options.kind_tolerance_deg * kDegree);
    } else {
      point.kind = forced;
    }
    point.weight = options.weight * (weight ? row[*weight] : 1.0);
    point.psi_sigma_uncertainty =
        (u_psi ? row[*u_psi] : options.psi_sigma_uncertainty_deg) * kDegree;
    point.ln_volume_uncertainty = u_v ? row[*u_v] : options.ln_volume_uncertainty;
    // Name the column of a non-finite value before the generic validation.
    for (size_t c = 0; c < row.size(); ++c) {
      const bool unused_stretching =
          !automatic && forced == StateKind::kAsbs && psi_e && c == psi_e->first;
      if (!std::isfinite(row[c]) && !unused_stretching &&
          std::find(options.ignore_columns.begin(), options.ignore_columns.end(),
                    table.columns[c]) == options.ignore_columns.end()) {
        throw InputError(fmt::format("{}: column '{}' is {}: every value must be a finite number",
                                     point.source, table.columns[c], row[c]));
      }
    }
    dataset.points.push_back(point);
  }
  dataset.Validate();
  return dataset;
}

StateDataset ReadStatesCsv(const std::string& path, const std::string& name,
                           const CsvReadOptions& options) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("cannot open CSV file '{}' (dataset '{}')", path, name));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return ParseStatesCsv(text, path, name, options);
}

void WriteStatesCsv(const StateDataset& dataset, const std::string& path) {
  std::vector<std::vector<double>> columns(8);
  for (const AsymptoticStatePoint& point : dataset.points) {
    columns[0].push_back(point.mean_stress);
    columns[1].push_back(point.void_ratio);
    columns[2].push_back(point.psi_sigma / kDegree);
    columns[3].push_back(point.psi_epsilon / kDegree);
    columns[4].push_back(point.weight);
    columns[5].push_back(point.psi_sigma_uncertainty / kDegree);
    columns[6].push_back(point.ln_volume_uncertainty);
    columns[7].push_back(std::log1p(point.void_ratio));
  }
  WriteCsv(path,
           {quantity::kMeanStress, quantity::kVoidRatio, quantity::kPsiSigma, quantity::kPsiEpsilon,
            "weight", "psi_sigma_uncertainty_deg", "ln_1_plus_e_uncertainty", quantity::kLnVolume},
           columns);
}

}  // namespace granasym::calibration
