// A rigid particle shape made of sphere *nodes*, given in the body frame with the reference
// point at the body's volume centroid. The body's director is the body-frame unit vector that
// orientation observers report (the axis joining the two nodes of a dicolloid).
#pragma once

#include <string>
#include <vector>

#include "fldsim/box.hpp"
#include "fldsim/plugin_base.hpp"

namespace fldsim {

struct Node {
  Vec3 position;  // body frame, relative to the volume centroid
  double radius;
};

class FLDSIM_VISIBLE Shape : public Component {
 public:
  virtual const std::vector<Node>& nodes() const = 0;
  // True volume of the union of the nodes (lens overlaps removed), in a^3.
  virtual double volume() const = 0;
  // Body-frame unit director; (0,0,1) for a sphere (orientation is then meaningless).
  virtual Vec3 director() const { return Vec3::UnitZ(); }
  // Radius of the smallest sphere around the centroid containing every node.
  double bounding_radius() const;
  // False when the shape is a single sphere (no orientation to measure).
  virtual bool anisotropic() const { return nodes().size() > 1; }
};

}  // namespace fldsim
