// The rate study (issue 10 §2, SPEC §8.2): asymptotic states of proportional
// paths driven at fixed inertial numbers I* (and at a constant ‖D‖, the
// paper's 167 1/s), from NC states at several p, with replicates. Per
// (E, ψ_ε, p_0, rate) it gives the replicate means with 95 % Student-t
// intervals; per (E, ψ_ε, p_0) the quasi-static limit, extrapolated as I → 0
// by the least-squares line y = a + b·I(d_max) through the states of the
// smallest I* (the small-I form of the μ(I) laws that the paper cites: da
// Cruz et al. 2005, its ref. [10], and Jop et al. 2006, ref. [29]); per
// (E, ψ_ε, rate) the line ln(1+e) = N − λ ln p of its asymptotic states (the
// NCL at ψ_ε = 0°, the CSL at 90°, the NEL beyond); and whether the two
// smallest I* agree within their intervals in e, ψ_σ and the CSL's position
// (SPEC §8.2: rate-independent); the stiffness scaling (§1), the extension
// sweep (§3) and, with analysis/drained_study.h, the drained triaxial cases.
//
// Pure statistics: `RateStudy::Analyse` takes the states and reads no file.
// Rate cases are the cases whose `figures` key names "rate" (the programme
// says which cases make up the rate study: studies/programmes/rate.toml);
// analysis/rate_cases.h reads them from a study folder, analysis/rate_files.h
// writes the analysis' files (rate_*.csv) and reads its states back, and
// analysis/quasi_static_selection.h picks the states a rate study's models
// are calibrated to.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "analysis/drained_study.h"
#include "analysis/estimate.h"
#include "analysis/rate_options.h"
#include "dem/strain_path_stage.h"

namespace granasym::analysis {

// One rate case's asymptotic state (a row of rate_states.csv).
struct RateState {
  int replicate = 1;
  std::string case_name, stage, flags;
  TableKind kind = TableKind::kNone;
  TableStatus status = TableStatus::kNoResult;
  double youngs_modulus_mpa = 0;
  double psi_epsilon_deg = 0;  // the stage's nominal direction
  double start_p_kpa = 0;      // the state it started from: the parent stage's p target
  dem::RateRule rule = dem::RateRule::kConstant;
  double inertial_number = std::numeric_limits<double>::quiet_NaN();  // I* (inertial rule)
  double stretching_rate = 0;  // ‖D‖ (constant), its cap (inertial), 1/s
  // The asymptotic state (the state table's row).
  double p_kpa = 0, e = 0, ln_1_plus_e = 0, psi_sigma_deg = 0, q_over_p = 0;
  double ocr = 0;  // against the study's NCL (the state table's)
  // Against the NCL of the same E and rate (its ψ_ε = 0° line in
  // rate_lines.csv), set by RateStudy::Analyse; NaN without that line.
  double ocr_same_rate = std::numeric_limits<double>::quiet_NaN();
  double inertial_number_dmin = 0, inertial_number_dmax = 0;
  double stiffness_number = 0;  // κ at the asymptote's p (SPEC §8.2)
  // A ψ_ε = 0° path's own NCL at its rate: ln(1+e) = N − λ ln(p / 1 kPa) by
  // least squares through the stage's rows once p has grown by a factor e
  // from its first row (one unit of ln p, the compression detector's window:
  // past the change of rate at the start), over [path_p_min_kpa,
  // path_p_max_kpa]; NaN for other paths and for fewer than 3 such rows. The
  // asymptotic states of these paths all lie at the stress cap, so the NCL of
  // a rate (rate_lines.csv) comes from these lines.
  double path_n = std::numeric_limits<double>::quiet_NaN();
  double path_lambda = std::numeric_limits<double>::quiet_NaN();
  double path_p_min_kpa = std::numeric_limits<double>::quiet_NaN();
  double path_p_max_kpa = std::numeric_limits<double>::quiet_NaN();
  bool HasPathLine() const { return std::isfinite(path_n) && std::isfinite(path_lambda); }
  // The rate of the case: I* for the inertial rule, ‖D‖ for a constant one.
  double rate() const {
    return rule == dem::RateRule::kInertial ? inertial_number : stretching_rate;
  }
};

// What groups states: the material, the direction, the start and the rate.
struct RateKey {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  bool operator<(const RateKey& other) const;
  bool operator==(const RateKey& other) const { return !(*this < other) && !(other < *this); }
  std::string RateLabel() const;  // "I* = 0.001" or "‖D‖ = 167 1/s"
};
RateKey KeyOf(const RateState& state);

// Per (E, ψ_ε, p_0, rate): the replicates' states and their means.
struct RateGroup {
  RateKey key;
  int states = 0;     // rows of the group
  int used = 0;       // of them usable (statuses, flags)
  int liquefied = 0;  // of them a gas (status or flag "gas": no asymptotic state)
  // "2 usable of 3 states" and, when some liquefied, "(1 liquefied)".
  std::string UsableText() const;
  Estimate p_kpa, e, ln_1_plus_e, psi_sigma_deg, q_over_p, ocr, ocr_same_rate, inertial_number_dmin,
      inertial_number_dmax, stiffness_number;
};

// Per (E, ψ_ε, rate): ln(1+e) = N − λ ln(p / 1 kPa) through the usable states
// of every start (all replicates), and ln(1+e) on it at the reference p.
struct RateLine {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int points = 0;
  double n = std::numeric_limits<double>::quiet_NaN();
  double lambda = std::numeric_limits<double>::quiet_NaN();
  Estimate position;  // ln(1+e) at reference_p_kpa (the prediction's standard error)
  double p_min_kpa = 0, p_max_kpa = 0;
  bool valid() const { return std::isfinite(n) && std::isfinite(lambda); }
};

// Per (E, ψ_ε, p_0) and quantity (psi_sigma_deg, q_over_p, ln_1_plus_e): the
// line y = a + b·I(d_max) through the usable states of the smallest I*.
struct QuasiStaticFit {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  std::string quantity;
  std::vector<double> rates;  // the I* values fitted over, ascending
  int points = 0;
  double i_min = std::numeric_limits<double>::quiet_NaN();  // the measured I(d_max) range
  double i_max = std::numeric_limits<double>::quiet_NaN();
  Estimate limit;  // a: the value as I → 0
  Estimate slope;  // b
  bool valid() const { return std::isfinite(limit.mean); }
};

// Per (E, ψ_ε, p_0): the two smallest I* compared in ln(1+e), ψ_σ and the
// CSL's position (ln(1+e) at the reference p of the CSLs of those I* at
// this E). Rate-independent when all three agree, rate-dependent when one
// differs, undetermined otherwise (`reason` says what is missing).
struct RateVerdict {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  double smallest = std::numeric_limits<double>::quiet_NaN();  // I*
  double next = std::numeric_limits<double>::quiet_NaN();      // the next larger I*
  Estimate ln_v_smallest, ln_v_next, psi_smallest, psi_next, csl_smallest, csl_next;
  Comparison ln_1_plus_e, psi_sigma, csl_position;
  std::string verdict;  // rate_independent, rate_dependent, undetermined
  std::string reason;
};

// Stiffness scaling (issue 10 §1): per (ψ_ε, p_0, rate) with groups at the
// reference modulus and at another E, the other E against the reference in
// ψ_σ and in the position of the CSL of that rate (its ln(1+e) at the
// reference p; on an isochoric path e is the start's, which the modulus
// changes, so the CSL's position is compared, not e), with the stiffness
// numbers κ = E/p-like of both. stiffness_independent when both agree within
// the 95 % interval of their difference (Welch), stiffness_dependent when one
// differs, undetermined otherwise (`reason`).
struct StiffnessComparison {
  double youngs_modulus_mpa = 0, reference_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  Estimate psi_reference, psi_other, csl_reference, csl_other, kappa_reference, kappa_other;
  Comparison psi_sigma, csl_position;  // other − reference
  std::string verdict, reason;
};

// §3 (issue 10): the extension sweep. Per (E, rate, p_0), the groups with
// ψ_ε ≥ 90° in ascending ψ_ε, each with the asymptotic σ_r/p = 1 − (q/p)/3
// (zero at the limit "d", where ψ_σ = atan √2 = 54.74°, SPEC §2) and how
// many of its replicates liquefied (status or flag "gas": no load-bearing
// network or p below the floor, SPEC §8.3).
struct ExtensionStep {
  double youngs_modulus_mpa = 0, start_p_kpa = 0, psi_epsilon_deg = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int states = 0, used = 0, liquefied = 0;
  Estimate sigma_r_over_p, psi_sigma_deg, p_kpa, ln_1_plus_e;
  // asymptote: σ_r/p > 0 outside its interval; limit_d: zero within it (or
  // below); liquefied: most replicates liquefied; undetermined: fewer than
  // two usable states and no majority liquefied.
  std::string status;
};

// The end of one sweep: the limit ψ_ε(d) (σ_r/p zero within its interval),
// or the ψ_ε at which the sample liquefies first, or neither up to the
// largest ψ_ε swept.
struct ExtensionLimit {
  double youngs_modulus_mpa = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int steps = 0;
  double psi_max_deg = std::numeric_limits<double>::quiet_NaN();  // the largest ψ_ε swept
  // limit_d, liquefied, not_reached (σ_r/p > 0 up to psi_max), undetermined.
  std::string result;
  double last_asymptote_deg = std::numeric_limits<double>::quiet_NaN();
  double liquefied_at_deg = std::numeric_limits<double>::quiet_NaN();
  double limit_step_deg = std::numeric_limits<double>::quiet_NaN();  // the first limit_d step
  // ψ_ε(d): the root of the least-squares line σ_r/p = a + b ψ_ε through the
  // usable states of the limit step and the (up to two) asymptote steps
  // before it, with its delta-method interval (t, points − 2 dof).
  Estimate psi_d_deg;
  std::string Text() const;  // "psi_epsilon(d) = 127.2 +- 3.1 deg", "liquefied at ..."
};

struct RateStudy {
  RateStudyOptions options;
  std::vector<RateState> states;  // every row, usable or not
  std::vector<RateGroup> groups;  // in key order
  std::vector<RateLine> lines;
  std::vector<QuasiStaticFit> quasi_static;
  std::vector<RateVerdict> verdicts;
  std::vector<ExtensionStep> extension_steps;    // by (E, rate, p_0), ψ_ε ascending
  std::vector<ExtensionLimit> extension_limits;  // one per (E, rate, p_0) with a ψ_ε > 90° step
  std::vector<StiffnessComparison> stiffness;    // per other E, ψ_ε, p_0 and rate
  DrainedStudy drained;                          // the drained triaxial cases
  bool Usable(const RateState& state) const;
  bool Usable(const DrainedState& state) const;  // the same rule for drained states
  const RateGroup* Find(const RateKey& key) const;
  // The Young's modulus of most groups (ties: the largest), the study's main
  // material; the others are its stiffness variants. Without rate groups,
  // that of most drained groups; NaN without either.
  double ReferenceModulus() const;
  std::string Text() const;  // a few lines for the console
  // The study's answers to issue 10's questions, one sentence each, with
  // their intervals: the quasi-static critical state and whether it depends
  // on p (drained), ψ_σ of the isochoric paths as I → 0 per start and where
  // they liquefy, how far the extension states go, and the verdicts on rate
  // and stiffness independence (the report's first paragraphs).
  std::vector<std::string> Answers() const;
  static RateStudy Analyse(std::vector<RateState> states, const RateStudyOptions& options = {});
};

}  // namespace granasym::analysis
