#include "SphereShape.hpp"

#include <numbers>

#include "fldsim/error.hpp"

namespace fldsim::shapes {

SphereShape::SphereShape(double a) {
  if (!(a > 0.0)) throw Error("sphere: radius a must be > 0");
  nodes_.push_back({Vec3::Zero(), a});
}

double SphereShape::volume() const {
  const double a = nodes_[0].radius;
  return 4.0 / 3.0 * std::numbers::pi * a * a * a;
}

}  // namespace fldsim::shapes
