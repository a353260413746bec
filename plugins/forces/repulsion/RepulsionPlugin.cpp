#include "ShortRangeRepulsion.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(force, fldsim::ShortRangeRepulsion, "repulsion", "1.1.0",
              "the paper's short-range node-node repulsion (Kumar & Higdon)")
