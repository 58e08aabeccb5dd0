// Detection of the asymptotic state reached under proportional straining,
// with a stated criterion that is stored with every detected state.
#pragma once

#include <string>
#include <vector>

namespace granasym {
class CanonicalText;
class ConfigTable;
}  // namespace granasym

namespace granasym::dem {

// Asymptotic-state criterion (SPEC §5): over the last `window_strain` of
// accumulated strain ∫‖D‖dt, sampled every `sample_strain`,
//  (1) the fitted change of ψ_σ across the window is below psi_tolerance_deg,
//  (2) the change of ln p across each half of the window differs between the
//      halves by less than lnp_tolerance (d ln p/dε is stationary, so the
//      state moves parallel to an asymptotic line, or stays at constant p).
struct AsymptoteCriterion {
  double sample_strain = 2e-3;
  double window_strain = 0.1;
  double psi_tolerance_deg = 0.5;
  double lnp_tolerance = 0.02;
  std::string Describe() const;
  // Reads a [stage.asymptote] table (missing keys keep their defaults).
  static AsymptoteCriterion Parse(const ConfigTable& table);
  void Canonical(CanonicalText& text, const std::string& prefix) const;
};

class AsymptoteDetector {
 public:
  struct Sample {
    double strain;      // accumulated strain ∫‖D‖dt within the stage
    double psi_sigma;   // (rad)
    double log_p;       // ln(p / 1 kPa)
    double log_volume;  // ln(1 + e)
  };
  struct Result {
    bool detected = false;
    double psi_sigma = 0;            // mean over the window (rad)
    double psi_change_deg = 0;       // fitted change across the window
    double lnp_half_difference = 0;  // |Δln p (2nd half) − Δln p (1st half)|
    double slope_lnp = 0;            // d ln p / dε over the window
    double slope_lnv_lnp = 0;        // d ln(1+e) / d ln p over the window (−λ* on a line)
  };

  explicit AsymptoteDetector(AsymptoteCriterion criterion = {}) : criterion_(criterion) {}

  // Adds a sample; samples with p <= 0 restart the record (no contacts).
  void Add(const Sample& sample);
  // Evaluates the criterion over the last window.
  Result Evaluate() const;
  bool ready() const;  // a full window is available
  void Reset() { samples_.clear(); }

  const std::vector<Sample>& samples() const { return samples_; }
  void set_samples(std::vector<Sample> samples) { samples_ = std::move(samples); }
  const AsymptoteCriterion& criterion() const { return criterion_; }

 private:
  AsymptoteCriterion criterion_;
  std::vector<Sample> samples_;
};

}  // namespace granasym::dem
