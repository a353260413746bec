#include "SphereShape.hpp"

namespace fldsim::shapes {

void SphereShape::describe(ParamSchema& s) {
  s.number("a", 1.0, "a", "sphere radius").greater(0.0);
}

SphereShape::SphereShape(const Params& p) : SphereShape(p.number("a")) {}

}  // namespace fldsim::shapes
