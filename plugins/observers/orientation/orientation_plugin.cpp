// Plugin `orientation`: registers OrientationObserver (plugins/observers/common).
#include "OrientationObserver.hpp"
#include "fldsim/plugin.hpp"

namespace {

class OrientationPlugin : public fldsim::observers::OrientationObserver {
 public:
  static void describe(fldsim::ParamSchema& s) {
    s.integer("bins", 18, "",
              "theta bins over [0, pi/2]; phi gets twice as many over [-pi/2, pi/2] (same width)")
        .at_least(1);
  }
  explicit OrientationPlugin(const fldsim::Params& p) : OrientationObserver(config(p)) {}

 private:
  static fldsim::observers::OrientationConfig config(const fldsim::Params& p) {
    const int bins = static_cast<int>(p.integer("bins"));
    return {bins, 2 * bins};
  }
};

}  // namespace

FLDSIM_PLUGIN(observer, OrientationPlugin, "orientation", "1.0.0",
              "P(theta), P(phi), theta_m, phi_m, S_ii, the order tensor of the directors and the "
              "decorrelation_time of their averages (is the run long enough?)")
