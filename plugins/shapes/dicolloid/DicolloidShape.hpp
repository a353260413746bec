// Dicolloid: two fused spheres of radii a (node 0) and b (node 1) whose centres are a distance c
// apart, |a - b| < c < a + b (c = 0 with a = b is the degenerate single sphere). The nodes lie on
// the body z axis with the exact volume centroid of the union (lens removed) at the origin; the
// director (0,0,1) points from node 0 to node 1.
#pragma once

#include "fldsim/params.hpp"
#include "fldsim/shape.hpp"

namespace fldsim::shapes {

class DicolloidShape : public Shape {
 public:
  DicolloidShape(double a, double b, double c);
  explicit DicolloidShape(const Params& p);
  static void describe(ParamSchema& s);

  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override { return volume_; }
  Vec3 director() const override { return Vec3::UnitZ(); }
  bool anisotropic() const override { return nodes_[0].position != nodes_[1].position; }

  // Why (a, b, c) is not a valid dicolloid, or empty when it is.
  static std::string invalid_reason(double a, double b, double c);

 private:
  std::vector<Node> nodes_;
  double volume_ = 0.0;
};

}  // namespace fldsim::shapes
