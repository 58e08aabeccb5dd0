#include "dem/grain_size_distribution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/csv_table.h"
#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::dem {
namespace {

std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

}  // namespace

GrainSizeDistribution::GrainSizeDistribution(std::vector<double> diameters,
                                             std::vector<double> percent_passing,
                                             std::string origin, std::vector<int> line_numbers)
    : diameters_(std::move(diameters)),
      percent_passing_(std::move(percent_passing)),
      origin_(std::move(origin)),
      line_numbers_(std::move(line_numbers)) {
  const size_t n = diameters_.size();
  if (n != percent_passing_.size()) {
    throw InputError(origin_ + ": " + std::to_string(n) + " diameters but " +
                     std::to_string(percent_passing_.size()) + " percentages");
  }
  GRANASYM_CHECK(line_numbers_.empty() || line_numbers_.size() == n)
      << line_numbers_.size() << " line numbers for " << n << " rows";
  auto where = [&](size_t k) { return origin_ + ": " + RowName(k) + ": "; };
  if (n < 2)
    throw InputError(origin_ + ": a GSD needs at least two sieves, got " + std::to_string(n));
  for (size_t k = 0; k < n; ++k) {
    const std::string row = where(k);
    if (!(diameters_[k] >= kMinSphereDiameter && diameters_[k] <= kMaxSphereDiameter)) {
      throw InputError(row + "diameter " + Number(diameters_[k] * 1e3) +
                       " mm must be a number in [" + Number(kMinSphereDiameter * 1e3) + ", " +
                       Number(kMaxSphereDiameter * 1e3) + "] mm (are the diameters in mm?)");
    }
    if (!(percent_passing_[k] >= 0 && percent_passing_[k] <= 100)) {
      throw InputError(row + "percent passing " + Number(percent_passing_[k]) +
                       " must be in [0, 100]");
    }
    if (k > 0 && !(diameters_[k] > diameters_[k - 1])) {
      throw InputError(row + "diameter " + Number(diameters_[k] * 1e3) +
                       " mm must be larger than the previous " + Number(diameters_[k - 1] * 1e3) +
                       " mm (diameters strictly increasing)");
    }
    if (k > 0 && percent_passing_[k] < percent_passing_[k - 1]) {
      throw InputError(row + "percent passing " + Number(percent_passing_[k]) +
                       " is below the previous " + Number(percent_passing_[k - 1]) +
                       " (the GSD must be non-decreasing)");
    }
  }
  if (percent_passing_.front() != 0.0) {
    throw InputError(where(0) + "percent passing " + Number(percent_passing_.front()) +
                     " at the smallest sieve; the table must start at 0 (add a sieve that "
                     "nothing passes)");
  }
  if (percent_passing_.back() != 100.0) {
    throw InputError(where(n - 1) + "percent passing " + Number(percent_passing_.back()) +
                     " at the largest sieve; the table must end at 100 (add a sieve that "
                     "everything passes)");
  }
  const double ratio = max_diameter() / min_diameter();
  if (!(ratio <= kMaxDiameterRatio)) {
    size_t first = 0;
    while (diameters_[first] != min_diameter()) ++first;
    throw InputError(origin_ + ": the sieves with mass span " + Number(min_diameter() * 1e3) +
                     " mm (" + RowName(first) + ") to " + Number(max_diameter() * 1e3) + " mm (" +
                     RowName(MaxDiameterRow()) + "), a ratio of " + Number(ratio) + "; at most " +
                     Number(kMaxDiameterRatio) +
                     " is supported, since the number of spheres grows as the cube of that ratio "
                     "(are the diameters in mm? use a reduced GSD for DEM samples)");
  }
  number_cdf_.assign(n, 0.0);
  for (size_t k = 1; k < n; ++k) {
    const double mass = (percent_passing_[k] - percent_passing_[k - 1]) / 100.0;
    const double a = diameters_[k - 1], b = diameters_[k];
    const double c = mass / std::log(b / a);
    number_cdf_[k] = number_cdf_[k - 1] + c / 3.0 * (std::pow(a, -3) - std::pow(b, -3));
  }
}

GrainSizeDistribution GrainSizeDistribution::ReadCsv(const std::string& path) {
  const CsvTable table = CsvTable::ReadFile(path);
  table.RequireOnlyColumns({"diameter_mm", "percent_passing_by_mass"});
  std::vector<double> diameters = table.ColumnValues("diameter_mm");
  for (double& d : diameters) d *= 1e-3;
  return GrainSizeDistribution(diameters, table.ColumnValues("percent_passing_by_mass"), path,
                               table.line_numbers);
}

std::string GrainSizeDistribution::DefaultPath() {
  if (const char* dir = std::getenv("GRANASYM_DATA_DIR")) {
    return std::string(dir) + "/gsd_zbraslav_reduced.csv";
  }
  return std::string(GRANASYM_DATA_DIR) + "/gsd_zbraslav_reduced.csv";
}

GrainSizeDistribution GrainSizeDistribution::Default() { return ReadCsv(DefaultPath()); }

std::string GrainSizeDistribution::RowName(size_t k) const {
  return line_numbers_.empty() ? "row " + std::to_string(k + 1)
                               : "line " + std::to_string(line_numbers_[k]);
}

size_t GrainSizeDistribution::MaxDiameterRow() const {
  size_t k = 0;
  while (percent_passing_[k] < 100.0) ++k;
  return k;
}

double GrainSizeDistribution::min_diameter() const {
  size_t k = 0;
  while (k + 1 < percent_passing_.size() && percent_passing_[k + 1] == 0.0) ++k;
  return diameters_[k];
}

double GrainSizeDistribution::max_diameter() const { return diameters_[MaxDiameterRow()]; }

std::vector<double> GrainSizeDistribution::QuantileRadii(size_t count) const {
  std::vector<double> radii(count);
  for (size_t k = 0; k < count; ++k) radii[k] = QuantileRadius(k, count);
  return radii;
}

double GrainSizeDistribution::QuantileRadius(size_t k, size_t count) const {
  const double total = number_cdf_.back();
  // Descending radii: quantile from the top of the number CDF.
  const double target = total * (1.0 - (static_cast<double>(k) + 0.5) / count);
  size_t segment = 1;
  while (segment + 1 < number_cdf_.size() && number_cdf_[segment] < target) ++segment;
  const double a = diameters_[segment - 1], b = diameters_[segment];
  const double mass = (percent_passing_[segment] - percent_passing_[segment - 1]) / 100.0;
  const double c = mass / std::log(b / a);
  // Solve (c/3)(a⁻³ − d⁻³) = target − N(a) for d.
  const double inverse_cube = std::pow(a, -3) - 3.0 * (target - number_cdf_[segment - 1]) / c;
  const double d = std::clamp(std::pow(inverse_cube, -1.0 / 3.0), a, b);
  return 0.5 * d;
}

double GrainSizeDistribution::MeanSphereVolume() const {
  // Per segment ∫ (π/6) d³ dN = (π/6) c ln(b/a) = (π/6) Δm: the volume is the
  // mass fraction, and the number is number_cdf_.
  return kPi / 6.0 / number_cdf_.back();
}

std::vector<double> GrainSizeDistribution::AchievedPercentPassing(
    const std::vector<double>& radii) const {
  std::vector<double> passing(diameters_.size(), 0.0);
  double total = 0.0;
  for (double r : radii) total += r * r * r;
  for (size_t k = 0; k < diameters_.size(); ++k) {
    double below = 0.0;
    for (double r : radii) {
      if (2.0 * r <= diameters_[k] * (1.0 + 1e-12)) below += r * r * r;
    }
    passing[k] = total > 0 ? 100.0 * below / total : 0.0;
  }
  return passing;
}

}  // namespace granasym::dem
