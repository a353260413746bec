#include "fldsim-sdk/lubrication/Visibility.hpp"

namespace fldsim::hydro {

namespace {
// True if the point p (relative to the body centre) lies strictly inside a node other than `self`.
bool buried(const Vec3& p, const Vec3* offsets, const double* radii, std::size_t nodes, std::size_t self) {
  for (std::size_t k = 0; k < nodes; ++k) {
    if (k == self) continue;
    if ((p - offsets[k]).squaredNorm() < radii[k] * radii[k]) return true;
  }
  return false;
}
// Smooth counterpart of !buried: product over siblings k of W(d_k / width + 1/2).
double exposure(const Vec3& p, const Vec3* offsets, const double* radii, std::size_t nodes, std::size_t self,
                double width) {
  double w = 1.0;
  for (std::size_t k = 0; k < nodes; ++k) {
    if (k == self) continue;
    const double x = ((p - offsets[k]).norm() - radii[k]) / width + 0.5;
    if (x <= 0.0) return 0.0;
    if (x < 1.0) w *= x * x * x * (10.0 + x * (-15.0 + 6.0 * x));
  }
  return w;
}
}  // namespace

bool nodes_visible(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                   std::size_t a, std::size_t b, const Vec3& r, double cutoff) {
  const double dist = r.norm();
  const double abar = 0.5 * (radii[a] + radii[b]);
  if (dist >= cutoff * abar) return false;
  const Vec3 d = r / dist;
  // Exit points of the centre-to-centre segment on each node's surface, in its body's frame.
  const Vec3 exit_i = offsets_i[a] + radii[a] * d;
  const Vec3 exit_j = offsets_j[b] - radii[b] * d;
  return !buried(exit_i, offsets_i, radii, nodes, a) && !buried(exit_j, offsets_j, radii, nodes, b);
}

double visibility_weight(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                         std::size_t a, std::size_t b, const Vec3& r, double cutoff, double width) {
  if (width <= 0.0) return nodes_visible(offsets_i, offsets_j, radii, nodes, a, b, r, cutoff) ? 1.0 : 0.0;
  const double dist = r.norm();
  if (dist >= cutoff * 0.5 * (radii[a] + radii[b])) return 0.0;
  const Vec3 d = r / dist;
  const double wi = exposure(offsets_i[a] + radii[a] * d, offsets_i, radii, nodes, a, width);
  if (wi == 0.0) return 0.0;
  return wi * exposure(offsets_j[b] - radii[b] * d, offsets_j, radii, nodes, b, width);
}

}  // namespace fldsim::hydro
