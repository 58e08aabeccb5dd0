// CSV input of asymptotic states with units in the column names.
#include "calibration/csv_state_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>

#include "common/csv_table.h"
#include "common/error.h"
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

const std::vector<std::string>& PlainColumns() {
  static const std::vector<std::string> plain = {
      "e", "ln_1_plus_e", "weight", "psi_sigma_uncertainty_deg", "ln_1_plus_e_uncertainty"};
  return plain;
}

// Index and factor of the column giving `prefix` in any known unit.
std::optional<std::pair<size_t, double>> FindQuantity(const CsvTable& table,
                                                      const std::string& prefix) {
  for (const Quantity& quantity : Quantities()) {
    if (prefix != quantity.prefix) continue;
    for (const auto& unit : quantity.units) {
      const std::string name = prefix + unit.first;
      for (size_t c = 0; c < table.columns.size(); ++c) {
        if (table.columns[c] == name) return std::make_pair(c, unit.second);
      }
    }
  }
  return std::nullopt;
}

std::optional<size_t> FindPlain(const CsvTable& table, const std::string& name) {
  for (size_t c = 0; c < table.columns.size(); ++c) {
    if (table.columns[c] == name) return c;
  }
  return std::nullopt;
}

void CheckColumns(const CsvTable& table, const CsvReadOptions& options) {
  for (const std::string& column : table.columns) {
    if (std::find(options.ignore_columns.begin(), options.ignore_columns.end(), column) !=
        options.ignore_columns.end()) {
      continue;
    }
    if (std::find(PlainColumns().begin(), PlainColumns().end(), column) != PlainColumns().end()) {
      continue;
    }
    bool known = false;
    for (const Quantity& quantity : Quantities()) {
      const std::string prefix = quantity.prefix;
      if (column.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string suffix = column.substr(prefix.size());
      if (suffix == "uncertainty_deg") continue;  // psi_sigma_uncertainty_deg, handled above
      std::string valid;
      for (const auto& unit : quantity.units) {
        if (suffix == unit.first) known = true;
        valid += (valid.empty() ? "" : ", ") + prefix + unit.first;
      }
      if (!known) {
        throw InputError(fmt::format("{}: column '{}': unknown units '{}' (valid: {})",
                                     table.origin, column, suffix, valid));
      }
    }
    if (!known) {
      throw InputError(fmt::format(
          "{}: unknown column '{}' (documented columns: p_kpa|p_mpa|p_pa, e|ln_1_plus_e, "
          "psi_sigma_deg|psi_sigma_rad|q_kpa, psi_epsilon_deg|psi_epsilon_rad, weight, "
          "psi_sigma_uncertainty_deg, ln_1_plus_e_uncertainty; list others in ignore_columns)",
          table.origin, column));
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

  const auto p = FindQuantity(table, "p_");
  if (!p) Missing(table, "mean stress (p_kpa, p_mpa or p_pa)");
  const auto e = FindPlain(table, "e");
  const auto ln_v = FindPlain(table, "ln_1_plus_e");
  if (!e && !ln_v) Missing(table, "void ratio (e or ln_1_plus_e)");
  const auto psi_s = FindQuantity(table, "psi_sigma_");
  const auto q = FindQuantity(table, "q_");
  if (!psi_s && !q) Missing(table, "stress direction (psi_sigma_deg, psi_sigma_rad or q_kpa)");
  const auto psi_e = FindQuantity(table, "psi_epsilon_");
  if (!psi_e && (automatic || forced != StateKind::kAsbs)) {
    Missing(table,
            "stretching direction (psi_epsilon_deg or psi_epsilon_rad; only kind = \"asbs\" "
            "datasets may omit it)");
  }
  const auto weight = FindPlain(table, "weight");
  const auto u_psi = FindPlain(table, "psi_sigma_uncertainty_deg");
  const auto u_v = FindPlain(table, "ln_1_plus_e_uncertainty");

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
           {"p_kpa", "e", "psi_sigma_deg", "psi_epsilon_deg", "weight", "psi_sigma_uncertainty_deg",
            "ln_1_plus_e_uncertainty", "ln_1_plus_e"},
           columns);
}

}  // namespace granasym::calibration
