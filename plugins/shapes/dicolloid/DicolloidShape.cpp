#include "DicolloidShape.hpp"

#include <cmath>

#include "fldsim-sdk/geometry/SphereUnion.hpp"
#include "fldsim/error.hpp"

namespace fldsim::shapes {

std::string DicolloidShape::invalid_reason(double a, double b, double c) {
  if (!(a > 0.0) || !(b > 0.0)) return "radii a and b must be > 0";
  if (!(c >= 0.0) || !(c < a + b)) return "c must satisfy 0 <= c < a + b (the spheres must touch or overlap)";
  if (c == 0.0 && a == b) return "";
  if (!(c > std::abs(a - b))) return "c must be > |a - b|, otherwise one sphere lies inside the other";
  return "";
}

DicolloidShape::DicolloidShape(double a, double b, double c) {
  if (const auto why = invalid_reason(a, b, c); !why.empty()) throw Error("dicolloid: " + why);
  // Volume V = V_a + V_b - V_lens and centroid (V_b c - V_lens z_lens)/V along the axis, exact.
  const VolumeAndCentroid vc = union_volume_centroid({{Vec3::Zero(), a}, {Vec3(0, 0, c), b}});
  volume_ = vc.volume;
  const double z0 = -vc.centroid.z();
  nodes_.push_back({Vec3(0, 0, z0), a});
  nodes_.push_back({Vec3(0, 0, z0 + c), b});
}

}  // namespace fldsim::shapes
