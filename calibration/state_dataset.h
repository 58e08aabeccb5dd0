// Asymptotic states to calibrate against (SPEC §7): each a tuple
// (ψ_ε, p, e, ψ_σ) with its kind, its source and its weight and uncertainties.
//
// Kinds: the isotropic NCL (ψ_ε = 0), the CSL (ψ_ε = 90°), compression
// asymptotic states (0 < ψ_ε < 90°), normal extension lines (ψ_ε > 90°, and
// the extension side ψ_ε < 0), points of ASBS cross-sections (known ψ_σ, p, e,
// no ψ_ε), and isotropic unloading branches: the rows of ψ_ε = 180° stages and
// the reload rows of ψ_ε = 0° stages below the largest p reached before them
// (never NCL rows). Unloading points are not asymptotic states of the models:
// they give the starting value of κ* and, with weight > 0 and a known branch
// start (DEM files), a ln(1+e) residual each against the model integrated
// isotropically from the branch's start (CalibrationProblem).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "common/enum_names.h"

namespace granasym::calibration {

enum class StateKind { kNcl, kCsl, kCompression, kExtension, kAsbs, kUnloading };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::StateKind> {
  using K = calibration::StateKind;
  static constexpr EnumEntry<K> kEntries[] = {
      {K::kNcl, "ncl", "isotropic normal compression line (psi_epsilon = 0)"},
      {K::kCsl, "csl", "critical state line (psi_epsilon = 90 deg)"},
      {K::kCompression, "compression", "asymptotic state with 0 < psi_epsilon < 90 deg"},
      {K::kExtension, "extension", "normal extension line (psi_epsilon > 90 deg or < 0)"},
      {K::kAsbs, "asbs", "point of an ASBS cross-section (no psi_epsilon)"},
      {K::kUnloading, "unloading",
       "isotropic unloading or reloading branch below the largest p before it (kappa*)"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// The name-table functions (common/enum_names.h) for this namespace's enums.
using granasym::FromString;
using granasym::ToString;

// The kind an asymptotic state at ψ_ε (rad) belongs to; `tolerance` (rad)
// decides what counts as exactly 0°, 90° and 180°.
StateKind KindFromStretching(double psi_epsilon, double tolerance);

struct AsymptoticStatePoint {
  StateKind kind = StateKind::kNcl;
  double psi_epsilon = 0.0;  // rad; for kAsbs points the source line's ψ_ε, or NaN when
                             // unknown (CSV); the fit does not use it for them
  double mean_stress = 0.0;  // p (kPa), > 0
  double void_ratio = 0.0;   // e
  double psi_sigma = 0.0;    // rad
  std::string source;        // e.g. "run.h5:/stages/003 (psi90)" or "lab.csv:12"
  double weight = 1.0;       // multiplies the squared residuals; 0: drawn, not fitted
  // One standard deviation of the measurement; residuals are divided by it.
  double psi_sigma_uncertainty = 0.0;  // rad, > 0
  double ln_volume_uncertainty = 0.0;  // of ln(1+e), > 0
  // Replicates averaged into this state (study tables), their 95 % interval
  // half-widths (NaN below two replicates or when not averaged) and the
  // source's own OCR against its own NCL (study tables; NaN when not given).
  int replicates = 1;
  double psi_sigma_ci95 = std::numeric_limits<double>::quiet_NaN();  // rad
  double ln_volume_ci95 = std::numeric_limits<double>::quiet_NaN();
  double source_ocr = std::numeric_limits<double>::quiet_NaN();
  // The DEM's rate at the state (study tables and DEM results; NaN when the
  // source does not say): the inertial numbers of the smallest and largest
  // grains, the largest over the replicates averaged into the state, and
  // the validity flags of its rows (their union, ';'-separated, e.g.
  // "rate_affected;overlap_above_2pct").
  double inertial_number_dmin = std::numeric_limits<double>::quiet_NaN();
  double inertial_number_dmax = std::numeric_limits<double>::quiet_NaN();
  std::string flags;
  // Unloading points: the state the branch starts from (p in kPa, e), where
  // the model is started to predict the point's e; NaN when unknown (CSV).
  double branch_start_p = std::numeric_limits<double>::quiet_NaN();
  double branch_start_e = std::numeric_limits<double>::quiet_NaN();

  // Whether the point is an asymptotic state (unloading points are not).
  bool IsAsymptotic() const { return kind != StateKind::kUnloading; }
  // Whether its residuals enter the objective (asymptotic, weight > 0).
  bool IsFitted() const { return IsAsymptotic() && weight > 0; }
  // Whether it is an unloading point whose ln(1+e) residual enters the
  // objective (weight > 0 and a known branch start).
  bool IsFittedUnloading() const {
    return kind == StateKind::kUnloading && weight > 0 && branch_start_p > 0 && branch_start_e > 0;
  }
  // Whether `flags` holds `flag`.
  bool HasFlag(const std::string& flag) const;
  // Whether its ψ_ε is known (all asymptotic kinds except kAsbs).
  bool HasStretching() const { return kind != StateKind::kAsbs && kind != StateKind::kUnloading; }
};

struct StateDataset {
  std::string name;    // from the calibration file or the file name
  std::string origin;  // file read
  std::vector<AsymptoticStatePoint> points;
  std::vector<std::string> warnings;  // e.g. stages without a detected asymptote

  size_t Count(StateKind kind) const;
  // Throws InputError naming the dataset, the point's source and the bad field
  // for NaN/infinite values, p ≤ 0, e ≤ 0, ψ_σ outside (−35.26°, 54.74°),
  // negative weights or non-positive uncertainties.
  void Validate() const;
};

// Checks the per-dataset settings that the CSV and DEM readers share; `why`
// names the offending setting and its valid range.
bool ValidReaderSettings(double kind_tolerance_deg, double psi_sigma_uncertainty_deg,
                         double ln_volume_uncertainty, double weight, std::string* why);

}  // namespace granasym::calibration
