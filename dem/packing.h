// A packing: spheres in a periodic box, as read from or written to the plain
// text exchange format (first line `N Lx Ly Lz`, then `x y z r` per sphere,
// metres), and its generation from a grain-size distribution.
//
// The text format, read strictly (every error an InputError naming the file,
// the line, the value and what would be valid):
//  - blank lines and lines whose first non-blank character is '#' are
//    comments, anywhere (WriteText writes none; files from other tools may);
//    any other line holds whitespace-separated fields, nothing after them;
//  - the header: exactly four fields `N Lx Ly Lz`; N a positive integer
//    written with digits only (no sign, point or exponent), at most
//    kMaxPackingSpheres; the cell sides finite numbers > 0 (m);
//  - then exactly N rows of exactly four finite numbers `x y z r` (m); no row
//    after the N-th;
//  - a diameter 2r in [kMinSphereDiameter, kMaxSphereDiameter] and at most
//    half the smallest cell side (the minimum image convention: a sphere may
//    not reach its own image; the engine's neighbour list further needs the
//    smallest side above 2 (d_max + skin), and reports it at its first build);
//  - the cell holds at most kMaxCellsPerLargestSphere cubes of the largest
//    diameter (Lx Ly Lz / d_max³): the neighbour grid of a more dilute cell
//    would not fit in memory (and usually the lengths are in another unit);
//  - coordinates anywhere within kMaxCellImages cell sides of the cell are
//    wrapped periodically into [0, L), as the engine does; farther ones are
//    rejected (wrapping them would lose most of their digits);
//  - no two spheres overlapping by the run's failure limit or more
//    (kValidityLimits.overlap_failure, dem/stage_validity.h: a relative
//    overlap (r_i + r_j − |x_ij|)/(r_i + r_j) of 25 %, minimum image;
//    coincident centres are 100 %), found with a cell list in O(N); smaller
//    overlaps are accepted, since the compressed packings that runs export
//    legitimately overlap (2 % and 10 % only flag a run's states).
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
  // Writes the text format with 17 significant digits, after Validate(path):
  // it never writes what ReadText refuses (WriteTextFileAtomically: FileError
  // when it cannot, the file under `path` left as it was).
  void WriteText(const std::string& path) const;
  // Checks the rules of the text format above on the packing in memory;
  // InputError naming `origin` and the sphere (1-based index) otherwise.
  void Validate(const std::string& origin) const;
};

// Limits of the text format (see above).
inline constexpr size_t kMaxPackingSpheres = 2147483647;           // the engine's 32-bit indices
inline constexpr double kMaxCellsPerLargestSphere = 1073741824.0;  // 2^30
inline constexpr double kMaxCellImages = 1000.0;
// Random sequential addition jams near a solid fraction of 0.4–0.5.
inline constexpr double kMaxGenerationSolidFraction = 0.55;

struct GenerationOptions {
  size_t count = 150000;     // number of spheres, at most kMaxPackingSpheres
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

// What a generation would need, computed in O(1) before it allocates.
struct GenerationEstimate {
  double largest_diameter = 0;    // of the generated spheres (the first quantile; m)
  double cells_per_sphere = 0;    // cell volume / largest_diameter³
  double grid_cells = 0;          // bins of the placement grid
  double bytes = 0;               // memory of the generation: radii, positions, grid
  double min_solid_fraction = 0;  // a lower bound on the solid fraction of the quantile radii
};
GenerationEstimate EstimateGeneration(const GrainSizeDistribution& gsd,
                                      const GenerationOptions& options);
// The machine's physical memory (bytes; sysconf), 0 when unknown.
double PhysicalMemoryBytes();
// Throws InputError (naming the GSD's origin where the table is the cause)
// unless the generation fits, checked in this order: the options are valid;
// the cell side is at least twice the largest generated diameter (the
// generated packing must satisfy the format's d ≤ L/2); the cell holds at
// most kMaxCellsPerLargestSphere cubes of that diameter (which bounds the
// placement grid; more usually means diameters in another unit); the
// estimated memory is at most `physical_memory` (bytes; 0: not checked); the
// lower bound on the solid fraction is below the random placement's 55 %.
// O(1) whatever the count: 10⁹ spheres are refused at once, not after
// minutes of allocation.
void CheckGenerationFits(const GrainSizeDistribution& gsd, const GenerationOptions& options,
                         double physical_memory);

// Radii by deterministic quantiles of `gsd`, placed at random without overlap
// (largest first) using a grid of cells no smaller than the largest diameter,
// so the cost is O(N). First CheckGenerationFits(gsd, options,
// PhysicalMemoryBytes()); throws InputError when the spheres cannot be placed.
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
