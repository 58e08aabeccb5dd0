// Detection of the asymptotic state of a stage (SPEC §8.4), one criterion per
// kind of path, with stated tolerances that are stored with every record.
//
// Each kind looks at the last window of samples (taken every sample_strain of
// accumulated strain ∫‖D‖dt within the stage):
//  - isochoric (ψ_ε = 90°): over the last window_strain, the fitted changes
//    of ln p and of ψ_σ across the window are below lnp_tolerance and
//    psi_tolerance_deg (the critical state: p and ψ_σ stationary);
//  - compression (|ψ_ε| < 90°) and extension (|ψ_ε| > 90°): over the last
//    window_lnp of |Δ ln p| (or window_strain, whichever is shorter), the
//    fitted change of ψ_σ across the window is below psi_tolerance_deg and
//    the slope d ln(1+e)/d ln p of the two half-windows differs by less than
//    slope_tolerance relative to its mean (the state moves parallel to an
//    NCL or a normal extension line). The window in ln p finds compression
//    asymptotes at hundreds of kPa, where a window in strain spans decades
//    of p;
//    An extension asymptotic state is a proportional path towards the
//    origin (SPEC §8.4): p falls while ψ_σ stays. Since ln(1+e) rises at the
//    rate ψ_ε imposes, its slope is stationary when the fitted rate of ln p
//    is: the rates of the two half-windows differ by less than lnp_tolerance
//    (in ln p over half a window), which stays meaningful where p barely
//    moves (the dense flows of the paper's rate). Its windows count only
//    where every sample has p at or above floor_kpa (the valid range, SPEC
//    §8.3); the detector keeps the last window that held (last_held()), so
//    that a path which held and then fell below the floor keeps its state;
//  - stress-controlled (triaxial): over the last window_strain, ψ_ε from the
//    strain increments of the two half-windows (not the noisy instantaneous
//    rates) differs by less than psi_epsilon_tolerance_deg, the fitted
//    change of ln(1+e) across the window is below lnv_tolerance and that of
//    ψ_σ below psi_tolerance_deg: a sample still dilating is not asymptotic.
// Slopes are least-squares fits against the accumulated strain (noise-free),
// so noise in p does not bias them. Tolerance boundaries are strict.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/enum_names.h"

namespace granasym {
class CanonicalText;
class ConfigTable;
}  // namespace granasym

namespace granasym::dem {

// Which asymptote a stage can reach, from its type (Stage::path_kind()).
enum class PathKind { kIsochoric, kCompression, kExtension, kStressControlled };

// What became of a stage's asymptote.
enum class AsymptoteStatus { kDetected, kDrifting, kNotReached, kGas, kInvalid };

}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::PathKind> {
  static constexpr EnumEntry<dem::PathKind> kEntries[] = {
      {dem::PathKind::kIsochoric, "isochoric", "strain path with psi_epsilon = 90 deg"},
      {dem::PathKind::kCompression, "compression", "strain path with |psi_epsilon| < 90 deg"},
      {dem::PathKind::kExtension, "extension", "strain path with |psi_epsilon| > 90 deg"},
      {dem::PathKind::kStressControlled, "stress_controlled", "a stress-controlled stage"},
  };
};

template <>
struct granasym::EnumNames<granasym::dem::AsymptoteStatus> {
  static constexpr EnumEntry<dem::AsymptoteStatus> kEntries[] = {
      {dem::AsymptoteStatus::kDetected, "detected", "the criterion held over a full window"},
      {dem::AsymptoteStatus::kDrifting, "drifting",
       "a full window was available but the criterion did not hold at the stage end"},
      {dem::AsymptoteStatus::kNotReached, "not_reached", "the window never filled"},
      {dem::AsymptoteStatus::kGas, "gas", "a gas or liquefied state: no asymptotic state"},
      {dem::AsymptoteStatus::kInvalid, "invalid", "the stage failed a validity guard"},
  };
};

namespace granasym::dem {

// The kind of a strain path of direction ψ_ε (deg): isochoric within 1e-6
// deg of ±90°, compression inside, extension outside.
PathKind StrainPathKind(double psi_epsilon_deg);

// The criterion of a kind of path ([stage.asymptote]); see the file comment.
// The defaults (of For(kind)) were tuned on 3000-sphere runs with the
// paper's numerics (NC to 10 and 200 kPa, then ψ_ε = 20°, 45°, 70°, 90°,
// 120° and a drained triaxial; docs/guide/scenes.md): a window of 0.15 strain or 1.0 of
// ln p holds enough of the fluctuations of a small sample (p scatters by
// ±20 % on the critical state of 3000 spheres) that a stationary state is
// accepted within a few windows, while the transients (the drop of p on an
// isochoric path, the dilation of a triaxial test, ψ_σ still rising along a
// compression path) change by more than the tolerances.
struct AsymptoteCriterion {
  PathKind kind = PathKind::kIsochoric;
  double sample_strain = 5e-4;  // all kinds: strain between samples
  // Isochoric and stress-controlled: the window (0.15); compression and
  // extension: the longest window (0.3), for paths along which p changes slowly.
  double window_strain = 0.15;
  double window_lnp = 1.0;         // compression, extension: |Δ ln p| of the window
  double psi_tolerance_deg = 1.0;  // fitted change of ψ_σ across the window (every kind)
  // Isochoric: fitted change of ln p across the window; extension (0.4): change
  // of the fitted rate of ln p between the half-windows, over half a window.
  double lnp_tolerance = 0.05;
  double slope_tolerance = 0.1;  // compression: relative change of the slope d ln(1+e)/d ln p
  double psi_epsilon_tolerance_deg = 3.0;  // stress-controlled: ψ_ε(2nd half) − ψ_ε(1st half)
  double lnv_tolerance = 0.004;  // stress-controlled: fitted change of ln(1+e) across the window
  // Extension: the floor of the valid range (kPa); windows reaching below it
  // are not evaluated (SPEC §8.3, the paper's 0.5 kPa).
  double floor_kpa = 0.5;
  // Compression and extension: no window that starts before this much
  // accumulated strain of the stage counts (0: any). From a stiff start (a
  // quasi-static NC state) a proportional strain path first unloads or
  // loads elastically, where the stress path is proportional too: ψ_σ
  // stays while ln p falls by the whole window in ln p within 0.02 of strain,
  // long before the plastic asymptote. Recorded in a scene's canonical text
  // only when set.
  double transient_strain = 0.0;

  // The defaults of a kind.
  static AsymptoteCriterion For(PathKind kind);
  // One line: the kind, its window and tolerances.
  std::string Describe() const;
  // Reads a [stage.asymptote] table for a kind: the keys of that kind only
  // (others are reported as unknown), missing keys keep their defaults.
  static AsymptoteCriterion Parse(const ConfigTable& table, PathKind kind);
  void Canonical(CanonicalText& text, const std::string& prefix) const;
};

class AsymptoteDetector {
 public:
  struct Sample {
    double strain;      // accumulated strain ∫‖D‖dt within the stage
    double psi_sigma;   // (rad)
    double log_p;       // ln(p / 1 kPa)
    double log_volume;  // ln(1 + e)
    double eps_a = 0;   // axial logarithmic strain, compression positive
    double eps_r = 0;   // radial logarithmic strain
    double time = 0;    // simulated time (s): finds the output rows of the window
  };
  struct Result {
    // kDetected, kDrifting or kNotReached (the caller adds gas and invalid).
    AsymptoteStatus status = AsymptoteStatus::kNotReached;
    bool detected() const { return status == AsymptoteStatus::kDetected; }
    // The window evaluated (zero when none).
    double window_strain = 0;      // strain span
    double window_lnp = 0;         // |ln p(end) − ln p(start)|
    double window_start_time = 0;  // simulated time of its first sample (s)
    double window_end_time = 0;    // and of its last
    double window_end_strain = 0;  // accumulated strain of its last sample
    // The range of p over the window's samples (kPa); below_floor when an
    // extension window reaches below floor_kpa (it is then not evaluated).
    double p_min_kpa = 0, p_max_kpa = 0;
    bool below_floor = false;
    // The state: means over the window; ψ_ε from the strain increments.
    double psi_sigma = 0;  // (rad)
    double mean_stress_kpa = 0;
    double void_ratio = 0;
    double psi_epsilon = 0;  // (rad)
    double q_over_p = 0;
    // The measures of the criteria (those of other kinds are computed too).
    double psi_change_deg = 0;          // fitted change of ψ_σ across the window
    double lnp_change = 0;              // fitted change of ln p across the window
    double lnp_half_difference = 0;     // |Δln p (2nd half) − Δln p (1st half)|
    double slope_change = 0;            // relative change of d ln(1+e)/d ln p, 2nd vs 1st half
    double psi_epsilon_change_deg = 0;  // |ψ_ε (2nd half) − ψ_ε (1st half)|
    double lnv_change = 0;              // fitted change of ln(1+e) across the window
    double slope_lnp = 0;               // d ln p / dε over the window
    double slope_lnv_lnp = 0;           // d ln(1+e) / d ln p over the window (−λ* on a line)
  };

  explicit AsymptoteDetector(AsymptoteCriterion criterion = {}) : criterion_(criterion) {}

  // Adds a sample; samples with p <= 0 restart the record (no contacts).
  void Add(const Sample& sample);
  // Evaluates the criterion of the kind over the last window.
  Result Evaluate() const;
  // Extension: evaluates the last window and keeps it when it holds (call
  // after each Add); other kinds: nothing.
  void Track();
  // The last window that held (extension; nullopt when none has).
  const std::optional<Result>& last_held() const { return last_held_; }
  void set_last_held(std::optional<Result> held) { last_held_ = std::move(held); }
  bool ready() const;  // a full window is available
  void Reset() { samples_.clear(); }

  const std::vector<Sample>& samples() const { return samples_; }
  void set_samples(std::vector<Sample> samples) { samples_ = std::move(samples); }
  const AsymptoteCriterion& criterion() const { return criterion_; }

  // A window needs at least this many samples, a half-window three.
  static constexpr size_t kMinSamples = 8;

 private:
  // The first sample of the last window; samples_.size() when none is full.
  size_t WindowBegin() const;

  AsymptoteCriterion criterion_;
  std::vector<Sample> samples_;
  std::optional<Result> last_held_;
};

// A Result as numbers in a fixed order (a checkpoint keeps the last held
// window this way), and back; Unpack throws std::invalid_argument on a
// vector of the wrong length.
std::vector<double> PackResult(const AsymptoteDetector::Result& result);
AsymptoteDetector::Result UnpackResult(const std::vector<double>& values);

}  // namespace granasym::dem
