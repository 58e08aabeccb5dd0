// A packing: spheres in a periodic box, as read from or written to the plain
// text exchange format (first line `N Lx Ly Lz`, then `x y z r` per sphere,
// metres), and its generation from a grain-size distribution.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/grain_size_distribution.h"

namespace granasym::dem {

struct Packing {
  std::array<double, 3> cell{};                  // side lengths of the periodic box (m)
  std::vector<std::array<double, 3>> positions;  // sphere centres (m), in [0, L)
  std::vector<double> radii;                     // (m)

  size_t size() const { return radii.size(); }
  double SolidVolume() const;
  double Porosity() const;  // 1 − V_solid / V_cell (overlaps neglected)

  // Reads the text format; errors name the file, the line and the value.
  static Packing ReadText(const std::string& path);
  // Writes the text format with 17 significant digits (WriteTextFileAtomically:
  // FileError when it cannot, the file under `path` left as it was).
  void WriteText(const std::string& path) const;
};

struct GenerationOptions {
  size_t count = 150000;     // number of spheres
  double cell_size = 0.031;  // side of the periodic cube (m)
  uint64_t seed = 1;         // random placement seed
  // Placement attempts per sphere before giving up (the random sequential
  // addition jams near a solid fraction of 0.4–0.5).
  int max_attempts = 200000;
  bool IsValid(std::string* why) const;
};

struct GenerationReport {
  size_t count = 0;
  double porosity = 0;
  double seconds = 0;
  int64_t attempts = 0;                  // total placement attempts
  std::vector<double> sieve_diameters;   // (m)
  std::vector<double> target_passing;    // (%)
  std::vector<double> achieved_passing;  // (%)
  std::string Table() const;             // readable GSD comparison
};

// Radii by deterministic quantiles of `gsd`, placed at random without overlap
// (largest first) using a grid of cells no smaller than the largest diameter,
// so the cost is O(N). Throws InputError when the spheres cannot be placed.
Packing GeneratePacking(const GrainSizeDistribution& gsd, const GenerationOptions& options,
                        GenerationReport* report = nullptr);

// A deterministic 64-bit generator (SplitMix64) so that the same seed gives
// the same packing on every platform and standard library.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t Next();
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  uint64_t state_;
};

}  // namespace granasym::dem
