// Plugin `pair_distribution`: registers PairDistributionObserver (plugins/observers/common).
#include <sstream>

#include "PairDistributionObserver.hpp"
#include "fldsim/plugin.hpp"

namespace {

using fldsim::observers::Projection;

class PairDistributionPlugin : public fldsim::observers::PairDistributionObserver {
 public:
  static void describe(fldsim::ParamSchema& s) {
    s.number("range", 5.0, "a", "half width of the maps and largest r of g(r) (at most half the box edge)")
        .greater(0.0);
    s.integer("bins", 100, "", "map cells per axis; g(r) has bins/2 shells").at_least(2);
    s.number("slab_half", 1.0, "a", "maps average over |third coordinate| < slab_half (paper: a)")
        .greater(0.0);
    s.text("projections", std::string("xy"), "comma-separated maps to build: xy (front view), xz, yz");
  }
  explicit PairDistributionPlugin(const fldsim::Params& p) : PairDistributionObserver(config(p)) {}

 private:
  static fldsim::observers::PairDistributionConfig config(const fldsim::Params& p) {
    fldsim::observers::PairDistributionConfig c;
    c.range = p.number("range");
    c.bins = static_cast<int>(p.integer("bins"));
    c.slab_half = p.number("slab_half");
    c.projections.clear();
    std::string list = p.text("projections");
    for (char& ch : list)
      if (ch == ',' || ch == '[' || ch == ']') ch = ' ';
    std::istringstream in(list);
    for (std::string name; in >> name;) {
      if (name == "xy")
        c.projections.push_back(Projection::XY);
      else if (name == "xz")
        c.projections.push_back(Projection::XZ);
      else if (name == "yz")
        c.projections.push_back(Projection::YZ);
      else
        p.fail("projections", "unknown projection '" + name + "' (expected xy, xz or yz)");
    }
    return c;
  }
};

}  // namespace

FLDSIM_PLUGIN(observer, PairDistributionPlugin, "pair_distribution", "1.0.0",
              "front-view g(x,y) in the slab |z| < a, other projections and radial g(r) of body centres")
