#include "analysis/rate_cases.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "analysis/rate_files.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/statistics.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "study/case_record.h"
#include "study/study_folder.h"

namespace granasym::analysis {
using study::CaseRecord;
using study::FigureSet;
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

// The rate case of `row` (a detector stage of a finished case) into
// `cases`: a drained triaxial stage or a strain path (others are left out).
void ReadRateCase(const std::string& directory, const StateRow& row, RateCases* cases) {
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
  if (index == stages.size()) return;
  const std::string group = dem::StageGroup(index);
  const auto canonical = CanonicalLines(dem::ReadProvenance(file).scene_canonical);
  const double modulus = CanonicalNumber(canonical, "material.youngs_modulus_mpa").value_or(kNaN);
  if (file.HasAttribute(group, dem::record::kStageAxialStrainRate)) {
    DrainedState d = FromRow<DrainedState>(row);  // a drained triaxial stage
    d.youngs_modulus_mpa = modulus;
    // Keys of the analysis' maps, so never NaN: a stiffness ratio absent
    // (Hertz–Mindlin has none) and a time-step fraction absent (a fixed time
    // step, Scene::Canonical) read as 0.
    d.local_damping = CanonicalNumber(canonical, "material.local_damping").value_or(0.0);
    d.stiffness_ratio = CanonicalNumber(canonical, "material.stiffness_ratio").value_or(0.0);
    d.time_step_fraction = CanonicalNumber(canonical, "numerics.time_step_fraction").value_or(0.0);
    d.radial_stress_kpa = file.ReadDoubleAttribute(group, dem::record::kStageRadialStressKpa);
    d.axial_strain_rate = file.ReadDoubleAttribute(group, dem::record::kStageAxialStrainRate);
    cases->drained.push_back(d);
    return;
  }
  if (!file.HasAttribute(group, dem::record::kStageStretchingRate))
    return;  // neither a strain path nor a drained triaxial stage
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
  s.start_p_kpa = parent.empty()
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
  cases->states.push_back(s);
}

}  // namespace

bool ServesRateStudy(const std::string& figures) {
  return FigureSet::Parse(figures, "the state table", "figures").ServesRateStudy();
}

RateCases ReadRateCases(const std::string& directory, const std::vector<StateRow>& rows) {
  RateCases cases;
  for (const StateRow& row : study::WithoutEnsembleRows(rows)) {
    if (!ServesRateStudy(row.figures)) continue;
    cases.any = true;
    if (row.status == TableStatus::kNoResult || row.stage.empty()) continue;
    ReadRateCase(directory, row, &cases);
  }
  return cases;
}

std::vector<std::string> QuasiStaticCompanions(const std::string& directory,
                                               const std::vector<StateRow>& rows,
                                               const RateStudy& study,
                                               const QuasiStaticSelection& selection) {
  std::vector<std::string> companions;
  std::set<std::string> seen(selection.cases.begin(), selection.cases.end());
  seen.insert(selection.drained_cases.begin(), selection.drained_cases.end());
  auto add = [&](const std::string& name) {
    if (seen.insert(name).second) companions.push_back(name);
  };
  bool isotropic = false;  // a rate case of the selection is a ψ_ε = 0° path
  for (const RateState& s : study.states) {
    if (std::abs(s.psi_epsilon_deg) < 1e-6 &&
        std::find(selection.cases.begin(), selection.cases.end(), s.case_name) !=
            selection.cases.end()) {
      isotropic = true;
    }
  }
  const std::optional<std::string> ncl = study::StudyNclCase(directory);
  for (const StateRow& row : study::WithoutEnsembleRows(rows)) {
    if (ServesRateStudy(row.figures) || row.status == TableStatus::kNoResult || row.stage.empty() ||
        seen.count(row.case_name)) {
      continue;
    }
    if (!isotropic && ncl && row.case_name == *ncl) {
      add(row.case_name);
      continue;
    }
    const fs::path result = fs::path(directory) / "cases" / row.case_id / "result.h5";
    if (!fs::exists(result)) continue;
    const Hdf5File file = Hdf5File::OpenRead(result.string());
    const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
    for (size_t k = 0; k < stages.size(); ++k) {
      if (stages[k].name != row.stage) continue;
      const std::string group = dem::StageGroup(k);
      const auto canonical = CanonicalLines(dem::ReadProvenance(file).scene_canonical);
      const double modulus =
          CanonicalNumber(canonical, "material.youngs_modulus_mpa").value_or(kNaN);
      if (modulus != selection.youngs_modulus_mpa ||
          !file.HasAttribute(group, dem::record::kStageRateRule) ||
          FromString<dem::RateRule>(file.ReadStringAttribute(group, dem::record::kStageRateRule)) !=
              dem::RateRule::kInertial) {
        break;
      }
      const double inertial =
          file.ReadDoubleAttribute(group, dem::record::kStageRateInertialNumber);
      if (inertial <= selection.inertial_number * (1 + 1e-9)) add(row.case_name);
      break;
    }
  }
  return companions;
}

std::optional<RateStudy> WriteRateStudy(const std::string& directory,
                                        const std::vector<StateRow>& rows,
                                        const RateStudyOptions& options) {
  RateCases cases = ReadRateCases(directory, rows);
  if (!cases.any) {
    RemoveRateFiles(directory);
    return std::nullopt;
  }
  RateStudy study = RateStudy::Analyse(std::move(cases.states), options);
  study.drained = DrainedStudy::Analyse(std::move(cases.drained), options);
  WriteRateFiles(directory, study);
  return study;
}

}  // namespace granasym::analysis
