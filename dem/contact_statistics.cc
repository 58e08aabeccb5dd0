#include "dem/contact_statistics.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace granasym::dem {
namespace {

double Percentile(std::vector<double>& values, double fraction) {
  if (values.empty()) return 0.0;
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(fraction * values.size()));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

template <bool kHistogram>
ContactStatistics Measure(const Engine& engine, const std::vector<double>* edges) {
  const auto& s = engine.scaled_positions();
  const auto& offsets = engine.neighbors().offsets();
  const auto& neighbors = engine.neighbors().neighbors();
  const auto& cell = engine.cell();
  const int64_t n = static_cast<int64_t>(s.size());
  std::vector<int32_t> per_particle(n, 0);
  std::vector<double> overlaps;
  ContactStatistics stats;
  if constexpr (kHistogram) stats.histogram.assign(edges->size() - 1, 0);
  for (int64_t i = 0; i < n; ++i) {
    for (int64_t p = offsets[i]; p < offsets[i + 1]; ++p) {
      const int32_t j = neighbors[p];
      double d2 = 0.0;
      const double delta[3] = {s[j].x - s[i].x, s[j].y - s[i].y, s[j].z - s[i].z};
      for (int d = 0; d < 3; ++d) {
        const double image = cell[d] * (delta[d] - std::nearbyint(delta[d]));
        d2 += image * image;
      }
      const double reach = s[i].w + s[j].w;
      if (d2 >= reach * reach) continue;
      const double relative = (reach - std::sqrt(d2)) / reach;
      overlaps.push_back(relative);
      ++per_particle[i];
      ++per_particle[j];
      if constexpr (kHistogram) {
        const auto bin =
            std::upper_bound(edges->begin(), edges->end(), relative) - edges->begin() - 1;
        const auto last = static_cast<std::ptrdiff_t>(stats.histogram.size()) - 1;
        ++stats.histogram[std::clamp<std::ptrdiff_t>(bin, 0, last)];
      }
    }
  }
  stats.contacts = static_cast<int64_t>(overlaps.size());
  stats.coordination = n > 0 ? 2.0 * stats.contacts / n : 0.0;
  int64_t none = 0, single = 0;
  for (int32_t c : per_particle) {
    none += c == 0;
    single += c == 1;
  }
  const int64_t mechanical = n - none - single;
  stats.mechanical_coordination =
      mechanical > 0 ? static_cast<double>(2 * stats.contacts - single) / mechanical : 0.0;
  if (!overlaps.empty()) {
    double sum = 0.0;
    for (double u : overlaps) sum += u;
    stats.overlap_mean = sum / overlaps.size();
    stats.overlap_max = *std::max_element(overlaps.begin(), overlaps.end());
    stats.overlap_p50 = Percentile(overlaps, 0.50);
    stats.overlap_p90 = Percentile(overlaps, 0.90);
    stats.overlap_p99 = Percentile(overlaps, 0.99);
  }
  return stats;
}

}  // namespace

std::vector<double> LogarithmicEdges(double low, double high, int bins) {
  GRANASYM_CHECK(low > 0 && high > low && bins > 0);
  std::vector<double> edges(bins + 1);
  for (int k = 0; k <= bins; ++k) edges[k] = low * std::pow(high / low, double(k) / bins);
  return edges;
}

ContactStatistics MeasureContacts(const Engine& engine, const std::vector<double>* edges) {
  return edges ? Measure<true>(engine, edges) : Measure<false>(engine, nullptr);
}

double KineticEnergy(const Engine& engine) {
  double energy = 0.0;
  const auto& v = engine.velocities();
  const auto& w = engine.spins();
  const bool rotation = engine.material().has_friction();
  for (size_t i = 0; i < v.size(); ++i) {
    energy += 0.5 * (v[i].x * v[i].x + v[i].y * v[i].y + v[i].z * v[i].z) / v[i].w;
    if (rotation) energy += 0.5 * (w[i].x * w[i].x + w[i].y * w[i].y + w[i].z * w[i].z) / w[i].w;
  }
  return energy;
}

double UnbalancedForceRatio(const Engine& engine) {
  const auto& sums = engine.sums();
  if (sums.contacts == 0 || sums.force_sum <= 0) return 0.0;
  double net = 0.0;
  for (const Vec4& f : engine.forces()) net += std::sqrt(f.x * f.x + f.y * f.y + f.z * f.z);
  const double mean_net = net / static_cast<double>(engine.size());
  const double mean_contact = sums.force_sum / static_cast<double>(sums.contacts);
  return mean_net / mean_contact;
}

}  // namespace granasym::dem
