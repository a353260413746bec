// The visibility rules of Visibility.hpp with the pair's distance |r| given: the neighbour list
// already holds it (bitwise r.norm(), CellNeighbourList), and the square root and its use were a
// tenth of a dicolloid assembly (bench/README.md, "Dicolloid node pairs: the Gram blocks as outer
// products"). Inline, so that the pair selection loop takes them without a call. Private to the
// lubrication library.
#pragma once

#include "fldsim/shape.hpp"

namespace fldsim::hydro {

namespace visibility_detail {
// True if the point p (relative to the body centre) lies strictly inside a node other than `self`.
inline bool buried(const Vec3& p, const Vec3* offsets, const double* radii, std::size_t nodes,
                   std::size_t self) {
  for (std::size_t k = 0; k < nodes; ++k) {
    if (k == self) continue;
    if ((p - offsets[k]).squaredNorm() < radii[k] * radii[k]) return true;
  }
  return false;
}
// Smooth counterpart of !buried: product over siblings k of W(d_k / width + 1/2).
inline double exposure(const Vec3& p, const Vec3* offsets, const double* radii, std::size_t nodes,
                       std::size_t self, double width) {
  double w = 1.0;
  for (std::size_t k = 0; k < nodes; ++k) {
    if (k == self) continue;
    const double x = ((p - offsets[k]).norm() - radii[k]) / width + 0.5;
    if (x <= 0.0) return 0.0;
    if (x < 1.0) w *= x * x * x * (10.0 + x * (-15.0 + 6.0 * x));
  }
  return w;
}
}  // namespace visibility_detail

inline bool nodes_visible_at(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii,
                             std::size_t nodes, std::size_t a, std::size_t b, const Vec3& r, double dist,
                             double cutoff) {
  const double abar = 0.5 * (radii[a] + radii[b]);
  if (dist >= cutoff * abar) return false;
  const Vec3 d = r / dist;
  // Exit points of the centre-to-centre segment on each node's surface, in its body's frame.
  const Vec3 exit_i = offsets_i[a] + radii[a] * d;
  const Vec3 exit_j = offsets_j[b] - radii[b] * d;
  return !visibility_detail::buried(exit_i, offsets_i, radii, nodes, a) &&
         !visibility_detail::buried(exit_j, offsets_j, radii, nodes, b);
}

inline double visibility_weight_at(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii,
                                   std::size_t nodes, std::size_t a, std::size_t b, const Vec3& r,
                                   double dist, double cutoff, double width) {
  if (width <= 0.0)
    return nodes_visible_at(offsets_i, offsets_j, radii, nodes, a, b, r, dist, cutoff) ? 1.0 : 0.0;
  if (dist >= cutoff * 0.5 * (radii[a] + radii[b])) return 0.0;
  const Vec3 d = r / dist;
  const double wi =
      visibility_detail::exposure(offsets_i[a] + radii[a] * d, offsets_i, radii, nodes, a, width);
  if (wi == 0.0) return 0.0;
  return wi * visibility_detail::exposure(offsets_j[b] - radii[b] * d, offsets_j, radii, nodes, b, width);
}

}  // namespace fldsim::hydro
