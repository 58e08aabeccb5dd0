// The steps a DEM stage will take, from its stop conditions and rate rule
// and a physical model of how the mean stress p moves along its path: the
// step counts of `study plan`, the ETA and the shards' balance
// (PlannedCase::estimated_steps). Pure functions of a parsed stage.
//
// The stage's strain norm s = ∫‖D‖dt at its end is the first of its stops
// that the model predicts:
//  - steps, time_s, strain_norm: exact; axial_strain, volumetric_strain,
//    shear_strain: exact on a strain path (fixed direction ψ_ε: each strain
//    is a fixed multiple of s) and for a triaxial stage's axial strain (fixed
//    ε̇_a); a triaxial stage's ‖D‖ is taken as √1.5 |ε̇_a|, its value at the
//    critical state (ε̇_v = 0);
//  - mean_stress_kpa: a generated sample first jams, bearing about
//    kJammedMeanStressKpa at a volumetric strain ln(φ/φ_0) from its generated
//    solid fraction φ_0, where φ = φ_J − a I is the solid fraction of a
//    dense granular flow at the inertial number I of that stress and the
//    stage's rate (φ_J = kJammedSolidFraction, a = kDilatancyCoefficient:
//    GDR MiDi 2004, da Cruz et al. 2005; at 167 1/s a sample bears 1 kPa at
//    φ ≈ 0.49, under the inertial rule at I* = 1e-3 at φ_J); a loading path
//    (ε̇_v > 0) then compresses by Δε_v = Δln φ(p) + C Δp/E: the denser
//    packing of the slower flow at the higher p, and the compliance of the
//    contacts (C = kContactCompliance, the paper's material's NCL between
//    100 and 1000 kPa: about three times the affine elastic strain p/K, the
//    rearrangements that the contacts' deformation allows); an unloading
//    path (ε̇_v < 0)
//    unloads elastically, dp = K dε_v with the affine bulk modulus of the
//    contact network K = Z φ_J κ p / (3π) (Z = 4, the frictional isostatic
//    coordination; κ the stiffness number of SPEC §8.3);
//  - asymptote: a shear path (ψ_ε = 90°, triaxial) reaches its critical
//    state after kShearTransientStrain and the detector then needs its window
//    (window_strain); a compression path after one e-fold of p (the
//    transient of ψ_σ) and its window in ln p (window_lnp, at most
//    window_strain); an extension path's
//    asymptote is not predicted (p falls towards the floor);
//  - liquefied: a stage that may liquefy ends at the latest at its caps (a
//    sample that has been a gas for a while reaches its asymptote later
//    than the model says: the rate study's isochoric paths at 167 1/s took
//    up to 1.8 times the predicted strain), and its steps are a bound ("at
//    most"). The earliest it can end (StageSteps::earliest) is its other
//    predicted stops, or its gas window (stop.liquefied_strain, else the
//    detector's window_strain) after it first becomes a gas: on an
//    unloading path once the elastic unloading takes p below the gas floor
//    (the detector's floor_kpa on an extension path, else the validity's
//    gas stress), on an isochoric path under the inertial rule at once (a
//    packing on the NCL sheared at constant volume falls towards its
//    critical state at the same void ratio, far below for stiff grains, and
//    at slow rates liquefies within the first rows: the rate study's
//    ψ_ε = 90° paths at I* <= 1e-3), never on a loading or
//    stress-controlled one; at the modelled p's own rate up to the first
//    gas, at the floor's after it;
//
// The steps follow from s and the rate: a constant ‖D‖ gives s/(‖D‖Δt);
// the inertial rule ‖D‖ = I* sqrt(p/(2ρ_s))/d (dem/strain_path_stage.h,
// between its floor of p and its cap) is integrated over the modelled p(s):
// p stays at the start value on an isochoric path and follows the
// loading law or the elastic unloading otherwise. Where p may fall
// below what the model says (a stage that may liquefy, an isochoric or
// dilating path under the inertial rule, whose p can collapse towards the
// rule's floor) the steps are those at the floor's rate: the bound. Steps
// before the generated sample jams, and after an unloading has taken p to
// zero, are a loose packing's (cheaper: study/cost.h).
#pragma once

#include <string>
#include <vector>

#include "dem/material.h"
#include "dem/stage.h"

namespace granasym::study {

// The model's material constants (see above).
inline constexpr double kJammedSolidFraction = 0.6;   // φ_J of frictional spheres (μ ≈ 0.5)
inline constexpr double kJammedMeanStressKpa = 1.0;   // p the packing bears when it jams
inline constexpr double kDilatancyCoefficient = 0.3;  // a of φ = φ_J − a I of a dense flow
inline constexpr double kContactCompliance = 25.0;    // C = dε_v/d(p/E) of loading
inline constexpr double kIsostaticCoordination = 4;   // Z of a jammed frictional packing
// The ‖D‖ at which the loose rate is measured (MeasuredRate): the loose
// steps of a slower stage cost less, down to those of grains that do not
// collide (a granular gas collides at a frequency ∝ ‖D‖).
inline constexpr double kCollisionalStrainRate = 167.0;
// Strain norm to the critical state: a shear strain ε_q of about 0.25
// (‖D‖ = √1.5 |ε̇_q| on an isochoric path).
inline constexpr double kShearTransientStrain = 0.3;

// What a stage's steps depend on besides its own keys.
struct StageSampleScales {
  double time_step = 0;  // (s)
  dem::Material material;
  dem::StageContext context;            // diameters (m) and density of the sample
  double generated_solid_fraction = 0;  // φ_0 of the generated sample
};

// The scales of a sample of these radii (m) in a cubic cell of side `cell` (m).
StageSampleScales SampleScalesOf(const std::vector<double>& radii, double cell,
                                 const dem::Material& material, double time_step);

struct StageSteps {
  double steps = 0;
  // Steps taken before the generated sample jams (a loose packing: cheaper
  // steps, MeasuredRate::loose_particle_steps_per_second), included in steps.
  double loose_steps = 0;  // (and those after an unloading has taken p to zero)
  // Of them, the share whose grains do not collide: loose_steps ·
  // (1 − min(1, ‖D‖/kCollisionalStrainRate)), ‖D‖ their rate
  // (MeasuredRate::still_particle_steps_per_second).
  double still_steps = 0;
  // The stage sums the stress on every step (a mean-stress stop, a
  // stress-controlled type): MeasuredRate::controlled_particle_steps_per_second.
  bool stress_every_step = false;
  bool at_most = false;  // a bound: the stage may end earlier (liquefaction, p below the model)
  // The stage's figures if it liquefies as early as the model allows (an
  // `at_most` stage; the same as the bound's otherwise): the range's low end.
  struct Earliest {
    double steps = 0, loose_steps = 0, still_steps = 0;
    double strain = 0;
  } earliest;
  double strain = 0;     // the strain norm s at its end
  double end_p_kpa = 0;  // the modelled p at its end (NaN: unknown)
  std::string reason;    // which stop ends it, e.g. "mean_stress_kpa", "strain_norm (at most)"
};

// The steps of `stage` starting at mean stress `start_p_kpa` (0: the
// generated, unloaded sample; NaN: unknown, taken as 100 kPa).
StageSteps EstimateStageSteps(const dem::Stage& stage, const StageSampleScales& scales,
                              double start_p_kpa);

}  // namespace granasym::study
