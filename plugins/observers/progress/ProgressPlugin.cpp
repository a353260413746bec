#include "ProgressObserver.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(observer, fldsim::ProgressObserver, "progress", "1.0.0",
              "live progress on stderr: steps/s over a moving window, ETA, minimum gap, CG iterations")
