// The adaptive time step of a DEM run: Δt a stated fraction of the shortest
// contact duration, re-evaluated as the contacts stiffen (issue 10; scene key
// numerics.time_step_fraction).
//
//   Δt = min( f · min( t_impact, min over touching pairs π sqrt(m_12 / k_n(u_N)) ),  Δt_max )
//
// k_n = dF_n/du_N is the law's tangent normal stiffness at the pair's current
// overlap (Engine::SmallestContactDuration) and m_12 = m_i m_j/(m_i + m_j).
// t_impact is the law's duration of a head-on impact of the two smallest
// spheres (ComputeContactDurations: paper Eq. 3 for the linear law, the Hertz
// duration at the reference speed of 1 m/s for Hertz–Mindlin): it is Δt/f
// before the first contact, and it stays a bound afterwards, because a
// contact that forms between two evaluations must be resolved too and its
// tangent stiffness just after touching says nothing about how stiff it
// becomes (a Hertz contact at u_N → 0 has k_n → 0).
//
// For the linear law every pair lasts at least t_impact (for r_j ≥ r_i,
// m_12/k_n ∝ r_i² x²/(1 − x + x²) ≥ r_i² with x = r_j/r_i), so Δt = f t_impact
// throughout: the rule skips the pass over the pairs (which could only return
// the same up to the rounding of two formulas) and Δt is exactly the fixed
// fraction of earlier versions. For Hertz–Mindlin k_n = 2E* sqrt(R* u_N)
// grows with the overlap, and Δt shrinks as p^(-1/6) once the loaded
// contacts are stiffer than an impact at 1 m/s.
//
// Stability: for a pair at any overlap the leapfrog limit is the fraction
// 2/(π sqrt(factor)) of its duration at the same stiffness
// (ContactDurations::stability_fraction), so f below it keeps every contact
// present at an evaluation stable; the margin f < limit covers contacts that
// stiffen between evaluations.
//
// When. The run loop evaluates the rule after the force evaluation of every
// stage's first step and then every `check_interval` steps of the stage
// (stage-relative, so that a run forked from a stage's end state steps
// exactly as the run that continued into the next stage); the Δt in force is
// part of the engine state (checkpoints, stage end states), so restarts
// continue bit-identically.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace granasym::dem {

class Engine;
struct Material;

class AdaptiveTimeStep {
 public:
  struct Options {
    // f: Δt over the shortest contact duration. The paper's Δt = 1.2e-7 s is
    // 0.114 of its reduced-mass duration 1.05e-6 s.
    double fraction = 0.1;
    // Steps between re-evaluations within a stage (each stage also starts
    // with one). A Hertz contact's duration changes as u_N^(-1/4): within
    // 100 steps at ‖D‖ = 167 1/s and Δt = 1e-7 s the strain changes by
    // 1.7e-3, far too little to matter against the margin of f.
    int64_t check_interval = 100;
    // Δt_max (s): an upper bound; infinity: none.
    double max_time_step = std::numeric_limits<double>::infinity();
    // Names the offending field in `why`.
    bool IsValid(std::string* why) const;
  };

  // For the sample's radii and its material (the impact bound is that of
  // ComputeContactDurations).
  AdaptiveTimeStep(const Options& options, const Material& material,
                   const std::vector<double>& radii);

  // The rule's largest Δt, min(f t_impact, Δt_max): its value before the
  // first contact and an upper bound of every later value (s).
  double UpperBound() const;
  // Whether the rule is evaluated at this step of a stage.
  bool Due(int64_t stage_steps) const { return stage_steps % options_.check_interval == 0; }
  // Δt from the contacts at the engine's current positions (after a force
  // evaluation; for the linear law UpperBound() without a pass) (s).
  double Evaluate(const Engine& engine) const;
  // Δt for a shortest contact duration `smallest_duration` (s; infinity:
  // no contact).
  double FromDuration(double smallest_duration) const;

  const Options& options() const { return options_; }
  double impact_duration() const { return impact_duration_; }
  // One line: the rule, e.g. "adaptive: 0.1 of the shortest contact duration
  // (re-evaluated every 100 steps)".
  std::string Describe() const;

 private:
  Options options_;
  double impact_duration_;  // t_impact (s)
  bool overlap_dependent_;  // the law's k_n depends on u_N (Hertz–Mindlin)
};

}  // namespace granasym::dem
