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

}  // namespace granasym::dem::testing
