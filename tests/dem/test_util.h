// Helpers shared by the DEM tests: temporary paths and small scenes.
#pragma once

#include <filesystem>
#include <string>

namespace granasym::dem::testing {

inline std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "granasym_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// A ~1000-sphere sample of the default GSD at the paper's initial porosity.
inline std::string SampleToml(int count = 1000, double cell_mm = 5.8, int seed = 3) {
  return "[sample.generate]\ncount = " + std::to_string(count) +
         "\ncell_size_mm = " + std::to_string(cell_mm) + "\nseed = " + std::to_string(seed) +
         "\n[numerics]\ntime_step_s = 1.2e-7\n";
}

// An isotropic compression stage (ψ_ε = 0°, ‖D‖ = 167 1/s) to p = `kpa`.
inline std::string NclStage(double kpa) {
  return "[[stage]]\nname = \"ncl\"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
         "[stage.stop]\nmean_stress_kpa = " +
         std::to_string(kpa) + "\n";
}

// A drained triaxial stage (the paper's ε̇_a) at σ_r = `kpa` to ε_a = `strain`.
inline std::string TriaxialStage(double kpa, double strain) {
  return "[[stage]]\nname = \"triaxial\"\ntype = \"triaxial\"\naxial_strain_rate = 136.355\n"
         "radial_stress_kpa = " +
         std::to_string(kpa) + "\n[stage.stop]\naxial_strain = " + std::to_string(strain) + "\n";
}

}  // namespace granasym::dem::testing
