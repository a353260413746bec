// Minimum image in a cubic periodic box without a Lees-Edwards offset, for differences of
// coordinates that lie within 1.5 box edges (wrapped positions, or node positions within a body's
// size of the box): two comparisons instead of LeesEdwardsBox::minimum_image's calls to round(),
// which dominated the oracle's time.
#pragma once

#include "fldsim/box.hpp"

namespace fldsim::oracle {

inline Vec3 periodic_difference(Vec3 d, double L) {
  const double half = 0.5 * L;
  for (int k = 0; k < 3; ++k) {
    if (d[k] > half) d[k] -= L;
    if (d[k] < -half) d[k] += L;
  }
  return d;
}

}  // namespace fldsim::oracle
