// Synthetic whole paths (issue 36 §3): a model's own element tests along
// DEM-like paths (Fig. 9 unload–reload cycles, Fig. 11 isochoric paths from
// NC and OC states, Fig. 12 drained triaxial, drained cycling), recorded as
// the DEM records them and resampled on strain as calibration/path_dataset.h does.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "calibration/path_dataset.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "constitutive/element_driver.h"

namespace granasym::calibration::testing {

// The records of `result` as raw path rows (strain path from the strain
// increments), and the indices of each stage's last row.
inline std::vector<PathSample> RecordsAsRows(const ElementTestResult& result,
                                             std::vector<size_t>* stage_ends) {
  std::vector<PathSample> rows;
  double s = 0;
  for (size_t i = 0; i < result.history.size(); ++i) {
    const ElementTestRecord& r = result.history[i];
    PathSample sample;
    sample.axial_strain = r.strain[0];
    sample.radial_strain = 0.5 * (r.strain[1] + r.strain[2]);
    const AxisymmetricStress stress = RecordStress(r);
    sample.axial_stress = stress.axial;
    sample.radial_stress = stress.radial;
    sample.void_ratio = r.void_ratio;
    if (!rows.empty()) {
      const double da = sample.axial_strain - rows.back().axial_strain;
      const double dr = sample.radial_strain - rows.back().radial_strain;
      const double ds = std::sqrt(da * da + 2 * dr * dr);
      if (!(ds > 0)) continue;
      s += ds;
    }
    sample.strain_path = s;
    rows.push_back(sample);
    if (stage_ends && (i + 1 == result.history.size() || result.history[i + 1].stage != r.stage)) {
      stage_ends->push_back(rows.size() - 1);
    }
  }
  return rows;
}

// An element test whose stages record `points` rows each over the part they
// run: stages ended by a stop are run again with the duration they took.
inline ElementTestResult RunRecorded(const ConstitutiveModel& model, const ModelState& start,
                                     std::vector<LoadingStage> stages, int points) {
  const ElementTest test(model, ElementTestOptions());
  ElementTestResult result = test.Run(start, stages);
  GRANASYM_CHECK(result.summary.success()) << result.summary.Report();
  for (size_t k = 0; k < stages.size(); ++k) {
    stages[k].duration = 1.000001 * result.summary.stages[k].integration.final_time;
    stages[k].output_points = points;
  }
  result = test.Run(start, stages);
  GRANASYM_CHECK(result.summary.success()) << result.summary.Report();
  return result;
}

// The model's own path from `start` through `stages`, as a path dataset.
inline PathDataset ModelPath(const ConstitutiveModel& model, const std::string& name,
                             const ModelState& start, std::vector<LoadingStage> stages,
                             PathControl control, PathKind kind, int points = 40) {
  const ElementTestResult result = RunRecorded(model, start, stages, 200);
  std::vector<size_t> ends;
  const std::vector<PathSample> rows = RecordsAsRows(result, &ends);
  PathDataset path;
  path.name = name;
  path.origin = "synthetic";
  path.source = name;
  path.samples = ResampleOnStrain(rows, points, ends);
  path.control = control;
  path.kind = kind;
  path.psi_sigma_uncertainty = 1.0 * kDegree;
  path.Validate();
  return path;
}

inline LoadingStage IsotropicTo(double p, bool loading) {
  LoadingStage stage = LoadingStage::Proportional(loading ? 0.0 : kPi, 1.0, 50.0);
  stage.stops.push_back({StopKind::kMeanStress, p});
  return stage;
}

// Fig. 9: from the NCL at 200 kPa, unload to 50, reload to 500, unload to
// 100, reload to 1000 kPa.
inline PathDataset UnloadReloadCycles(const ConstitutiveModel& model) {
  return ModelPath(model, "cycles", InitialStateFromOcr(model, 200.0, 0.0, 1.0),
                   {IsotropicTo(50, false), IsotropicTo(500, true), IsotropicTo(100, false),
                    IsotropicTo(1000, true)},
                   PathControl::kStrain, PathKind::kUnloadReload);
}

// Fig. 11: isochoric shearing from an isotropic state at p and OCR.
inline PathDataset IsochoricPath(const ConstitutiveModel& model, double p, double ocr,
                                 double axial_strain) {
  return ModelPath(
      model, fmt::format("isochoric p{} ocr{}", p, ocr), InitialStateFromOcr(model, p, 0.0, ocr),
      {LoadingStage::Isochoric(1.0, axial_strain)}, PathControl::kStrain, PathKind::kIsochoric);
}

// Fig. 12: drained triaxial (σ_r held) from an isotropic state at p and OCR.
inline PathDataset DrainedPath(const ConstitutiveModel& model, double p, double ocr,
                               double axial_strain) {
  return ModelPath(model, fmt::format("drained p{} ocr{}", p, ocr),
                   InitialStateFromOcr(model, p, 0.0, ocr),
                   {LoadingStage::ConstantRadialStress(1.0, axial_strain)}, PathControl::kDrained,
                   PathKind::kDrained);
}

// A stage of a DEM result file written by WriteDemPathFile.
struct DemStage {
  std::string name;
  int first = 0, last = 0;                // rows
  std::string type = "strain_path";       // or "triaxial"
  double psi_epsilon_deg = std::nan("");  // attribute written when finite
};

// A DEM result file (the layout of dem/run_record_names.h) holding `rows` as
// its series and `stages`.
inline void WriteDemPathFile(const std::string& file_path, const std::vector<PathSample>& rows,
                             const std::vector<DemStage>& stages) {
  std::vector<double> a, r, sa, sr, e, p, psi;
  for (const PathSample& s : rows) {
    a.push_back(s.axial_strain);
    r.push_back(s.radial_strain);
    sa.push_back(s.axial_stress);
    sr.push_back(s.radial_stress);
    e.push_back(s.void_ratio);
    p.push_back(s.MeanStress());
    psi.push_back(s.PsiSigma() / kDegree);
  }
  Hdf5File file = Hdf5File::CreateAtomic(file_path);
  file.WriteDoubles("/series/eps_a", a, "1");
  file.WriteDoubles("/series/eps_r", r, "1");
  file.WriteDoubles("/series/sigma_a_kpa", sa, "kPa");
  file.WriteDoubles("/series/sigma_r_kpa", sr, "kPa");
  file.WriteDoubles("/series/e", e, "1");
  file.WriteDoubles("/series/p_kpa", p, "kPa");
  file.WriteDoubles("/series/psi_sigma_deg", psi, "deg");
  file.CreateGroup("/stages");
  for (size_t k = 0; k < stages.size(); ++k) {
    const std::string g = fmt::format("/stages/{:03d}", k);
    file.CreateGroup(g);
    file.SetAttribute(g, "name", stages[k].name);
    file.SetAttribute(g, "type", stages[k].type);
    file.SetAttribute(g, "first_row", int64_t{stages[k].first});
    file.SetAttribute(g, "last_row", int64_t{stages[k].last});
    if (std::isfinite(stages[k].psi_epsilon_deg)) {
      file.SetAttribute(g, "psi_epsilon_deg", stages[k].psi_epsilon_deg);
    }
  }
  file.Commit();
}

// A model's element test written as a DEM result file, one stage per
// loading stage, named `names`, with `types` and ψ_ε (NaN: none) per stage.
inline void WriteModelRun(const ConstitutiveModel& model, const std::string& file,
                          const ModelState& start, const std::vector<LoadingStage>& stages,
                          const std::vector<std::string>& names,
                          const std::vector<std::string>& types = {},
                          const std::vector<double>& psi_epsilons_deg = {}) {
  const ElementTestResult result = RunRecorded(model, start, stages, 60);
  std::vector<size_t> ends;
  const std::vector<PathSample> rows = RecordsAsRows(result, &ends);
  std::vector<DemStage> written;
  int first = 0;
  for (size_t k = 0; k < ends.size(); ++k) {
    DemStage stage{names[k], first, static_cast<int>(ends[k])};
    if (k < types.size()) stage.type = types[k];
    if (k < psi_epsilons_deg.size()) stage.psi_epsilon_deg = psi_epsilons_deg[k];
    written.push_back(stage);
    first = static_cast<int>(ends[k]) + 1;
  }
  WriteDemPathFile(file, rows, written);
}

}  // namespace granasym::calibration::testing
