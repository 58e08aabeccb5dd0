#include "dem/packing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/state_measures.h"
#include "common/stopwatch.h"
#include "common/text_file.h"

namespace granasym::dem {

uint64_t SplitMix64::Next() {
  uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double Packing::SolidVolume() const {
  double volume = 0.0;
  for (double r : radii) volume += 4.0 / 3.0 * kPi * r * r * r;
  return volume;
}

double Packing::Porosity() const { return 1.0 - SolidVolume() / (cell[0] * cell[1] * cell[2]); }

Packing Packing::ReadText(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot open packing file '" + path + "'");
  Packing packing;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(path + ": line " + std::to_string(line_number) + ": " + what);
  };
  // Header: N Lx Ly Lz.
  while (std::getline(file, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos && line[0] != '#') break;
  }
  std::istringstream header(line);
  long long count = -1;
  if (!(header >> count >> packing.cell[0] >> packing.cell[1] >> packing.cell[2])) {
    fail("expected the header 'N Lx Ly Lz' (count and cell sides in metres), got '" + line + "'");
  }
  if (count <= 0) fail("sphere count " + std::to_string(count) + " must be > 0");
  for (int d = 0; d < 3; ++d) {
    if (!(packing.cell[d] > 0) || !std::isfinite(packing.cell[d])) {
      fail("cell side " + std::to_string(packing.cell[d]) + " m must be a finite number > 0");
    }
  }
  packing.positions.reserve(count);
  packing.radii.reserve(count);
  while (static_cast<long long>(packing.radii.size()) < count && std::getline(file, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    std::istringstream row(line);
    std::array<double, 3> x;
    double r;
    if (!(row >> x[0] >> x[1] >> x[2] >> r))
      fail("expected 'x y z r' in metres, got '" + line + "'");
    if (!(r > 0) || !std::isfinite(r)) fail("radius " + std::to_string(r) + " m must be > 0");
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(x[d])) fail("coordinate is not finite");
      // Accept coordinates outside the box: wrap them periodically.
      x[d] -= packing.cell[d] * std::floor(x[d] / packing.cell[d]);
    }
    packing.positions.push_back(x);
    packing.radii.push_back(r);
  }
  if (static_cast<long long>(packing.radii.size()) != count) {
    throw InputError(path + ": the header announces " + std::to_string(count) + " spheres but " +
                     std::to_string(packing.radii.size()) + " were found");
  }
  return packing;
}

void Packing::WriteText(const std::string& path) const {
  std::string text;
  text.reserve(80 * (size() + 1));
  char line[160];
  std::snprintf(line, sizeof(line), "%zu %.17g %.17g %.17g\n", size(), cell[0], cell[1], cell[2]);
  text += line;
  for (size_t i = 0; i < size(); ++i) {
    std::snprintf(line, sizeof(line), "%.17g %.17g %.17g %.17g\n", positions[i][0], positions[i][1],
                  positions[i][2], radii[i]);
    text += line;
  }
  WriteTextFileAtomically(path, text);
}

bool GenerationOptions::IsValid(std::string* why) const {
  if (count == 0) return *why = "count must be > 0", false;
  if (!(cell_size > 0)) return *why = "cell_size must be > 0", false;
  if (max_attempts <= 0) return *why = "max_attempts must be > 0", false;
  return true;
}

std::string GenerationReport::Table() const {
  std::ostringstream out;
  char line[128];
  std::snprintf(line, sizeof(line), "%zu spheres, porosity %.4f, %.2f s, %.2f attempts/sphere\n",
                count, porosity, seconds, count ? double(attempts) / count : 0.0);
  out << line << "  sieve [mm]   target [%]   achieved [%]\n";
  for (size_t k = 0; k < sieve_diameters.size(); ++k) {
    std::snprintf(line, sizeof(line), "  %10.4f   %10.2f   %12.2f\n", sieve_diameters[k] * 1e3,
                  target_passing[k], achieved_passing[k]);
    out << line;
  }
  return out.str();
}

Packing GeneratePacking(const GrainSizeDistribution& gsd, const GenerationOptions& options,
                        GenerationReport* report) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("sample generation: " + why);
  Stopwatch stopwatch;
  Packing packing;
  packing.cell = {options.cell_size, options.cell_size, options.cell_size};
  packing.radii = gsd.QuantileRadii(options.count);  // descending: largest placed first
  const double r_max = packing.radii.front();
  const double side = options.cell_size;
  if (side < 4.0 * r_max) {
    throw InputError("sample generation: cell side " + std::to_string(side * 1e3) +
                     " mm must be at least twice the largest diameter (" +
                     std::to_string(4e3 * r_max) + " mm)");
  }
  const double solid = packing.SolidVolume() / (side * side * side);
  if (solid >= 0.55) {
    throw InputError("sample generation: " + std::to_string(options.count) + " spheres fill " +
                     std::to_string(100 * solid) + " % of a " + std::to_string(side * 1e3) +
                     " mm cube; random placement needs a solid fraction below 55 %: "
                     "enlarge cell_size or reduce count");
  }
  // Grid of cubic bins of side >= 2 r_max: any overlapping pair lies in
  // neighbouring bins. Linked lists (head/next) keep it O(N) in memory.
  // With fewer than three bins per side the neighbourhood would wrap onto
  // itself; one bin holding every sphere is then correct (small cells only).
  const int fitting_bins = static_cast<int>(side / (2.0 * r_max));
  const int bins = fitting_bins >= 3 ? fitting_bins : 1;
  const double bin = side / bins;
  std::vector<int> head(static_cast<size_t>(bins) * bins * bins, -1);
  std::vector<int> next(options.count, -1);
  packing.positions.resize(options.count);
  SplitMix64 random(options.seed);
  int64_t attempts = 0;
  auto bin_of = [&](double x) { return std::min(bins - 1, static_cast<int>(x / bin)); };
  auto wrap = [&](int b) { return (b % bins + bins) % bins; };
  for (size_t i = 0; i < options.count; ++i) {
    const double r = packing.radii[i];
    bool placed = false;
    for (int attempt = 0; attempt < options.max_attempts && !placed; ++attempt) {
      ++attempts;
      const std::array<double, 3> x = {random.Uniform() * side, random.Uniform() * side,
                                       random.Uniform() * side};
      const int bx = bin_of(x[0]), by = bin_of(x[1]), bz = bin_of(x[2]);
      bool overlap = false;
      const int reach = bins >= 3 ? 1 : 0;
      for (int dx = -reach; dx <= reach && !overlap; ++dx) {
        for (int dy = -reach; dy <= reach && !overlap; ++dy) {
          for (int dz = -reach; dz <= reach && !overlap; ++dz) {
            const int cell_index = (wrap(bx + dx) * bins + wrap(by + dy)) * bins + wrap(bz + dz);
            for (int j = head[cell_index]; j >= 0; j = next[j]) {
              double distance2 = 0.0;
              for (int d = 0; d < 3; ++d) {
                double delta = packing.positions[j][d] - x[d];
                delta -= side * std::nearbyint(delta / side);
                distance2 += delta * delta;
              }
              const double contact = r + packing.radii[j];
              if (distance2 < contact * contact) {
                overlap = true;
                break;
              }
            }
          }
        }
      }
      if (!overlap) {
        packing.positions[i] = x;
        const int cell_index = (bx * bins + by) * bins + bz;
        next[i] = head[cell_index];
        head[cell_index] = static_cast<int>(i);
        placed = true;
      }
    }
    if (!placed) {
      throw InputError("sample generation: could not place sphere " + std::to_string(i + 1) +
                       " of " + std::to_string(options.count) + " (radius " +
                       std::to_string(r * 1e3) + " mm) after " +
                       std::to_string(options.max_attempts) +
                       " random attempts; the target solid fraction " + std::to_string(solid) +
                       " is too dense for random placement: enlarge cell_size or reduce count");
    }
  }
  if (report) {
    report->count = options.count;
    report->porosity = packing.Porosity();
    report->seconds = stopwatch.Seconds();
    report->attempts = attempts;
    report->sieve_diameters = gsd.diameters();
    report->target_passing = gsd.percent_passing();
    report->achieved_passing = gsd.AchievedPercentPassing(packing.radii);
  }
  return packing;
}

}  // namespace granasym::dem
