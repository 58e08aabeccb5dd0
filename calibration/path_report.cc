// Whole paths in the calibration's summary and plot data.
#include "calibration/path_report.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "common/state_measures.h"
#include "common/text_file.h"

namespace granasym::calibration {

std::string PathSummaryText(const CalibrationProblem& problem, const std::vector<double>& values) {
  std::string s;
  int unloading = 0;
  double ss_unloading = 0;
  std::vector<PointResidual> points;
  std::string why;
  if (problem.Evaluate(values, &points, &why)) {
    for (const PointResidual& r : points) {
      if (!problem.datasets()[r.dataset].points[r.point].IsFittedUnloading()) continue;
      ++unloading;
      ss_unloading += r.ln_volume_residual * r.ln_volume_residual;
    }
  }
  if (unloading > 0) {
    s += fmt::format(
        "  unloading points: {} fitted against the model driven isotropically from each "
        "branch's start: RMS ln(1+e) {:.4g}\n",
        unloading, std::sqrt(ss_unloading / unloading));
  }
  if (problem.paths().empty()) return s;
  std::vector<PathPrediction> predictions;
  if (!problem.EvaluatePaths(values, &predictions, &why)) {
    return s + "  paths: the model cannot be run along them: " + why + "\n";
  }
  for (size_t k = 0; k < problem.paths().size(); ++k) {
    const PathDataset& path = problem.paths()[k];
    const PathPrediction& m = predictions[k];
    double ss_p = 0, ss_psi = 0, ss_v = 0;
    const size_t n = path.samples.size() - 1;
    for (size_t i = 1; i < path.samples.size(); ++i) {
      const PathSample& d = path.samples[i];
      ss_p += std::pow(std::log(m.mean_stress[i] / d.MeanStress()), 2);
      ss_psi += std::pow((m.psi_sigma[i] - d.PsiSigma()) / kDegree, 2);
      ss_v += std::pow(std::log1p(m.void_ratio[i]) - std::log1p(d.void_ratio), 2);
    }
    s += fmt::format(
        "  path '{}' ({}, {} control, {} samples, weight {:g}): RMS ln p {:.4g}, "
        "psi_sigma {:.3g} deg",
        path.name, ToString(path.kind), ToString(path.control), path.samples.size(), path.weight,
        std::sqrt(ss_p / n), std::sqrt(ss_psi / n));
    if (path.control == PathControl::kDrained) {
      s += fmt::format(", ln(1+e) {:.4g}", std::sqrt(ss_v / n));
    }
    if (m.start_moved) s += "; the DEM's start lies beyond the model's NCL: started on it";
    if (!m.Complete(path)) {
      s += fmt::format("; the model stopped after {} of {} samples ({})", m.reached,
                       path.samples.size(), m.message);
    }
    s += "\n";
  }
  return s;
}

void WritePathPlotData(const CalibrationProblem& problem, const std::vector<double>& values,
                       const std::string& folder) {
  if (problem.paths().empty()) return;
  std::filesystem::create_directories(folder);
  std::vector<PathPrediction> predictions;
  std::string why;
  if (!problem.EvaluatePaths(values, &predictions, &why)) return;
  std::string list;
  for (size_t k = 0; k < problem.paths().size(); ++k) {
    const PathDataset& path = problem.paths()[k];
    const PathPrediction& m = predictions[k];
    std::string text =
        "strain_path,dem_p_kpa,dem_q_kpa,dem_q_over_p,dem_e,model_p_kpa,model_q_kpa,"
        "model_q_over_p,model_e\n";
    for (size_t i = 0; i < path.samples.size(); ++i) {
      const PathSample& d = path.samples[i];
      const double model_ratio = StressRatio(m.psi_sigma[i]);
      text += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                          d.strain_path, d.MeanStress(), d.axial_stress - d.radial_stress,
                          (d.axial_stress - d.radial_stress) / d.MeanStress(), d.void_ratio,
                          m.mean_stress[i], model_ratio * m.mean_stress[i], model_ratio,
                          m.void_ratio[i]);
    }
    const std::string file = fmt::format("path_{}.csv", k + 1);
    WriteTextFileAtomically(folder + "/" + file, text);
    list +=
        fmt::format("{}\t{} ({})\t{}\n", file, path.name, ToString(path.kind), ToString(path.kind));
  }
  WriteTextFileAtomically(folder + "/paths.txt", list);
}

}  // namespace granasym::calibration
