#include "DicolloidShape.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(shape, fldsim::shapes::DicolloidShape, "dicolloid", "1.0.0",
              "two fused spheres of radii a, b with centre distance c")
