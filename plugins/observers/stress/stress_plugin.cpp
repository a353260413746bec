// Plugin `stress`: registers StressObserver (plugins/observers/common).
#include "StressObserver.hpp"
#include "fldsim/plugin.hpp"

namespace {

class StressPlugin : public fldsim::observers::StressObserver {
 public:
  static void describe(fldsim::ParamSchema&) {}
  explicit StressPlugin(const fldsim::Params&) {}
};

}  // namespace

FLDSIM_PLUGIN(
    observer, StressPlugin, "stress", "1.0.0",
    "relative viscosity, N1, N2 and particle pressure split into hydrodynamic, interparticle, Brownian")
