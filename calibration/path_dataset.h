// Whole DEM paths to calibrate against (issue 36 §3): the model is
// integrated along the DEM's own recorded strain path from the DEM's own
// initial state, and the misfit is over the whole curve, not only its end.
//
// A path is a run of consecutive stages of a granasym DEM result file
// (dem/run_record_names.h: /series eps_a, eps_r, sigma_a_kpa, sigma_r_kpa, e),
// resampled on the strain path length s = ∫‖dε‖ (‖dε‖² = dε_a² + 2 dε_r²) at
// `points` evenly spaced values plus every stage boundary (the reversals of
// an unload–reload cycle are kept exactly). Sample 0 is the initial state:
// the model starts there at the DEM's σ_a, σ_r and e (when that state lies
// outside the model's state boundary surface for the parameters tried, at
// the same stress on it: OCR = 1; the e residuals then show the offset).
//
// Control between two samples (PathControl):
//   strain   ε_a and ε_r prescribed (isotropic cycles, isochoric paths,
//            proportional paths): the model's e follows the strain, so only
//            the stress is compared;
//   drained  ε_a prescribed and σ_r following the DEM's (held on a drained
//            triaxial path): stress and e are compared.
// `auto` takes drained for a path of kind drained, else when σ_r varies by
// less than 2 % of its mean over the path while σ_a varies by more than 10 %,
// else strain.
//
// Residuals per sample k ≥ 1 (CalibrationProblem), each · √(weight / n)
// with n the number of samples after the first, so that a path counts as
// `weight` states whatever its resolution:
//   (ln p_model − ln p_DEM) / σ_ln p
//   (ψ_σ,model − ψ_σ,DEM) / σ_ψ
//   (ln(1+e_model) − ln(1+e_DEM)) / σ_v       (drained control only)
// A model integration that stops early (limit point, inadmissible state)
// keeps its last valid state for the remaining samples, so that the cost
// stays finite and grows with what is missed; PathPrediction says how far
// it got.
#pragma once

#include <string>
#include <vector>

#include "common/enum_names.h"
#include "constitutive/constitutive_model.h"

namespace granasym::calibration {

enum class PathControl { kAuto, kStrain, kDrained };
// What a path is for (reports, figures and the study's datasets).
enum class PathKind { kAuto, kUnloadReload, kIsochoric, kDrained, kCycling, kGeneral };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::PathControl> {
  using C = calibration::PathControl;
  static constexpr EnumEntry<C> kEntries[] = {
      {C::kAuto, "auto", "drained where sigma_r is held and sigma_a is not, else strain"},
      {C::kStrain, "strain", "axial and radial strain prescribed"},
      {C::kDrained, "drained", "axial strain prescribed, sigma_r following the DEM's"},
  };
};
template <>
struct EnumNames<calibration::PathKind> {
  using K = calibration::PathKind;
  static constexpr EnumEntry<K> kEntries[] = {
      {K::kAuto, "auto", "from the path: drained, isochoric, isotropic (unload_reload) or general"},
      {K::kUnloadReload, "unload_reload", "isotropic unloading-reloading cycles (kappa*)"},
      {K::kIsochoric, "isochoric", "undrained (constant volume) shearing (r or nu, alpha)"},
      {K::kDrained, "drained", "drained triaxial shearing (alpha, beta)"},
      {K::kCycling, "cycling", "cycling to the densest state (e_d0)"},
      {K::kGeneral, "general", "any other strain path"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

using granasym::FromString;
using granasym::ToString;

// One point of a path, compression positive.
struct PathSample {
  double strain_path = 0.0;  // s = ∫‖dε‖ from the path's start
  double axial_strain = 0.0, radial_strain = 0.0;
  double axial_stress = 0.0, radial_stress = 0.0;  // kPa
  double void_ratio = 0.0;
  double MeanStress() const { return (axial_stress + 2.0 * radial_stress) / 3.0; }
  double PsiSigma() const;  // rad
};

struct PathDataset {
  std::string name;    // from the calibration file
  std::string origin;  // file read
  std::string source;  // e.g. "run.h5:/stages/003-006 (unload_1 .. reload_2)"
  PathKind kind = PathKind::kGeneral;
  PathControl control = PathControl::kStrain;  // never kAuto once read
  std::vector<PathSample> samples;             // [0]: the initial state
  double weight = 1.0;                         // 0: drawn, not fitted
  double ln_p_uncertainty = 0.02;              // of ln p
  double psi_sigma_uncertainty = 0.0;          // rad, > 0
  double ln_volume_uncertainty = 0.002;        // of ln(1+e)
  std::vector<std::string> warnings;

  // Residuals per sample after the first: 2 (strain control) or 3 (drained).
  int ResidualsPerSample() const { return control == PathControl::kDrained ? 3 : 2; }
  // Fitted residuals: 0 for weight 0.
  int NumResiduals() const {
    return weight > 0 ? ResidualsPerSample() * static_cast<int>(samples.size() - 1) : 0;
  }
  // Throws InputError naming the path for fewer than 3 samples, non-finite
  // or non-positive stresses and void ratios, a strain path that does not
  // grow, kAuto left, negative weights or non-positive uncertainties.
  void Validate() const;
};

// The control and kind `auto` resolves to for `samples` (see the header).
PathControl DetectControl(const std::vector<PathSample>& samples);
PathKind DetectKind(const std::vector<PathSample>& samples, PathControl control);

// `raw` resampled on the strain path length: `points` evenly spaced values
// of s (linear interpolation between rows) plus the rows in `keep` (stage
// boundaries), the first and the last row. `raw[i].strain_path` must not
// decrease.
std::vector<PathSample> ResampleOnStrain(const std::vector<PathSample>& raw, int points,
                                         const std::vector<size_t>& keep);

struct PathReadOptions {
  // Names of the stages the path runs through, consecutive in the file (the
  // first one's first row is the initial state); empty: not a valid choice.
  std::vector<std::string> stages;
  PathControl control = PathControl::kAuto;
  PathKind kind = PathKind::kAuto;
  int points = 40;  // evenly spaced in s, plus the stage boundaries
  double weight = 1.0;
  double ln_p_uncertainty = 0.02;
  double psi_sigma_uncertainty_deg = 1.0;
  double ln_volume_uncertainty = 0.002;
  bool IsValid(std::string* why) const;
};

// The path of `options.stages` in the DEM result file `path`. Throws
// InputError naming the file and the stage for a missing stage (with the
// stages the file has), stages that are not consecutive, a stage the run
// failed in, or series without the strain and stress columns.
PathDataset ReadPathDem(const std::string& path, const std::string& name,
                        const PathReadOptions& options);

// The model along a path: per sample (the first included) p, ψ_σ and e.
struct PathPrediction {
  std::vector<double> mean_stress, psi_sigma, void_ratio;  // kPa, rad, 1
  int reached = 0;           // samples reached by the integration (≥ 1)
  bool start_moved = false;  // the DEM's start was outside the model's SBS
  std::string message;       // why the integration stopped early, if it did
  bool Complete(const PathDataset& path) const {
    return reached == static_cast<int>(path.samples.size());
  }
};

// Integrates `model` along `path` (see the header); false, with the reason,
// only when no start state can be made (then nothing else is filled).
bool PredictPath(const ConstitutiveModel& model, const PathDataset& path,
                 PathPrediction* prediction, std::string* why);

// The model's ln(1+e) on an isotropic path from (p0, e0) through the mean
// stresses `targets` (kPa, in the order given: e.g. the rows of an
// unloading branch); false with the reason when the integration fails.
bool PredictIsotropicBranch(const ConstitutiveModel& model, double p0, double e0,
                            const std::vector<double>& targets, std::vector<double>* ln_volume,
                            std::string* why);

}  // namespace granasym::calibration
