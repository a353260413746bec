// A single sphere of radius a: one node at the centre, no orientation.
#pragma once

#include "fldsim/params.hpp"
#include "fldsim/shape.hpp"

namespace fldsim::shapes {

class SphereShape : public Shape {
 public:
  explicit SphereShape(double a = 1.0);
  explicit SphereShape(const Params& p);
  static void describe(ParamSchema& s);

  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override;
  bool anisotropic() const override { return false; }

 private:
  std::vector<Node> nodes_;
};

}  // namespace fldsim::shapes
