// The nearest periodic image of a pair in the engine's scaled coordinates
// (positions divided by the cell sides of a diagonal cell).
#pragma once

#include "dem/vec.h"

namespace granasym::dem {

// Minimum image of a scaled separation: delta minus its nearest integer,
// rounded by adding and subtracting 1.5·2^52 (exact for |delta| < 2^51 in the
// default rounding mode; no int conversion and no SSE4.1 round needed). For
// a double, or for a GCC vector of doubles lane by lane (the same operations
// on each lane, so the same results).
template <class Real>
inline Real MinimumImage(Real delta) {
  constexpr double kRound = 6755399441055744.0;
  return delta - ((delta + kRound) - kRound);
}

// The branch vector l = x_j + s − x_i of the nearest image of j, from scaled
// positions and the cell sides (m).
inline Vec3 Branch(const Vec4& pi, const Vec4& pj, double lx, double ly, double lz) {
  return {lx * MinimumImage(pj.x - pi.x), ly * MinimumImage(pj.y - pi.y),
          lz * MinimumImage(pj.z - pi.z)};
}

}  // namespace granasym::dem
