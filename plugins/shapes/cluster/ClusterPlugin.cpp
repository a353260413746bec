#include "ClusterShape.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(shape, fldsim::shapes::ClusterShape, "cluster", "1.0.0",
              "a rigid union of spheres given as rows [x, y, z, r]")
