#include "analysis/quasi_static_selection.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "common/config.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace fs = std::filesystem;

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
    // No ψ_ε = 90° rate case at all, and drained cases: the critical state
    // is theirs, and the smallest I* of the rate cases sets the set.
    bool isochoric = false;
    for (const RateState& s : study.states) {
      isochoric = isochoric || std::abs(s.psi_epsilon_deg - 90) < 1e-6;
    }
    if (std::isnan(selection.inertial_number) && !isochoric && !rates.empty() &&
        !study.drained.states.empty()) {
      selection.inertial_number = *rates.begin();
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
  text +=
      "]\n# the study's other cases of the set: not rate cases, but run at I* or slower, and the "
      "study's NCL where no rate case at I* is a psi_epsilon = 0 deg path\nother_cases = [";
  for (size_t k = 0; k < s.other_cases.size(); ++k) {
    text += (k ? ", " : "") + TomlQuoted(s.other_cases[k]);
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
  if (table.Has("other_cases")) s.other_cases = table.GetStrings("other_cases");
  return s;
}

std::string SelectionText(const QuasiStaticSelection& s) {
  std::string others;
  for (const std::string& name : s.other_cases) others += (others.empty() ? "" : ", ") + name;
  return fmt::format(
      "the {} rate cases at I* = {:g}, the {} drained triaxial cases at the slowest axial rate of "
      "each σ_r{}, E = {:g} MPa",
      s.cases.size(), s.inertial_number, s.drained_cases.size(),
      others.empty()
          ? std::string()
          : fmt::format(" and {} other case{} at I* or slower ({})", s.other_cases.size(),
                        s.other_cases.size() == 1 ? "" : "s", others),
      s.youngs_modulus_mpa);
}

std::vector<std::string> QuasiStaticSelection::AllCases() const {
  std::vector<std::string> all = cases;
  all.insert(all.end(), drained_cases.begin(), drained_cases.end());
  all.insert(all.end(), other_cases.begin(), other_cases.end());
  return all;
}

}  // namespace granasym::analysis
