// The drained triaxial part of the rate study (issue 10 §2): drained
// triaxial compression (constant σ_r, constant ε̇_a) from the NC states, the
// critical state under stress control. The isochoric paths from loose NC
// states liquefy as I* → 0, so the quasi-static M, φ_c and CSL come from
// these cases. On a drained path p moves only from σ_r to about 1.4 σ_r, so
// a constant ε̇_a keeps I nearly fixed; the analysis uses the I(d_max)
// measured over each asymptote's window. Pure statistics: the states come
// from analysis/rate_cases.h or analysis/rate_files.h.
#pragma once

#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/estimate.h"
#include "analysis/rate_options.h"

namespace granasym::analysis {

// The material and numerics that the drained analysis keeps apart, each
// read from the case's scene: besides E, Cundall's local damping χ, the
// stiffness ratio k_t/k_n and the time-step fraction f (0: a fixed time
// step), which the study of what sets M varies (issue 39 §2,
// studies/programmes/critical_state_friction.toml). Every row type below
// holds them as its first four numbers.
using DrainedMaterial = std::tuple<double, double, double, double>;  // E, χ, k_t/k_n, f
template <typename Row>
DrainedMaterial MaterialOf(const Row& row) {
  return {row.youngs_modulus_mpa, row.local_damping, row.stiffness_ratio, row.time_step_fraction};
}
template <typename Row>
void SetMaterial(const DrainedMaterial& material, Row* row) {
  std::tie(row->youngs_modulus_mpa, row->local_damping, row->stiffness_ratio,
           row->time_step_fraction) = material;
}
// "E = 500 MPa, χ = 0.2, k_t/k_n = 1, f = 0.2"
std::string MaterialText(const DrainedMaterial& material);

// φ_c = asin(3M/(6 + M)) of a triaxial-compression stress ratio M, its
// interval by the delta method.
Estimate FrictionAngleOf(const Estimate& m);

// One drained triaxial rate case's asymptotic state (a row of
// rate_drained_states.csv).
struct DrainedState {
  int replicate = 1;
  std::string case_name, stage, flags;
  TableStatus status = TableStatus::kNoResult;
  double youngs_modulus_mpa = 0, local_damping = 0, stiffness_ratio = 0, time_step_fraction = 0;
  double radial_stress_kpa = 0, axial_strain_rate = 0;  // ε̇_a (1/s)
  double p_kpa = 0, e = 0, ln_1_plus_e = 0, psi_sigma_deg = 0, q_over_p = 0;
  double inertial_number_dmin = 0, inertial_number_dmax = 0;
};

// Per (material, σ_r, ε̇_a): the replicates' means.
struct DrainedGroup {
  double youngs_modulus_mpa = 0, local_damping = 0, stiffness_ratio = 0, time_step_fraction = 0;
  double radial_stress_kpa = 0, axial_strain_rate = 0;
  int states = 0, used = 0;
  Estimate p_kpa, e, ln_1_plus_e, psi_sigma_deg, q_over_p, inertial_number_dmax;
};

// Per (material, σ_r): y = a + b·I(d_max) through the usable states of every rate
// (at least two rates): M = q/p, ln(1+e) and ln p as I → 0; and the two
// slowest rates compared in M and ln(1+e) (rate_independent when both
// agree within the 95 % interval of their difference).
struct DrainedLimit {
  double youngs_modulus_mpa = 0, local_damping = 0, stiffness_ratio = 0, time_step_fraction = 0;
  double radial_stress_kpa = 0;
  int rates = 0, points = 0;
  double i_min = std::numeric_limits<double>::quiet_NaN();
  double i_max = std::numeric_limits<double>::quiet_NaN();
  Estimate m, ln_1_plus_e, ln_p_kpa;                          // the limits a
  Estimate m_slope;                                           // b of M
  double slowest = std::numeric_limits<double>::quiet_NaN();  // ε̇_a (1/s)
  double next = std::numeric_limits<double>::quiet_NaN();
  Comparison m_change, ln_1_plus_e_change;  // next − slowest
  std::string verdict, reason;              // rate_independent, rate_dependent, undetermined
  bool valid() const { return std::isfinite(m.mean); }
};

// Per material: the quasi-static critical state from the limits of every σ_r.
struct DrainedCriticalState {
  double youngs_modulus_mpa = 0, local_damping = 0, stiffness_ratio = 0, time_step_fraction = 0;
  int starts = 0;       // σ_r with a limit
  Estimate m;           // mean of the limits' M (Student t, starts − 1 dof)
  Estimate phi_c_deg;   // φ_c = asin(3M/(6 + M)), its interval by the delta method
  Estimate m_per_ln_p;  // slope of the limits' M against ln p: M's p-dependence
  Estimate lambda;      // the CSL ln(1+e) = Γ − λ ln(p / 1 kPa) through the limits
  double gamma = std::numeric_limits<double>::quiet_NaN();
  Estimate position;  // ln(1+e) on it at the reference p
  std::string Text(double reference_p_kpa) const;
};

struct DrainedStudy {
  std::vector<DrainedState> states;
  std::vector<DrainedGroup> groups;            // by (material, σ_r, ε̇_a)
  std::vector<DrainedLimit> limits;            // by (material, σ_r)
  std::vector<DrainedCriticalState> critical;  // by material
  // `usable`: the rate study's rule for a state's status and flags.
  static DrainedStudy Analyse(std::vector<DrainedState> states, const RateStudyOptions& options);
};

// The rate study's rule for a drained state: its status and flags
// (PassesFilters), a positive p and finite ln(1+e) and q/p.
bool DrainedUsable(const DrainedState& state, const RateStudyOptions& options);

}  // namespace granasym::analysis
