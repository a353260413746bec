#include "SphereShape.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(shape, fldsim::shapes::SphereShape, "sphere", "1.0.0", "a single sphere of radius a")
