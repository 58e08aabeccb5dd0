// The quasi-static states of a rate study (issue 10 §4) that `study
// calibrate` fits the models to, and the file that records them for the
// figures and the report (DIR/calibration/quasi_static.toml).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/rate_study.h"

namespace granasym::analysis {

// §4 (issue 10): the quasi-static states that `study calibrate` fits the
// models to in a rate study, and that figure rate (e) sets beside the
// paper-rate ones: the rate cases at one I* and the reference modulus. By
// default the smallest I* whose ψ_ε = 90° cases have usable states from at
// least two starts (so that it has a CSL); in a study without ψ_ε = 90° rate
// cases whose critical state comes from drained cases alone
// (studies/programmes/quasi_static_extension.toml), the smallest I* of its
// rate cases; `inertial_number` chooses it.
// With them, the drained triaxial cases of the reference modulus at the
// slowest axial rate of each σ_r that has usable states: the critical state
// under stress control, which the isochoric paths from loose NC states do
// not reach as I* → 0 (they liquefy).
// The other quasi-static selection (issue 36 §2), for a study without a rate
// study: the states whose I(d_max) lies below this bound, the upper end of
// the quasi-static regime of dense granular flows (I < 1e-3: GDR MiDi 2004,
// da Cruz et al. 2005), a decade below the DEM's rate_affected flag (1e-2,
// SPEC §8.3). `study calibrate --max-inertial-number` changes it.
inline constexpr double kQuasiStaticInertialNumber = 1e-3;

struct QuasiStaticSelection {
  double inertial_number = std::numeric_limits<double>::quiet_NaN();
  double youngs_modulus_mpa = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> cases;          // case names, each once, in the states' order
  std::vector<std::string> drained_cases;  // likewise, the drained cases
  // The study's other cases of the set (QuasiStaticCompanions in
  // analysis/rate_cases.h): cases that do not serve the rate study but run
  // at I* or slower, and the study's NCL where no rate case at I* is a
  // ψ_ε = 0° path.
  std::vector<std::string> other_cases;
  // Every case of the set: cases, drained_cases and other_cases.
  std::vector<std::string> AllCases() const;
  std::string reason;  // why there is none (empty when valid)
  bool valid() const { return !cases.empty(); }
};
// "the 16 rate cases at I* = 0.001, the 2 drained triaxial cases at the
// slowest axial rate of each σ_r and 3 other cases at I* or slower (ncl_qs,
// ...), E = 500 MPa": what the report and the figures say of a selection.
std::string SelectionText(const QuasiStaticSelection& s);
QuasiStaticSelection SelectQuasiStatic(const RateStudy& study,
                                       std::optional<double> inertial_number = std::nullopt);
// DIR/calibration/quasi_static.toml, written by `study calibrate` for a rate
// study: the selection its calibrations were fitted to.
inline constexpr char kQuasiStaticSelectionFile[] = "calibration/quasi_static.toml";
void WriteQuasiStaticSelection(const std::string& directory, const QuasiStaticSelection& s);
// The selection written there, or nullopt without the file (InputError when malformed).
std::optional<QuasiStaticSelection> ReadQuasiStaticSelection(const std::string& directory);

}  // namespace granasym::analysis
