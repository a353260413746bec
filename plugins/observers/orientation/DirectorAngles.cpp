#include "DirectorAngles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fldsim::observers {

DirectorAngles director_angles(const Vec3& n_raw) {
  const Vec3 n = n_raw.normalized();
  const double theta = std::acos(std::min(1.0, std::abs(n.z())));
  // atan2(x, y): angle from +y towards +x; then fold by pi into (-pi/2, pi/2] (n and -n, and
  // the mirror z -> -z that the theta folding implies, map (x, y) to (-x, -y)), so that the flow
  // axis is +pi/2 whichever way the director points along it.
  double phi = std::atan2(n.x(), n.y());
  if (phi > 0.5 * std::numbers::pi) phi -= std::numbers::pi;
  if (phi <= -0.5 * std::numbers::pi) phi += std::numbers::pi;
  return {theta, phi};
}

}  // namespace fldsim::observers
