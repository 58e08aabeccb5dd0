// Reading a study's state table, with selections and replicate means.
#include "calibration/study_state_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "calibration/fit_result.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "common/statistics.h"
#include "study/state_table_names.h"

namespace granasym::calibration {

namespace {

namespace names = granasym::study::table;

std::string Join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

bool Contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::vector<std::string> SplitFlags(const std::string& flags) {
  std::vector<std::string> parts;
  std::stringstream in(flags);
  std::string part;
  while (std::getline(in, part, names::kFlagSeparator)) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

struct Row {
  int replicate = 1;
  std::string kind, status, case_name, stage, flags, ncl_reference, source;
  double psi_epsilon_deg = 0, p_kpa = 0, e = 0, psi_sigma_deg = 0, ocr = 0;
  double inertial_number_dmin = std::nan(""), inertial_number_dmax = std::nan("");
};

std::vector<Row> ReadRows(const std::string& path) {
  const Hdf5File file = Hdf5File::OpenRead(path);
  const std::string group = names::kStatesGroup;
  auto column = [&](const char* name) { return group + "/" + name; };
  for (const char* required :
       {names::kColumnReplicate, names::kColumnKind, names::kColumnStatus, names::kColumnCaseName,
        names::kColumnStage, names::kColumnFlags, names::kColumnPsiEpsilon,
        names::kColumnMeanStress, names::kColumnVoidRatio, names::kColumnPsiSigma}) {
    if (!file.Exists(column(required))) {
      throw InputError(
          fmt::format("{}: not a granasym study state table (no dataset {}; "
                      "`granasym study run` writes it)",
                      path, column(required)));
    }
  }
  const std::vector<int64_t> replicate = file.ReadInts(column(names::kColumnReplicate));
  const std::vector<std::string> kind = file.ReadStrings(column(names::kColumnKind));
  const std::vector<std::string> status = file.ReadStrings(column(names::kColumnStatus));
  const std::vector<std::string> case_name = file.ReadStrings(column(names::kColumnCaseName));
  const std::vector<std::string> stage = file.ReadStrings(column(names::kColumnStage));
  const std::vector<std::string> flags = file.ReadStrings(column(names::kColumnFlags));
  const std::vector<double> psi_e = file.ReadDoubles(column(names::kColumnPsiEpsilon));
  const std::vector<double> p = file.ReadDoubles(column(names::kColumnMeanStress));
  const std::vector<double> e = file.ReadDoubles(column(names::kColumnVoidRatio));
  const std::vector<double> psi_s = file.ReadDoubles(column(names::kColumnPsiSigma));
  const bool has_ocr = file.Exists(column(names::kColumnOcr));
  const std::vector<double> ocr =
      has_ocr ? file.ReadDoubles(column(names::kColumnOcr)) : std::vector<double>();
  const bool has_reference = file.Exists(column(names::kColumnNclReference));
  const std::vector<std::string> reference =
      has_reference ? file.ReadStrings(column(names::kColumnNclReference))
                    : std::vector<std::string>();
  // Tables written before the source column hold no ensemble rows.
  const bool has_source = file.Exists(column(names::kColumnSource));
  const std::vector<std::string> source =
      has_source ? file.ReadStrings(column(names::kColumnSource)) : std::vector<std::string>();
  // Tables (and joined rows) written before issue 36 may lack the rate.
  const auto optional_doubles = [&](const char* name) {
    return file.Exists(column(name)) ? file.ReadDoubles(column(name)) : std::vector<double>();
  };
  const std::vector<double> i_dmin = optional_doubles(names::kColumnInertialNumberDmin);
  const std::vector<double> i_dmax = optional_doubles(names::kColumnInertialNumberDmax);
  const size_t n = replicate.size();
  for (size_t size : {kind.size(), status.size(), case_name.size(), stage.size(), flags.size(),
                      psi_e.size(), p.size(), e.size(), psi_s.size()}) {
    if (size != n) {
      throw InputError(fmt::format("{}: the columns of {} differ in length ({} and {} rows)", path,
                                   group, n, size));
    }
  }
  std::vector<Row> rows(n);
  for (size_t k = 0; k < n; ++k) {
    Row& r = rows[k];
    r.replicate = static_cast<int>(replicate[k]);
    r.kind = kind[k];
    r.status = status[k];
    r.case_name = case_name[k];
    r.stage = stage[k];
    r.flags = flags[k];
    r.psi_epsilon_deg = psi_e[k];
    r.p_kpa = p[k];
    r.e = e[k];
    r.psi_sigma_deg = psi_s[k];
    r.ocr = k < ocr.size() ? ocr[k] : std::nan("");
    r.ncl_reference = k < reference.size() ? reference[k] : "";
    r.source = k < source.size() ? source[k] : "";
    if (k < i_dmin.size()) r.inertial_number_dmin = i_dmin[k];
    if (k < i_dmax.size()) r.inertial_number_dmax = i_dmax[k];
  }
  return rows;
}

}  // namespace

const std::vector<std::string>& StudyTableKinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> names;
    for (study::TableKind kind : EnumValues<study::TableKind>()) {
      if (kind != study::TableKind::kNone) names.push_back(ToString(kind));  // a state's kinds
    }
    return names;
  }();
  return kinds;
}

const std::vector<std::string>& StudyTableStatuses() {
  static const std::vector<std::string> statuses = [] {
    std::vector<std::string> names;
    for (study::TableStatus status : EnumValues<study::TableStatus>()) {
      names.push_back(ToString(status));
    }
    return names;
  }();
  return statuses;
}

bool StudyReadOptions::IsValid(std::string* why) const {
  for (const std::string& kind : kinds) {
    if (!Contains(StudyTableKinds(), kind)) {
      *why = fmt::format("kinds: '{}' is not a kind of the state table: expected {}", kind,
                         Join(StudyTableKinds()));
      return false;
    }
  }
  if (kinds.empty()) {
    *why = "kinds is empty: give at least one of " + Join(StudyTableKinds());
    return false;
  }
  for (const std::string& status : statuses) {
    if (!Contains(StudyTableStatuses(), status)) {
      *why = fmt::format("statuses: '{}' is not a status of the state table: expected {}", status,
                         Join(StudyTableStatuses()));
      return false;
    }
  }
  if (statuses.empty()) {
    *why = "statuses is empty: give at least one of " + Join(StudyTableStatuses());
    return false;
  }
  if (!(psi_epsilon_min_deg < psi_epsilon_max_deg && psi_epsilon_min_deg >= -180 &&
        psi_epsilon_max_deg <= 180)) {
    *why = fmt::format(
        "psi_epsilon_range_deg = [{}, {}]: expected [lo, hi] with -180 <= lo < hi <= 180",
        psi_epsilon_min_deg, psi_epsilon_max_deg);
    return false;
  }
  if (!(max_inertial_number > 0)) {
    *why = fmt::format("max_inertial_number = {} must be > 0 (infinite: no bound)",
                       max_inertial_number);
    return false;
  }
  if (!(triaxial_kind_tolerance_deg >= 0 && triaxial_kind_tolerance_deg < 45)) {
    *why = fmt::format("triaxial_kind_tolerance_deg = {} must be in [0, 45)",
                       triaxial_kind_tolerance_deg);
    return false;
  }
  return ValidReaderSettings(kind_tolerance_deg, psi_sigma_uncertainty_deg, ln_volume_uncertainty,
                             weight, why);
}

StateDataset ReadStatesStudy(const std::string& directory, const std::string& name,
                             const StudyReadOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("dataset '" + name + "': " + why);
  const std::filesystem::path given(directory);
  const std::string path =
      std::filesystem::is_directory(given) ? (given / names::kFileName).string() : directory;
  if (!std::filesystem::exists(path)) {
    throw InputError(
        fmt::format("dataset '{}': {} does not exist (a study folder holds {} once "
                    "`granasym study run` has finished)",
                    name, path, names::kFileName));
  }
  const std::vector<Row> rows = ReadRows(path);

  // Selection, then groups by (case_name, stage) in the table's order.
  std::map<std::pair<std::string, std::string>, std::vector<const Row*>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::string, int> present;  // "kind status" → rows, for the message
  // The ensemble rows (the replicates' mean paths) are no replicate of their
  // state: the replicates' own rows are averaged here.
  const std::string ensemble = ToString(study::TableSource::kEnsemble);
  const bool bounded = std::isfinite(options.max_inertial_number);
  int too_fast = 0, rate_unknown = 0;  // rows left out by the I(d_max) bound
  for (const Row& row : rows) {
    if (row.source == ensemble) continue;
    ++present[row.kind + " " + row.status];
    if (!Contains(options.kinds, row.kind) || !Contains(options.statuses, row.status)) continue;
    if (!(row.psi_epsilon_deg >= options.psi_epsilon_min_deg &&
          row.psi_epsilon_deg <= options.psi_epsilon_max_deg)) {
      continue;
    }
    bool excluded = false;
    for (const std::string& flag : SplitFlags(row.flags)) {
      excluded = excluded || Contains(options.exclude_flags, flag);
    }
    if (excluded) continue;
    if (!options.ncl_references.empty() && !Contains(options.ncl_references, row.ncl_reference)) {
      continue;
    }
    if (!options.cases.empty() && !Contains(options.cases, row.case_name)) continue;
    if (bounded && !(row.inertial_number_dmax < options.max_inertial_number)) {
      ++(std::isnan(row.inertial_number_dmax) ? rate_unknown : too_fast);
      continue;
    }
    const auto key = std::make_pair(row.case_name, row.stage);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&row);
  }

  StateDataset dataset;
  dataset.name = name;
  dataset.origin = path;
  if (order.empty()) {
    std::string counts;
    for (const auto& [key, count] : present) counts += fmt::format(" {} {};", count, key);
    throw InputError(fmt::format(
        "dataset '{}': {}: no state passes the selections (kinds {}; statuses {}; "
        "psi_epsilon_range_deg [{}, {}]; exclude_flags {}{}{}{}); the table holds:{}",
        name, path, Join(options.kinds), Join(options.statuses), options.psi_epsilon_min_deg,
        options.psi_epsilon_max_deg, Join(options.exclude_flags),
        options.ncl_references.empty() ? "" : "; ncl_references " + Join(options.ncl_references),
        options.cases.empty() ? "" : fmt::format("; {} named cases", options.cases.size()),
        bounded ? fmt::format("; max_inertial_number {:g}, which left out {} rows at or above it "
                              "and {} without an inertial number",
                              options.max_inertial_number, too_fast, rate_unknown)
                : "",
        counts));
  }
  if (too_fast + rate_unknown > 0) {
    dataset.warnings.push_back(fmt::format(
        "max_inertial_number = {:g} left out {} rows with I(d_max) at or above it and {} rows "
        "without an inertial number",
        options.max_inertial_number, too_fast, rate_unknown));
  }
  const double stated_psi = options.psi_sigma_uncertainty_deg * kDegree;
  const double stated_v = options.ln_volume_uncertainty;
  for (const auto& key : order) {
    const std::vector<const Row*>& members = groups[key];
    std::vector<double> ln_p, ln_v, psi_s, psi_e, ocr;
    std::string replicates;
    AsymptoticStatePoint point;
    for (const Row* row : members) {
      if (!(row->p_kpa > 0 && row->e > 0 && std::isfinite(row->psi_sigma_deg))) {
        throw InputError(fmt::format(
            "dataset '{}': {}: row {}/{} (replicate {}) has p_kpa = {}, e = {}, psi_sigma_deg = "
            "{}: a selected state needs p > 0, e > 0 and a finite psi_sigma (select other "
            "statuses or exclude its flags)",
            name, path, row->case_name, row->stage, row->replicate, row->p_kpa, row->e,
            row->psi_sigma_deg));
      }
      ln_p.push_back(std::log(row->p_kpa));
      ln_v.push_back(std::log1p(row->e));
      psi_s.push_back(row->psi_sigma_deg * kDegree);
      psi_e.push_back(row->psi_epsilon_deg * kDegree);
      if (std::isfinite(row->ocr) && row->ocr > 0) ocr.push_back(std::log(row->ocr));
      replicates += (replicates.empty() ? "r" : ",r") + std::to_string(row->replicate);
      // The largest I of the replicates, the union of their flags.
      for (auto [value, into] :
           {std::pair{row->inertial_number_dmin, &point.inertial_number_dmin},
            std::pair{row->inertial_number_dmax, &point.inertial_number_dmax}}) {
        if (std::isfinite(value) && !(*into >= value)) *into = value;
      }
      for (const std::string& flag : SplitFlags(row->flags)) {
        if (!point.HasFlag(flag)) point.flags += (point.flags.empty() ? "" : ";") + flag;
      }
    }
    const std::optional<study::TableKind> kind =
        FromString<study::TableKind>(members.front()->kind);
    point.psi_epsilon = Mean(psi_e);
    if (kind == study::TableKind::kTriaxial) {
      point.kind =
          KindFromStretching(point.psi_epsilon, options.triaxial_kind_tolerance_deg * kDegree);
    } else if (kind == study::TableKind::kNcl || kind == study::TableKind::kCsl) {
      point.kind = kind == study::TableKind::kNcl ? StateKind::kNcl : StateKind::kCsl;
    } else {
      // compression / extension rows keep their side of 90° even when their
      // ψ_ε is close to it.
      point.kind =
          kind == study::TableKind::kCompression ? StateKind::kCompression : StateKind::kExtension;
    }
    point.mean_stress = std::exp(Mean(ln_p));
    point.void_ratio = std::expm1(Mean(ln_v));
    point.psi_sigma = Mean(psi_s);
    point.source_ocr = ocr.size() == members.size() ? std::exp(Mean(ocr)) : std::nan("");
    point.weight = options.weight;
    point.replicates = static_cast<int>(members.size());
    const double n = static_cast<double>(members.size());
    if (members.size() >= 2) {
      const double se_psi = StandardError(psi_s), se_v = StandardError(ln_v);
      point.psi_sigma_uncertainty = std::max(se_psi, stated_psi / std::sqrt(n));
      point.ln_volume_uncertainty = std::max(se_v, stated_v / std::sqrt(n));
      const double t = StudentT95(static_cast<int>(members.size()) - 1);
      point.psi_sigma_ci95 = t * se_psi;
      point.ln_volume_ci95 = t * se_v;
    } else {
      point.psi_sigma_uncertainty = stated_psi;
      point.ln_volume_uncertainty = stated_v;
    }
    point.source =
        fmt::format("{}/{} ({} {})", key.first, key.second, members.front()->kind, replicates);
    dataset.points.push_back(point);
  }
  return dataset;
}

}  // namespace granasym::calibration
