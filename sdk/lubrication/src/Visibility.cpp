#include "fldsim-sdk/lubrication/Visibility.hpp"

#include "VisibilityAt.hpp"

namespace fldsim::hydro {

bool nodes_visible(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                   std::size_t a, std::size_t b, const Vec3& r, double cutoff) {
  return nodes_visible_at(offsets_i, offsets_j, radii, nodes, a, b, r, r.norm(), cutoff);
}

double visibility_weight(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                         std::size_t a, std::size_t b, const Vec3& r, double cutoff, double width) {
  return visibility_weight_at(offsets_i, offsets_j, radii, nodes, a, b, r, r.norm(), cutoff, width);
}

}  // namespace fldsim::hydro
