#include "dem/neighbor_list.h"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace granasym::dem {

void NeighborList::Build(const std::vector<Vec4>& s, const std::array<double, 3>& cell, double skin,
                         int threads) {
  const int64_t n = static_cast<int64_t>(s.size());
  double max_radius = 0.0;
  for (const Vec4& p : s) max_radius = std::max(max_radius, p.w);
  const double reach = 2.0 * max_radius + skin;
  for (int d = 0; d < 3; ++d) {
    if (!(cell[d] > 2.0 * reach)) {
      throw RuntimeError(fmt::format(
          "the periodic cell side {:.6g} mm has become smaller than twice the interaction reach "
          "{:.6g} mm (largest diameter + skin): the cell is too small for its largest spheres; "
          "use more particles",
          cell[d] * 1e3, reach * 1e3));
    }
  }
  // Bins of side >= reach; with fewer than three bins along an axis one bin
  // spans it (the neighbourhood would otherwise visit a bin twice).
  std::array<int, 3> bins;
  for (int d = 0; d < 3; ++d) {
    const int fitting = static_cast<int>(cell[d] / reach);
    bins[d] = fitting >= 3 ? fitting : 1;
  }
  const int64_t bin_count = int64_t{bins[0]} * bins[1] * bins[2];
  auto wrap01 = [](double x) { return x - std::floor(x); };
  std::vector<int32_t> bin_of(n);
  std::vector<int64_t> bin_start(bin_count + 1, 0);
  for (int64_t i = 0; i < n; ++i) {
    const int bx = std::min(bins[0] - 1, static_cast<int>(wrap01(s[i].x) * bins[0]));
    const int by = std::min(bins[1] - 1, static_cast<int>(wrap01(s[i].y) * bins[1]));
    const int bz = std::min(bins[2] - 1, static_cast<int>(wrap01(s[i].z) * bins[2]));
    bin_of[i] = static_cast<int32_t>((int64_t{bx} * bins[1] + by) * bins[2] + bz);
    ++bin_start[bin_of[i] + 1];
  }
  for (int64_t b = 0; b < bin_count; ++b) bin_start[b + 1] += bin_start[b];
  std::vector<int32_t> members(n);
  {
    std::vector<int64_t> fill(bin_start.begin(), bin_start.end() - 1);
    for (int64_t i = 0; i < n; ++i) members[fill[bin_of[i]]++] = static_cast<int32_t>(i);
  }
  // Unique neighbouring bins of each axis offset.
  std::array<std::vector<int>, 3> offsets_of_axis;
  for (int d = 0; d < 3; ++d) {
    if (bins[d] >= 3)
      offsets_of_axis[d] = {-1, 0, 1};
    else
      offsets_of_axis[d] = {0};
  }

  // Each thread lists the pairs of a contiguous range of i, ascending j per i.
  const int thread_count = std::max(1, threads);
  std::vector<std::vector<int32_t>> chunk_neighbors(thread_count);
  std::vector<int64_t> counts(n, 0);
#pragma omp parallel num_threads(thread_count)
  {
    const int t = omp_get_thread_num();
    const int64_t begin = n * t / thread_count, end = n * (t + 1) / thread_count;
    std::vector<int32_t>& local = chunk_neighbors[t];
    local.reserve(static_cast<size_t>((end - begin) * 8));
    for (int64_t i = begin; i < end; ++i) {
      const size_t first = local.size();
      const int32_t b = bin_of[i];
      const int bx = b / (bins[1] * bins[2]), by = (b / bins[2]) % bins[1], bz = b % bins[2];
      for (int ox : offsets_of_axis[0]) {
        const int nx = (bx + ox + bins[0]) % bins[0];
        for (int oy : offsets_of_axis[1]) {
          const int ny = (by + oy + bins[1]) % bins[1];
          for (int oz : offsets_of_axis[2]) {
            const int nz = (bz + oz + bins[2]) % bins[2];
            const int64_t nb = (int64_t{nx} * bins[1] + ny) * bins[2] + nz;
            for (int64_t m = bin_start[nb]; m < bin_start[nb + 1]; ++m) {
              const int32_t j = members[m];
              if (j <= i) continue;
              double dx = s[j].x - s[i].x, dy = s[j].y - s[i].y, dz = s[j].z - s[i].z;
              dx = cell[0] * (dx - std::nearbyint(dx));
              dy = cell[1] * (dy - std::nearbyint(dy));
              dz = cell[2] * (dz - std::nearbyint(dz));
              const double cut = s[i].w + s[j].w + skin;
              if (dx * dx + dy * dy + dz * dz < cut * cut) local.push_back(j);
            }
          }
        }
      }
      std::sort(local.begin() + first, local.end());
      counts[i] = static_cast<int64_t>(local.size() - first);
    }
  }
  std::vector<int64_t> offsets(n + 1, 0);
  for (int64_t i = 0; i < n; ++i) offsets[i + 1] = offsets[i] + counts[i];
  std::vector<int32_t> neighbors(offsets[n]);
  {
    int64_t position = 0;
    for (const auto& local : chunk_neighbors) {
      std::copy(local.begin(), local.end(), neighbors.begin() + position);
      position += static_cast<int64_t>(local.size());
    }
  }
  // Carry the history of pairs present in both lists.
  std::vector<Vec3> shear, rolling;
  if (track_shear_) shear = CarryHistory(shear_, offsets, neighbors, thread_count);
  if (track_rolling_) rolling = CarryHistory(rolling_, offsets, neighbors, thread_count);
  offsets_ = std::move(offsets);
  neighbors_ = std::move(neighbors);
  shear_ = std::move(shear);
  rolling_ = std::move(rolling);
  DeriveOwners();
  build_positions_ = s;
  build_cell_ = cell;
  skin_ = skin;
  max_radius_ = max_radius;
  ++builds_;
}

std::vector<Vec3> NeighborList::CarryHistory(const std::vector<Vec3>& history,
                                             const std::vector<int64_t>& offsets,
                                             const std::vector<int32_t>& neighbors,
                                             int threads) const {
  std::vector<Vec3> carried(neighbors.size(), Vec3{});
  const int64_t n = static_cast<int64_t>(offsets.size()) - 1;
  // A first build, or a history of another list (restored from elsewhere), has nothing to carry.
  if (offsets_.size() != offsets.size() || history.size() != neighbors_.size()) return carried;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int64_t i = 0; i < n; ++i) {
    int64_t a = offsets_[i];
    const int64_t a_end = offsets_[i + 1];
    for (int64_t p = offsets[i]; p < offsets[i + 1]; ++p) {
      while (a < a_end && neighbors_[a] < neighbors[p]) ++a;
      if (a < a_end && neighbors_[a] == neighbors[p]) carried[p] = history[a];
    }
  }
  return carried;
}

double VerletSkinUsed(double max_displacement, const std::array<double, 3>& cell,
                      const std::array<double, 3>& build_cell, double max_radius, double skin) {
  double strain = 0.0;
  for (int d = 0; d < 3; ++d) strain = std::max(strain, std::abs(cell[d] / build_cell[d] - 1.0));
  return 2.0 * max_displacement + strain * (2.0 * max_radius + skin);
}

bool VerletListMayMissContact(double max_displacement, const std::array<double, 3>& cell,
                              const std::array<double, 3>& build_cell, double max_radius,
                              double skin) {
  return VerletSkinUsed(max_displacement, cell, build_cell, max_radius, skin) >= skin;
}

double VerletMetricFactor(double max_radius, double skin) {
  const double strain = skin / (2.0 * max_radius + skin);
  return (1.0 + strain) / (1.0 - strain);
}

double LargestDisplacement(const std::vector<Vec4>& s, const std::vector<Vec4>& reference,
                           const std::array<double, 3>& cell, int threads) {
  const int64_t n = static_cast<int64_t>(s.size());
  double max2 = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : max2)
  for (int64_t i = 0; i < n; ++i) {
    const double dx = cell[0] * (s[i].x - reference[i].x);
    const double dy = cell[1] * (s[i].y - reference[i].y);
    const double dz = cell[2] * (s[i].z - reference[i].z);
    max2 = std::max(max2, dx * dx + dy * dy + dz * dz);
  }
  return std::sqrt(max2);
}

bool NeighborList::NeedsRebuild(double max_displacement, const std::array<double, 3>& cell) const {
  if (offsets_.empty()) return true;
  return VerletListMayMissContact(max_displacement, cell, build_cell_, max_radius_, skin_);
}

double NeighborList::MaxDisplacement(const std::vector<Vec4>& s, const std::array<double, 3>& cell,
                                     int threads) const {
  return LargestDisplacement(s, build_positions_, cell, threads);
}

double NeighborList::MetricFactor() const { return VerletMetricFactor(max_radius_, skin_); }

NeighborList::State NeighborList::Save() const {
  return {offsets_,    neighbors_, shear_,      rolling_, build_positions_,
          build_cell_, skin_,      max_radius_, builds_};
}

void NeighborList::Restore(State state) {
  offsets_ = std::move(state.offsets);
  neighbors_ = std::move(state.neighbors);
  shear_ = std::move(state.shear);
  rolling_ = std::move(state.rolling);
  build_positions_ = std::move(state.build_positions);
  build_cell_ = state.build_cell;
  skin_ = state.skin;
  max_radius_ = state.max_radius;
  builds_ = state.builds;
  // A state saved with another material (a fork that adds or drops friction
  // or rolling resistance) carries a history this list does not keep, or
  // none where it keeps one: drop it, or start every pair from zero.
  auto adapt = [&](std::vector<Vec3>& history, bool tracked, const char* what) {
    if (!tracked) {
      history.clear();
    } else if (history.empty()) {
      history.assign(neighbors_.size(), Vec3{});
    }
    GRANASYM_CHECK(history.size() == (tracked ? neighbors_.size() : 0))
        << "the restored list has " << history.size() << " " << what << " for " << neighbors_.size()
        << " pairs";
  };
  adapt(shear_, track_shear_, "shear forces");
  adapt(rolling_, track_rolling_, "rolling moments");
  DeriveOwners();
}

void NeighborList::DeriveOwners() {
  owners_.resize(neighbors_.size());
  const int64_t n = static_cast<int64_t>(offsets_.size()) - 1;
  for (int64_t i = 0; i < n; ++i) {
    std::fill(owners_.begin() + offsets_[i], owners_.begin() + offsets_[i + 1],
              static_cast<int32_t>(i));
  }
}

}  // namespace granasym::dem
