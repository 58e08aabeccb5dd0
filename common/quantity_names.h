// One spelling per quantity in every output granasym writes: the DEM's
// series (dem/run_record_names.h), the element tests of the constitutive
// models (CSV and HDF5), the calibration's tables and the study's tables.
// Units are part of the name where the quantity has one; angles are in
// degrees; stresses are compression positive. Header-only, no dependencies.
//
// Renamed in issue 33 (the old names are the constants of `former` below,
// which readers still accept): the element tests' CSV (`model run --csv`,
// result.csv of a study's model runs) stress_a_kpa -> sigma_a_kpa,
// stress_r_kpa -> sigma_r_kpa, void_ratio -> e, strain_a -> eps_a,
// strain_r -> eps_r; their HDF5 (`model run --out`, result.h5) time ->
// time_s, void_ratio -> e, mean_stress -> p_kpa, deviator_stress -> q_kpa,
// psi_sigma / psi_epsilon (radians) -> psi_sigma_deg / psi_epsilon_deg
// (degrees, units "deg"); and the asymptotes' HDF5 (`model asymptotes`)
// psi_sigma / psi_epsilon (radians) -> psi_sigma_deg / psi_epsilon_deg.
// The calibration's outputs already used these names.
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

// The names of the models' outputs before issue 33 (see above), for readers
// of older files: CsvTable::Column(name, former_name).
namespace former {
inline constexpr char kTime[] = "time";                 // HDF5
inline constexpr char kMeanStress[] = "mean_stress";    // HDF5
inline constexpr char kDeviator[] = "deviator_stress";  // HDF5
inline constexpr char kAxialStress[] = "stress_a_kpa";
inline constexpr char kRadialStress[] = "stress_r_kpa";
inline constexpr char kVoidRatio[] = "void_ratio";
inline constexpr char kAxialStrain[] = "strain_a";
inline constexpr char kRadialStrain[] = "strain_r";
inline constexpr char kPsiSigmaRadians[] = "psi_sigma";      // HDF5, in radians
inline constexpr char kPsiEpsilonRadians[] = "psi_epsilon";  // HDF5, in radians
}  // namespace former

}  // namespace granasym::quantity
