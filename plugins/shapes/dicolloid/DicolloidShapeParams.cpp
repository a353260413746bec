#include "DicolloidShape.hpp"

namespace fldsim::shapes {

void DicolloidShape::describe(ParamSchema& s) {
  s.number("a", 1.0, "a", "radius of node 0").greater(0.0);
  s.number("b", 1.0, "a", "radius of node 1").greater(0.0);
  s.number("c", 0.2, "a", "distance between the two node centres, |a - b| < c < a + b").at_least(0.0);
}

namespace {
double checked_c(const Params& p) {
  const double a = p.number("a"), b = p.number("b"), c = p.number("c");
  if (const auto why = DicolloidShape::invalid_reason(a, b, c); !why.empty()) p.fail("c", why);
  return c;
}
}  // namespace

DicolloidShape::DicolloidShape(const Params& p)
    : DicolloidShape(p.number("a"), p.number("b"), checked_c(p)) {}

}  // namespace fldsim::shapes
