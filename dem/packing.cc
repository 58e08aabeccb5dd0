#include "dem/packing.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "common/error.h"
#include "common/state_measures.h"
#include "common/stopwatch.h"
#include "common/text_file.h"
#include "dem/stage_validity.h"

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

namespace {

// Numbers from a file, shortest form that reads back the same ("0.001", "1e-300").
std::string Num(double value) { return fmt::format("{}", value); }

const char* const kAxis[3] = {"x", "y", "z"};

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string field;
  while (in >> field) fields.push_back(field);
  return fields;
}

// A line as shown in messages: trimmed, at most 60 characters.
std::string Shown(const std::string& line) {
  const size_t first = line.find_first_not_of(" \t\r");
  const size_t last = line.find_last_not_of(" \t\r");
  if (first == std::string::npos) return "";
  std::string text = line.substr(first, last - first + 1);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// The whole field as a finite number (an underflow reads as its rounded
// value, as WriteText's 17 digits of a subnormal number must read back).
bool ParseFinite(const std::string& field, double* value) {
  char* end = nullptr;
  *value = std::strtod(field.c_str(), &end);
  return !field.empty() && *end == '\0' && std::isfinite(*value);
}

std::string CellSideProblem(int axis, double side) {
  if (std::isfinite(side) && side > 0) return "";
  return fmt::format("cell side L{} = {} m must be a finite number > 0", kAxis[axis], Num(side));
}

// Why a sphere breaks a rule of the format in `cell` (before wrapping), or "".
std::string SphereProblem(const std::array<double, 3>& x, double r,
                          const std::array<double, 3>& cell) {
  const double d = 2.0 * r;
  if (!(d >= kMinSphereDiameter && d <= kMaxSphereDiameter)) {
    return fmt::format(
        "radius {} m must be a finite number > 0 with a diameter in [{}, {}] m (are the lengths "
        "in metres?)",
        Num(r), Num(kMinSphereDiameter), Num(kMaxSphereDiameter));
  }
  const double smallest = std::min({cell[0], cell[1], cell[2]});
  if (d > 0.5 * smallest) {
    return fmt::format(
        "radius {} m: the diameter {} m exceeds {} m, half the smallest cell side {} m (a "
        "sphere may not reach its own periodic image; enlarge the cell)",
        Num(r), Num(d), Num(0.5 * smallest), Num(smallest));
  }
  for (int a = 0; a < 3; ++a) {
    if (!(std::abs(x[a]) <= kMaxCellImages * cell[a])) {
      return fmt::format(
          "coordinate {} = {} m lies more than {} cell sides ({} m) from the cell; coordinates "
          "within that range are wrapped periodically, farther ones are refused (are the lengths "
          "in metres?)",
          kAxis[a], Num(x[a]), Num(kMaxCellImages), Num(kMaxCellImages * cell[a]));
    }
  }
  return "";
}

double CellsPerLargestSphere(const std::array<double, 3>& cell, double largest_diameter) {
  return cell[0] * cell[1] * cell[2] / (largest_diameter * largest_diameter * largest_diameter);
}

std::string GridProblem(const std::array<double, 3>& cell, double largest_diameter) {
  const double cubes = CellsPerLargestSphere(cell, largest_diameter);
  if (cubes <= kMaxCellsPerLargestSphere) return "";
  return fmt::format(
      "the cell ({} x {} x {} m) holds {:.3g} cubes of the largest diameter {} m; at most {:.3g} "
      "(2^30) are supported, since the neighbour grid grows with it (are the lengths in metres?)",
      Num(cell[0]), Num(cell[1]), Num(cell[2]), cubes, Num(largest_diameter),
      kMaxCellsPerLargestSphere);
}

// Into [0, L) (a coordinate within rounding of 0 or L maps to 0, the same point).
double Wrap(double x, double side) {
  if (x >= 0 && x < side) return x;
  const double wrapped = x - side * std::floor(x / side);
  return wrapped >= 0 && wrapped < side ? wrapped : 0.0;
}

struct OverlapPair {
  size_t i = 0, j = 0;
  double distance = 0;  // of the centres, minimum image (m)
  double relative = 0;  // (r_i + r_j − distance)/(r_i + r_j)
};

// The first pair (in the order of i) whose relative overlap reaches the run's
// failure limit; positions anywhere (binned wrapped, distances by minimum
// image). A cell list of bins no smaller than the
// largest diameter, at most ~4 per sphere (the neighbour list's grid is sized
// by the reach alone and keeps a contact history; this check needs neither).
std::optional<OverlapPair> FindExcessiveOverlap(const Packing& packing) {
  const size_t n = packing.size();
  const double reach = 2.0 * *std::max_element(packing.radii.begin(), packing.radii.end());
  const double cap = std::max(3.0, std::floor(std::cbrt(4.0 * static_cast<double>(n))));
  std::array<int64_t, 3> bins;
  for (int a = 0; a < 3; ++a) {
    const double fitting = std::min(cap, std::floor(packing.cell[a] / reach));
    bins[a] = fitting >= 3 ? static_cast<int64_t>(fitting) : 1;
  }
  std::vector<int64_t> bin_of(n), start(bins[0] * bins[1] * bins[2] + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    int64_t b = 0;
    for (int a = 0; a < 3; ++a) {
      const double x = Wrap(packing.positions[i][a], packing.cell[a]);
      const auto k = static_cast<int64_t>(x / packing.cell[a] * bins[a]);
      b = b * bins[a] + std::clamp<int64_t>(k, 0, bins[a] - 1);
    }
    bin_of[i] = b;
    ++start[b + 1];
  }
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<size_t> members(n);
  {
    std::vector<int64_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; ++i) members[fill[bin_of[i]]++] = i;
  }
  const double limit = kValidityLimits.overlap_failure;
  for (size_t i = 0; i < n; ++i) {
    const int64_t b = bin_of[i];
    const int64_t home[3] = {b / (bins[1] * bins[2]), (b / bins[2]) % bins[1], b % bins[2]};
    const int reach_x = bins[0] >= 3, reach_y = bins[1] >= 3, reach_z = bins[2] >= 3;
    for (int ox = -reach_x; ox <= reach_x; ++ox) {
      for (int oy = -reach_y; oy <= reach_y; ++oy) {
        for (int oz = -reach_z; oz <= reach_z; ++oz) {
          const int64_t nx = (home[0] + ox + bins[0]) % bins[0];
          const int64_t ny = (home[1] + oy + bins[1]) % bins[1];
          const int64_t nz = (home[2] + oz + bins[2]) % bins[2];
          const int64_t nb = (nx * bins[1] + ny) * bins[2] + nz;
          for (int64_t m = start[nb]; m < start[nb + 1]; ++m) {
            const size_t j = members[m];
            if (j <= i) continue;
            double distance2 = 0.0;
            for (int a = 0; a < 3; ++a) {
              double delta = packing.positions[j][a] - packing.positions[i][a];
              delta -= packing.cell[a] * std::nearbyint(delta / packing.cell[a]);
              distance2 += delta * delta;
            }
            const double contact = packing.radii[i] + packing.radii[j];
            if (distance2 >= contact * contact) continue;
            const double distance = std::sqrt(distance2);
            const double relative = (contact - distance) / contact;
            if (relative >= limit) return OverlapPair{i, j, distance, relative};
          }
        }
      }
    }
  }
  return std::nullopt;
}

std::string OverlapText(const Packing& packing, const OverlapPair& pair) {
  const double r_i = packing.radii[pair.i], r_j = packing.radii[pair.j];
  const std::string limit = fmt::format(
      "at most {:.3g} % of the sum of the radii is accepted (the run's failure "
      "limit, dem/stage_validity.h)",
      100 * kValidityLimits.overlap_failure);
  if (pair.distance <= 1e-9 * (r_i + r_j)) {
    return fmt::format("spheres are coincident (centres {:.3g} m apart, radii {} and {} m); {}",
                       pair.distance, Num(r_i), Num(r_j), limit);
  }
  return fmt::format(
      "spheres overlap by {:.3g} % of the sum of their radii (centres {:.6g} m apart, radii {} "
      "and {} m); {}",
      100 * pair.relative, pair.distance, Num(r_i), Num(r_j), limit);
}

}  // namespace

Packing Packing::ReadText(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot open packing file '" + path + "'");
  Packing packing;
  std::string line;
  int64_t line_number = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}: line {}: {}", path, line_number, what));
  };
  // The fields of the next line that is not blank or a comment; false at the end.
  std::vector<std::string> fields;
  auto next = [&] {
    while (std::getline(file, line)) {
      ++line_number;
      const size_t first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      fields = SplitFields(line);
      return true;
    }
    return false;
  };
  if (!next()) {
    throw InputError(path +
                     ": the packing file is empty: expected the header 'N Lx Ly Lz' (sphere "
                     "count, cell sides in metres)");
  }
  const int64_t header_line = line_number;
  if (fields.size() != 4) {
    fail(fmt::format(
        "the header '{}' has {} fields; expected exactly 4: 'N Lx Ly Lz' (sphere count, cell "
        "sides in metres)",
        Shown(line), fields.size()));
  }
  const std::string& count_text = fields[0];
  if (count_text.find_first_not_of("0123456789") != std::string::npos) {
    fail(fmt::format(
        "sphere count '{}' must be a positive integer written with digits only (header 'N Lx Ly "
        "Lz')",
        count_text));
  }
  const size_t max_digits = std::to_string(kMaxPackingSpheres).size();
  const size_t digits =
      count_text.size() - std::min(count_text.find_first_not_of('0'), count_text.size());
  const uint64_t count = digits > max_digits ? UINT64_MAX : std::stoull(count_text);
  if (count == 0 || count > kMaxPackingSpheres) {
    fail(fmt::format("sphere count {} must be in [1, {}]", count_text, kMaxPackingSpheres));
  }
  for (int a = 0; a < 3; ++a) {
    if (!ParseFinite(fields[1 + a], &packing.cell[a])) {
      fail(fmt::format("cell side L{} '{}' is not a finite number (header 'N Lx Ly Lz', metres)",
                       kAxis[a], fields[1 + a]));
    }
    const std::string problem = CellSideProblem(a, packing.cell[a]);
    if (!problem.empty()) fail(problem);
  }
  // Not count: a wrong header must not allocate gigabytes before the rows say so.
  const size_t expected = std::min<uint64_t>(count, uint64_t{1} << 20);
  packing.positions.reserve(expected);
  packing.radii.reserve(expected);
  std::vector<int64_t> lines;
  lines.reserve(expected);
  while (packing.size() < count) {
    if (!next()) {
      throw InputError(fmt::format(
          "{}: the header (line {}) announces {} spheres, but the file ends after {} (at line {})",
          path, header_line, count, packing.size(), line_number));
    }
    if (fields.size() != 4) {
      fail(fmt::format("sphere {} '{}' has {} fields; expected exactly 4: 'x y z r' in metres",
                       packing.size() + 1, Shown(line), fields.size()));
    }
    double values[4];
    for (int k = 0; k < 4; ++k) {
      if (!ParseFinite(fields[k], &values[k])) {
        fail(
            fmt::format("field {} ('{}') of sphere {} is not a finite number; expected 'x y z r' "
                        "in metres",
                        k + 1, fields[k], packing.size() + 1));
      }
    }
    const std::array<double, 3> x = {values[0], values[1], values[2]};
    const std::string problem = SphereProblem(x, values[3], packing.cell);
    if (!problem.empty()) fail(problem);
    packing.positions.push_back(
        {Wrap(x[0], packing.cell[0]), Wrap(x[1], packing.cell[1]), Wrap(x[2], packing.cell[2])});
    packing.radii.push_back(values[3]);
    lines.push_back(line_number);
  }
  if (next()) {
    fail(fmt::format(
        "'{}' follows the {} spheres that the header (line {}) announces; the count must equal "
        "the number of rows (only blank lines and '#' comments may follow)",
        Shown(line), count, header_line));
  }
  const size_t largest =
      std::max_element(packing.radii.begin(), packing.radii.end()) - packing.radii.begin();
  const std::string grid = GridProblem(packing.cell, 2.0 * packing.radii[largest]);
  if (!grid.empty()) {
    throw InputError(
        fmt::format("{}: lines {} and {}: {}", path, header_line, lines[largest], grid));
  }
  if (const auto pair = FindExcessiveOverlap(packing)) {
    throw InputError(fmt::format("{}: lines {} and {}: {}", path, lines[pair->i], lines[pair->j],
                                 OverlapText(packing, *pair)));
  }
  return packing;
}

void Packing::Validate(const std::string& origin) const {
  auto fail = [&](const std::string& what) { throw InputError(origin + ": " + what); };
  if (radii.empty()) fail("no spheres: a packing needs at least one");
  if (positions.size() != radii.size()) {
    fail(fmt::format("{} positions for {} radii", positions.size(), radii.size()));
  }
  if (size() > kMaxPackingSpheres) {
    fail(fmt::format("{} spheres; at most {}", size(), kMaxPackingSpheres));
  }
  for (int a = 0; a < 3; ++a) {
    const std::string problem = CellSideProblem(a, cell[a]);
    if (!problem.empty()) fail(problem);
  }
  for (size_t i = 0; i < size(); ++i) {
    const std::string problem = SphereProblem(positions[i], radii[i], cell);
    if (!problem.empty()) fail(fmt::format("sphere {}: {}", i + 1, problem));
  }
  const size_t largest = std::max_element(radii.begin(), radii.end()) - radii.begin();
  const std::string grid = GridProblem(cell, 2.0 * radii[largest]);
  if (!grid.empty()) fail(fmt::format("sphere {}: {}", largest + 1, grid));
  if (const auto pair = FindExcessiveOverlap(*this)) {
    fail(fmt::format("spheres {} and {}: {}", pair->i + 1, pair->j + 1, OverlapText(*this, *pair)));
  }
}

void Packing::WriteText(const std::string& path) const {
  Validate(path + " (to be written)");
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
  if (count > kMaxPackingSpheres) {
    return *why = fmt::format("count {} must be at most {}", count, kMaxPackingSpheres), false;
  }
  if (!(cell_size > 0) || !std::isfinite(cell_size)) {
    return *why = "cell_size must be a finite number > 0", false;
  }
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

GenerationEstimate EstimateGeneration(const GrainSizeDistribution& gsd,
                                      const GenerationOptions& options) {
  GenerationEstimate estimate;
  if (options.count == 0) return estimate;
  const double count = static_cast<double>(options.count);
  const double side = options.cell_size;
  const double r_max = gsd.QuantileRadius(0, options.count);
  estimate.largest_diameter = 2.0 * r_max;
  estimate.cells_per_sphere = CellsPerLargestSphere({side, side, side}, estimate.largest_diameter);
  // As GeneratePacking: bins of side >= 2 r_max, or one bin.
  const double fitting = std::floor(side / (2.0 * r_max));
  const double bins = fitting >= 3 ? fitting : 1;
  estimate.grid_cells = bins * bins * bins;
  // Radii and positions (doubles), the grid's next and head links (ints).
  estimate.bytes = count * (4 * sizeof(double) + sizeof(int)) + estimate.grid_cells * sizeof(int);
  // The quantile diameters d_k = Q(u_k), u_k = (k + ½)/N, of a non-decreasing
  // Q: (1/N) Σ Q(u_k)³ ≥ ∫₀^{1−1/(2N)} Q³ du ≥ E[d³] − Q(1)³/(2N), so the
  // solid volume is at least N V̄ − V(d_top)/2 (less a rounding margin).
  const double d_top = gsd.diameters().back();
  const double lower = count * gsd.MeanSphereVolume() - 0.5 * kPi / 6.0 * d_top * d_top * d_top;
  estimate.min_solid_fraction = std::max(0.0, lower / (side * side * side)) * (1.0 - 1e-9);
  return estimate;
}

double PhysicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0.0;
  return static_cast<double>(pages) * static_cast<double>(page_size);
}

void CheckGenerationFits(const GrainSizeDistribution& gsd, const GenerationOptions& options,
                         double physical_memory) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("sample generation: " + why);
  const GenerationEstimate estimate = EstimateGeneration(gsd, options);
  const double side = options.cell_size;
  const double d_max = estimate.largest_diameter;
  if (side < 2.0 * d_max) {
    throw InputError(fmt::format(
        "sample generation: cell side {:.6g} mm must be at least twice the largest generated "
        "diameter {:.6g} mm (GSD '{}' reaches {:.6g} mm at {}), since a sphere may not reach "
        "its own periodic image: enlarge cell_size",
        side * 1e3, d_max * 1e3, gsd.origin(), gsd.max_diameter() * 1e3,
        gsd.RowName(gsd.MaxDiameterRow())));
  }
  if (!(estimate.cells_per_sphere <= kMaxCellsPerLargestSphere)) {
    throw InputError(fmt::format(
        "sample generation: a {:.6g} mm cell holds {:.3g} cubes of the largest generated "
        "diameter {:.6g} mm (GSD '{}' reaches {:.6g} mm at {}); at most {:.3g} (2^30) are "
        "supported, since the placement grid and the run's neighbour grid grow with it: are the "
        "diameters in mm (not metres)? Otherwise reduce cell_size",
        side * 1e3, estimate.cells_per_sphere, d_max * 1e3, gsd.origin(), gsd.max_diameter() * 1e3,
        gsd.RowName(gsd.MaxDiameterRow()), kMaxCellsPerLargestSphere));
  }
  if (physical_memory > 0 && estimate.bytes > physical_memory) {
    throw InputError(fmt::format(
        "sample generation: {} spheres need about {:.3g} GB of memory (radii, positions and a "
        "placement grid of {:.3g} bins) for the generation alone, more than the {:.3g} GB of "
        "physical memory of this machine: reduce count",
        options.count, estimate.bytes / 1e9, estimate.grid_cells, physical_memory / 1e9));
  }
  if (estimate.min_solid_fraction >= kMaxGenerationSolidFraction) {
    throw InputError(fmt::format(
        "sample generation: {} spheres fill at least {:.3g} % of a {:.6g} mm cube; random "
        "placement needs a solid fraction below {:.3g} %: enlarge cell_size or reduce count",
        options.count, 100 * estimate.min_solid_fraction, side * 1e3,
        100 * kMaxGenerationSolidFraction));
  }
}

Packing GeneratePacking(const GrainSizeDistribution& gsd, const GenerationOptions& options,
                        GenerationReport* report) {
  // Before any allocation that grows with the count or the grid.
  CheckGenerationFits(gsd, options, PhysicalMemoryBytes());
  Stopwatch stopwatch;
  Packing packing;
  packing.cell = {options.cell_size, options.cell_size, options.cell_size};
  packing.radii = gsd.QuantileRadii(options.count);  // descending: largest placed first
  const double r_max = packing.radii.front();
  const double side = options.cell_size;
  const double solid = packing.SolidVolume() / (side * side * side);
  if (solid >= kMaxGenerationSolidFraction) {
    throw InputError(fmt::format(
        "sample generation: {} spheres fill {:.3g} % of a {:.6g} mm cube; random placement "
        "needs a solid fraction below {:.3g} %: enlarge cell_size or reduce count",
        options.count, 100 * solid, side * 1e3, 100 * kMaxGenerationSolidFraction));
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
      throw InputError(fmt::format(
          "sample generation: could not place sphere {} of {} (radius {:.6g} mm) after {} "
          "random attempts; the target solid fraction {:.3g} is too dense for random placement: "
          "enlarge cell_size or reduce count",
          i + 1, options.count, r * 1e3, options.max_attempts, solid));
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
