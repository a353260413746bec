// A two-node test shape: unit spheres at (0, 0, +-h) in the body frame. Enough for the
// trajectory tests, which only need node positions and radii.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "fldsim/shape.hpp"
#include "fldsim/system.hpp"

namespace fldsim::test {

class TinyDimer : public Shape {
 public:
  explicit TinyDimer(double half_distance)
      : nodes_{{Vec3(0, 0, half_distance), 1.0}, {Vec3(0, 0, -half_distance), 1.0}} {}
  const std::vector<Node>& nodes() const override { return nodes_; }
  // Two unit spheres minus their lens (centre distance c = 2h < 2): 8 pi/3 - pi (4 + c)(2 - c)^2 / 12.
  double volume() const override {
    const double c = 2.0 * std::fabs(nodes_[0].position.z());
    return 8.0 * M_PI / 3.0 - M_PI * (4.0 + c) * (2.0 - c) * (2.0 - c) / 12.0;
  }

 private:
  std::vector<Node> nodes_;
};

inline System tiny_system(std::size_t n, double box_edge) {
  return System(std::make_shared<TinyDimer>(0.5), n, box_edge, Physics{});
}

}  // namespace fldsim::test
