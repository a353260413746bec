#include "TrajectoryObserver.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(observer, fldsim::TrajectoryObserver, "trajectory", "1.0.0",
              "H5MD trajectory: box, wrapped centres, quaternions, Lees-Edwards offset (optionally nodes)")
