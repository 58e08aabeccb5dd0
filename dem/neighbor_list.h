// Verlet neighbour list of a periodic, affinely deforming box, built from a
// cell list; carries the contact history of each pair (shear force, rolling
// moment) across rebuilds.
//
// Half list in CSR form: for particle i the neighbours j > i lie in
// neighbors()[offsets()[i] .. offsets()[i+1]), ascending, each with its stored
// shear force and (with rolling resistance) rolling moment. A pair is listed when its minimum-image
// gap is below the skin. The list stays valid while (Rebuild criterion, rigorous for a diagonal
// cell)
//   2 max_i |δx_i| + ε (2 r_max + skin) < skin,
// δx_i being the non-affine displacement since the build measured in the
// current metric and ε the largest relative change of a cell side.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dem/vec.h"

namespace granasym::dem {

// The rebuild criterion of a Verlet list of `skin` built at `build_cell`
// (rigorous for a diagonal cell): the list may miss a contact once
//   2 max_displacement + ε (2 max_radius + skin) >= skin,
// ε being the largest relative change of a cell side since the build.
bool VerletListMayMissContact(double max_displacement, const std::array<double, 3>& cell,
                              const std::array<double, 3>& build_cell, double max_radius,
                              double skin);
// The criterion's left side, 2 max_displacement + ε (2 max_radius + skin):
// how much of the skin the pairs may have closed since the build (m).
double VerletSkinUsed(double max_displacement, const std::array<double, 3>& cell,
                      const std::array<double, 3>& build_cell, double max_radius, double skin);
// Factor by which a displacement summed in the metrics of the steps since a
// build can grow when measured in the current metric, while the criterion
// above holds: the side ratios stay within 1 ± ε*, ε* = skin/(2 r_max + skin).
double VerletMetricFactor(double max_radius, double skin);
// max_i |H (s_i − reference_i)|: the largest non-affine displacement since
// the reference positions, in the current metric (m).
double LargestDisplacement(const std::vector<Vec4>& scaled_positions,
                           const std::vector<Vec4>& reference, const std::array<double, 3>& cell,
                           int threads);

class NeighborList {
 public:
  // `scaled_positions` are positions divided by the cell sides (any real
  // value; periodic images are found by rounding). `radii` in metres.
  void Build(const std::vector<Vec4>& scaled_positions, const std::array<double, 3>& cell,
             double skin, int threads);

  // True when the list may miss a contact for the given current state.
  bool NeedsRebuild(double max_displacement, const std::array<double, 3>& cell) const;
  // The largest non-affine displacement since the build, |H (s_i − s_i,build)|
  // in the current metric (m): one pass over the particles.
  double MaxDisplacement(const std::vector<Vec4>& scaled_positions,
                         const std::array<double, 3>& cell, int threads) const;
  // Factor by which a displacement summed in the metrics of the steps since
  // the build can grow when measured in the current metric: the cell side
  // ratios stay within 1 ± ε*, ε* = skin/(2 r_max + skin), or the strain term
  // of the criterion would have forced a rebuild.
  double MetricFactor() const;

  bool built() const { return !offsets_.empty(); }
  const std::vector<int64_t>& offsets() const { return offsets_; }
  const std::vector<int32_t>& neighbors() const { return neighbors_; }
  // The i of each pair (derived from offsets) for loops over flat pair ranges.
  const std::vector<int32_t>& owners() const { return owners_; }
  std::vector<Vec3>& shear() { return shear_; }
  const std::vector<Vec3>& shear() const { return shear_; }
  // Rolling moment on i of each pair (N m); empty unless tracked.
  std::vector<Vec3>& rolling() { return rolling_; }
  const std::vector<Vec3>& rolling() const { return rolling_; }
  size_t pair_count() const { return neighbors_.size(); }
  int64_t builds() const { return builds_; }
  double skin() const { return skin_; }
  double max_radius() const { return max_radius_; }

  // Keep or drop the shear history (a scene without friction keeps none) and
  // the rolling-moment history (kept only with rolling resistance).
  void set_track_shear(bool track) { track_shear_ = track; }
  void set_track_rolling(bool track) { track_rolling_ = track; }

  // Complete state for checkpoints, so that a restart continues with the
  // same pair order (and therefore bit-identical sums).
  struct State {
    std::vector<int64_t> offsets;
    std::vector<int32_t> neighbors;
    std::vector<Vec3> shear;
    std::vector<Vec3> rolling;  // empty unless tracked
    std::vector<Vec4> build_positions;
    std::array<double, 3> build_cell{};
    double skin = 0, max_radius = 0;
    int64_t builds = 0;
  };
  State Save() const;
  void Restore(State state);

 private:
  void DeriveOwners();
  // The history of pairs present in both the current list and the new one
  // (sorted merge per i); zero for new pairs.
  std::vector<Vec3> CarryHistory(const std::vector<Vec3>& history,
                                 const std::vector<int64_t>& offsets,
                                 const std::vector<int32_t>& neighbors, int threads) const;
  std::vector<int64_t> offsets_;
  std::vector<int32_t> neighbors_;
  std::vector<int32_t> owners_;
  std::vector<Vec3> shear_;
  std::vector<Vec3> rolling_;
  std::vector<Vec4> build_positions_;  // scaled positions and radius at the build
  std::array<double, 3> build_cell_{};
  double skin_ = 0;
  double max_radius_ = 0;
  int64_t builds_ = 0;
  bool track_shear_ = true;
  bool track_rolling_ = false;
};

}  // namespace granasym::dem
