// Asymptotic states (Gudehus & Mašín 2009; paper Sec. 2): the stress ratio and
// OCR that proportional stretching at ψ_ε approaches from any initial state.
//
// Analytic for the hypoplastic clay (Mašín & Herle 2005, SPEC §6.1): every
// stress direction ψ_σ maps to ψ_ε of D̂ ∝ −𝔸⁻¹:N and to OCR = 2 (f_d^SBS)^(−1/α);
// inverted for a given ψ_ε by bracketing and bisection over the admissible
// ψ_σ ∈ (−atan(1/√2), atan √2) (σ_a → 0 and σ_r → 0).
// By integration for any model: proportional stretching until
// |dψ_σ/ds| + |d ln OCR/ds| (per unit strain path s) falls below a tolerance,
// found exactly by root finding.
#pragma once

#include <string>
#include <vector>

#include "constitutive/element_driver.h"
#include "constitutive/hypoplastic_clay.h"

namespace granasym {

struct AsymptoticState {
  double psi_epsilon = 0.0;   // rad
  double psi_sigma = 0.0;     // rad
  double ocr = 0.0;           // p_e*/p
  double stress_ratio = 0.0;  // q/p
};

// ψ_σ → (ψ_ε, OCR). Returns false outside the model's domain.
bool AnalyticAsymptoteForStress(const HypoplasticClay& model, double psi_sigma,
                                AsymptoticState* state, std::string* why);
// ψ_ε → (ψ_σ, OCR) to 1e-13 rad in ψ_σ. Returns false when ψ_ε has no asymptote.
bool AnalyticAsymptoteForStretching(const HypoplasticClay& model, double psi_epsilon,
                                    AsymptoticState* state, std::string* why);
// `points` states evenly spaced in ψ_σ over the admissible range (ends excluded).
std::vector<AsymptoticState> AnalyticAsymptoteCurve(const HypoplasticClay& model, int points);
// The admissible ψ_ε range (rad) of the analytic asymptotes (its ends excluded).
void AnalyticStretchingRange(const HypoplasticClay& model, double* lowest, double* highest);

struct AsymptoteSearchOptions {
  ElementTestOptions element_test;
  // Stationarity: |dψ_σ/ds| + |d ln OCR/ds| below this (per unit strain path).
  // For London clay 1e-7 puts ψ_σ and OCR within about 1e-9 of the analytic
  // asymptote (the approach is exponential in strain, rate ≈ 20–30 per unit);
  // below about 1e-8 the measure reaches the integration noise floor.
  double tolerance = 1e-7;
  // Longest strain path ∫‖D‖dt before giving up.
  double max_strain_path = 60.0;
  AsymptoteSearchOptions() {
    element_test.integrator.relative_tolerance = 1e-10;
    element_test.integrator.absolute_tolerance = 1e-14;
  }
  bool IsValid(std::string* why) const;
};

struct IntegratedAsymptote {
  bool found = false;
  AsymptoticState state;
  double strain_path = 0.0;  // strain path needed
  // At the detection; after rescaling (ConstitutiveModel::ScaleState) these are
  // of the rescaled state, whose ψ_σ and OCR are those of the real one.
  double mean_stress = 0.0;  // kPa
  double void_ratio = 0.0;
  ElementTestSummary summary;
};

// Proportional stretching at ψ_ε from `initial` until the asymptote criterion holds.
IntegratedAsymptote IntegrateAsymptote(const ConstitutiveModel& model, const ModelState& initial,
                                       double psi_epsilon, const AsymptoteSearchOptions& options);

}  // namespace granasym
