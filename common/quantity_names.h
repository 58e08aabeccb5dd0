// One spelling per quantity in every output granasym writes: the DEM's
// series (dem/run_record_names.h), the element tests of the constitutive
// models (CSV and HDF5), the calibration's tables and the study's tables.
// Units are part of the name where the quantity has one; angles are in
// degrees; stresses are compression positive. Header-only, no dependencies.
//
// Renamed in issue 33 (old names are still read): the model outputs'
// stress_a_kpa -> sigma_a_kpa, stress_r_kpa -> sigma_r_kpa,
// void_ratio -> e, strain_a -> eps_a, strain_r -> eps_r, and in their HDF5
// files mean_stress -> p_kpa, deviator_stress -> q_kpa,
// psi_sigma / psi_epsilon (radians) -> psi_sigma_deg / psi_epsilon_deg.
#pragma once

namespace granasym::quantity {

inline constexpr char kTime[] = "time_s";
inline constexpr char kMeanStress[] = "p_kpa";          // p = (σ_a + 2σ_r)/3
inline constexpr char kDeviator[] = "q_kpa";            // q = σ_a − σ_r
inline constexpr char kAxialStress[] = "sigma_a_kpa";   // σ_a = σ_11
inline constexpr char kRadialStress[] = "sigma_r_kpa";  // σ_r = (σ_22 + σ_33)/2
inline constexpr char kVoidRatio[] = "e";
inline constexpr char kLnVolume[] = "ln_1_plus_e";
inline constexpr char kAxialStrain[] = "eps_a";  // logarithmic, compression positive
inline constexpr char kRadialStrain[] = "eps_r";
inline constexpr char kVolumetricStrain[] = "eps_v";
inline constexpr char kShearStrain[] = "eps_s";
inline constexpr char kPsiSigma[] = "psi_sigma_deg";      // stress path angle ψ_σ
inline constexpr char kPsiEpsilon[] = "psi_epsilon_deg";  // strain path angle ψ_ε
inline constexpr char kOverconsolidation[] = "ocr";

}  // namespace granasym::quantity
