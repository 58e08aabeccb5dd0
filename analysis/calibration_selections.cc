#include "analysis/calibration_selections.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "analysis/rate_files.h"
#include "analysis/report_tables.h"
#include "common/config.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace fs = std::filesystem;
namespace {

// A finite number of a CSV field (report_tables.h's Number), else none.
std::optional<double> NumberOf(const std::string& text) {
  const std::optional<double> v = report::Number(text);
  return v && std::isfinite(*v) ? v : std::nullopt;
}

std::string Number(const std::optional<double>& v) {
  return v ? fmt::format("{:.10g}", *v) : std::string();
}

bool IsRateStudy(const std::string& directory) {
  return fs::exists(fs::path(directory) / kRateStatesFile) ||
         fs::exists(fs::path(directory) / kRateDrainedStatesFile);
}

// parameters.csv of one folder by parameter name, in the file's order.
std::vector<std::pair<std::string, SelectionParameter>> ReadParameters(
    const std::string& path, std::vector<std::string>* units) {
  const CsvTextTable table = CsvTextTable::ReadFile(path);
  const size_t name = table.Column("parameter"), value = table.Column("value"),
               low = table.Column("ci95_low"), high = table.Column("ci95_high"),
               status = table.Column("status");
  const int profile = table.Find("profile"), profile_low = table.Find("profile_low"),
            profile_high = table.Find("profile_high"), unit = table.Find("units");
  std::vector<std::pair<std::string, SelectionParameter>> out;
  for (size_t k = 0; k < table.rows.size(); ++k) {
    const std::vector<std::string>& row = table.rows[k];
    SelectionParameter p;
    const std::optional<double> v = NumberOf(row[value]);
    if (!v) {
      throw InputError(fmt::format("{}:{}: parameter '{}': value '{}' is not a number", path,
                                   table.line_numbers[k], row[name], row[value]));
    }
    p.value = *v;
    p.status = row[status];
    p.profile = profile >= 0 ? row[profile] : "";
    const std::optional<double> plo = profile_low >= 0 ? NumberOf(row[profile_low]) : std::nullopt,
                                phi =
                                    profile_high >= 0 ? NumberOf(row[profile_high]) : std::nullopt;
    const std::optional<double> jlo = NumberOf(row[low]), jhi = NumberOf(row[high]);
    if (p.profile == "determined" && plo && phi) {
      p.low = plo, p.high = phi, p.interval = "profile";
    } else if (p.profile != "flat" && jlo && jhi) {
      p.low = jlo, p.high = jhi, p.interval = "jacobian";
    }
    if (units) units->push_back(unit >= 0 ? row[unit] : "");
    out.emplace_back(row[name], p);
  }
  return out;
}

std::string FitStatusOf(const std::string& file) {
  if (!fs::exists(file)) return "";
  return ConfigTable::ParseFile(file).GetString("status", "");
}

}  // namespace

const char* SelectionName(CalibrationSelection selection) {
  return selection == CalibrationSelection::kAll ? "all" : "quasi_static";
}

CalibrationSelection DefaultSelection(const std::string& directory) {
  return IsRateStudy(directory) ? CalibrationSelection::kQuasiStatic : CalibrationSelection::kAll;
}

std::string SelectionFolder(const std::string& directory, const std::string& model,
                            CalibrationSelection selection) {
  if (selection == DefaultSelection(directory)) return "calibration/" + model;
  return std::string("calibration/") + SelectionName(selection) + "/" + model;
}

std::string SelectionTitle(const std::string& directory, CalibrationSelection selection) {
  if (selection == CalibrationSelection::kQuasiStatic) return "quasi-static";
  return IsRateStudy(directory) ? "all rates (--select all)" : "paper rate (all detected states)";
}

std::string SelectionAdvice(const std::string& directory) {
  if (IsRateStudy(directory)) {
    return "A paper uses the quasi-static selection: the rate study's quasi-static set, driven at "
           "a controlled I* whose rate independence was tested (docs/guide/calibration.md, "
           "'Which one a paper should use').";
  }
  return "A paper uses the quasi-static parameters of a rate study's quasi-static set where the "
         "study has one; here the paper-rate fit describes the DEM at its rate (most states "
         "flagged rate_affected), and the quasi-static selection of this study (states with "
         "I(d_max) below a bound) is a check of how much the rate moves the parameters, a biased "
         "subset, not the paper's values (docs/guide/calibration.md, 'Which one a paper should "
         "use').";
}

std::string SelectionToml(CalibrationSelection selection, const std::string& description) {
  return fmt::format("selection = \"{}\"\ndescription = {}\n", SelectionName(selection),
                     TomlQuoted(description));
}

std::vector<SelectionCalibration> CalibratedSelections(const std::string& directory,
                                                       const std::string& model) {
  std::vector<SelectionCalibration> out;
  const CalibrationSelection first = DefaultSelection(directory);
  for (CalibrationSelection selection :
       {first, first == CalibrationSelection::kAll ? CalibrationSelection::kQuasiStatic
                                                   : CalibrationSelection::kAll}) {
    const std::string folder = SelectionFolder(directory, model, selection);
    if (!fs::exists(fs::path(directory) / folder / "fit_status.toml") &&
        !fs::exists(fs::path(directory) / folder / "parameters.csv")) {
      continue;
    }
    out.push_back({selection, folder, selection == first});
  }
  return out;
}

std::string SelectionParameter::Verdict() const {
  if (profile == "flat") return "undetermined (profile flat)";
  if (status == "undetermined") return "undetermined (fixed at its start value)";
  if (status == "at_bound") return "at a bound";
  return status;
}

std::string SelectionParameter::ValueText() const {
  if (low && high) return fmt::format("{:.5g} [{:.5g}, {:.5g}]", value, *low, *high);
  return fmt::format("{:.5g}", value);
}

SelectionComparison CompareSelections(const std::string& directory,
                                      const std::vector<std::string>& models) {
  SelectionComparison comparison;
  for (const std::string& model : models) {
    const std::string all =
        (fs::path(directory) / SelectionFolder(directory, model, CalibrationSelection::kAll))
            .string();
    const std::string quasi =
        (fs::path(directory) /
         SelectionFolder(directory, model, CalibrationSelection::kQuasiStatic))
            .string();
    if (!fs::exists(all + "/parameters.csv") || !fs::exists(quasi + "/parameters.csv")) continue;
    std::vector<std::string> units_all, units_quasi;
    const auto a = ReadParameters(all + "/parameters.csv", &units_all);
    const auto q = ReadParameters(quasi + "/parameters.csv", &units_quasi);
    comparison.models.push_back(model);
    comparison.fit_status_all.push_back(FitStatusOf(all + "/fit_status.toml"));
    comparison.fit_status_quasi_static.push_back(FitStatusOf(quasi + "/fit_status.toml"));
    // The parameters in the paper-rate file's order, then any only in the other.
    for (size_t k = 0; k < a.size(); ++k) {
      SelectionComparisonRow row{model, a[k].first, units_all[k], a[k].second, std::nullopt};
      for (size_t j = 0; j < q.size(); ++j) {
        if (q[j].first != a[k].first) continue;
        row.quasi_static = q[j].second;
        if (row.units.empty()) row.units = units_quasi[j];
      }
      comparison.rows.push_back(row);
    }
    for (size_t j = 0; j < q.size(); ++j) {
      bool seen = false;
      for (const auto& p : a) seen = seen || p.first == q[j].first;
      if (!seen) {
        comparison.rows.push_back({model, q[j].first, units_quasi[j], std::nullopt, q[j].second});
      }
    }
  }
  return comparison;
}

std::string ParametersBySelectionCsv(const SelectionComparison& comparison) {
  std::string csv = "model,parameter,units";
  for (const char* s : {"all", "quasi_static"}) {
    csv += fmt::format(
        ",{0}_value,{0}_low,{0}_high,{0}_interval,{0}_status,{0}_profile,{0}_verdict", s);
  }
  csv += ",fit_status_all,fit_status_quasi_static\n";
  for (const SelectionComparisonRow& row : comparison.rows) {
    csv += row.model + "," + row.parameter + "," + row.units;
    for (const std::optional<SelectionParameter>& p : {row.all, row.quasi_static}) {
      if (!p) {
        csv += ",,,,,,,";
        continue;
      }
      csv += fmt::format(",{:.10g},{},{},{},{},{},{}", p->value, Number(p->low), Number(p->high),
                         p->interval, p->status, p->profile, p->Verdict());
    }
    size_t m = 0;
    while (comparison.models[m] != row.model) ++m;
    csv += "," + comparison.fit_status_all[m] + "," + comparison.fit_status_quasi_static[m] + "\n";
  }
  return csv;
}

std::string WriteParametersBySelection(const std::string& directory,
                                       const std::vector<std::string>& models) {
  const fs::path path = fs::path(directory) / kParametersBySelectionFile;
  const SelectionComparison comparison = CompareSelections(directory, models);
  if (comparison.empty()) {
    fs::remove(path);
    return "";
  }
  WriteTextFileAtomically(path.string(), ParametersBySelectionCsv(comparison));
  return path.string();
}

}  // namespace granasym::analysis
