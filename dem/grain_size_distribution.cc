#include "dem/grain_size_distribution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/csv_table.h"
#include "common/error.h"

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
                                             std::string origin)
    : diameters_(std::move(diameters)),
      percent_passing_(std::move(percent_passing)),
      origin_(std::move(origin)) {
  const size_t n = diameters_.size();
  if (n != percent_passing_.size()) {
    throw InputError(origin_ + ": " + std::to_string(n) + " diameters but " +
                     std::to_string(percent_passing_.size()) + " percentages");
  }
  if (n < 2)
    throw InputError(origin_ + ": a GSD needs at least two sieves, got " + std::to_string(n));
  for (size_t k = 0; k < n; ++k) {
    const std::string row = origin_ + ": row " + std::to_string(k + 1) + ": ";
    if (!(diameters_[k] > 0)) {
      throw InputError(row + "diameter " + Number(diameters_[k] * 1e3) + " mm must be > 0");
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
  if (percent_passing_.front() != 0.0 || percent_passing_.back() != 100.0) {
    throw InputError(origin_ + ": percent passing must start at 0 and end at 100 (got " +
                     Number(percent_passing_.front()) + " and " + Number(percent_passing_.back()) +
                     ")");
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
  std::vector<double> diameters = table.ColumnValues("diameter_mm");
  for (double& d : diameters) d *= 1e-3;
  return GrainSizeDistribution(diameters, table.ColumnValues("percent_passing_by_mass"), path);
}

std::string GrainSizeDistribution::DefaultPath() {
  if (const char* dir = std::getenv("GRANASYM_DATA_DIR")) {
    return std::string(dir) + "/gsd_zbraslav_reduced.csv";
  }
  return std::string(GRANASYM_DATA_DIR) + "/gsd_zbraslav_reduced.csv";
}

GrainSizeDistribution GrainSizeDistribution::Default() { return ReadCsv(DefaultPath()); }

double GrainSizeDistribution::min_diameter() const {
  size_t k = 0;
  while (k + 1 < percent_passing_.size() && percent_passing_[k + 1] == 0.0) ++k;
  return diameters_[k];
}

double GrainSizeDistribution::max_diameter() const {
  size_t k = 0;
  while (percent_passing_[k] < 100.0) ++k;
  return diameters_[k];
}

std::vector<double> GrainSizeDistribution::QuantileRadii(size_t count) const {
  std::vector<double> radii(count);
  const double total = number_cdf_.back();
  size_t segment = 1;
  for (size_t k = 0; k < count; ++k) {
    // Descending radii: quantile from the top of the number CDF.
    const double target = total * (1.0 - (static_cast<double>(k) + 0.5) / count);
    segment = 1;
    while (segment + 1 < number_cdf_.size() && number_cdf_[segment] < target) ++segment;
    const double a = diameters_[segment - 1], b = diameters_[segment];
    const double mass = (percent_passing_[segment] - percent_passing_[segment - 1]) / 100.0;
    const double c = mass / std::log(b / a);
    // Solve (c/3)(a⁻³ − d⁻³) = target − N(a) for d.
    const double inverse_cube = std::pow(a, -3) - 3.0 * (target - number_cdf_[segment - 1]) / c;
    const double d = std::clamp(std::pow(inverse_cube, -1.0 / 3.0), a, b);
    radii[k] = 0.5 * d;
  }
  return radii;
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
