// Plugin `diffusion`: registers DiffusionObserver (plugins/observers/common).
#include "DiffusionObserver.hpp"
#include "fldsim/plugin.hpp"

namespace {

class DiffusionPlugin : public fldsim::observers::DiffusionObserver {
 public:
  static void describe(fldsim::ParamSchema& s) {
    s.number("max_lag", 10.0, "time", "largest lag, in the run's time unit").greater(0.0);
    s.integer("lags", 20, "", "number of log-spaced lags").at_least(1).at_most(1000);
    // Each origin keeps every body's reference position: the bound keeps that in memory.
    s.integer("origins", 20, "", "time origins held in memory at once (sets their spacing)")
        .at_least(1)
        .at_most(10000);
  }
  explicit DiffusionPlugin(const fldsim::Params& p)
      : DiffusionObserver({p.number("max_lag"), static_cast<int>(p.integer("lags")),
                           static_cast<int>(p.integer("origins"))}) {}
};

}  // namespace

FLDSIM_PLUGIN(observer, DiffusionPlugin, "diffusion", "1.0.0",
              "shear-corrected MSD per axis, director autocorrelations, D_short, D_long and D_r")
