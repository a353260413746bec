#include "fldsim/shape.hpp"

#include <algorithm>

namespace fldsim {

double Shape::bounding_radius() const {
  double r = 0.0;
  for (const auto& n : nodes()) r = std::max(r, n.position.norm() + n.radius);
  return r;
}

}  // namespace fldsim
