// Plugin `pair_distribution`: registers PairDistributionObserver (plugins/observers/common).
#include <algorithm>
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
    // bins^2 cells per map: at most 2000 keeps three maps under 100 MB.
    s.integer("bins", 100, "", "map cells per axis; g(r) has bins/2 shells").at_least(2).at_most(2000);
    s.number("slab_half", 1.0, "a", "maps average over |third coordinate| < slab_half (paper: a)")
        .greater(0.0);
    // A text value until the parameter schema has a list-of-choices type: YAML `[xy, xz]` is a
    // sequence, which ParamSchema::text refuses, so the list is written "xy, xz" (or quoted "[xy, xz]").
    s.text("projections", std::string("xy"),
           "maps to build, a comma-separated list of distinct xy (front view), xz, yz, e.g. \"xy, xz, yz\"");
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
      Projection proj;
      if (name == "xy")
        proj = Projection::XY;
      else if (name == "xz")
        proj = Projection::XZ;
      else if (name == "yz")
        proj = Projection::YZ;
      else
        p.fail("projections", "unknown projection '" + name + "' (expected a list of xy, xz, yz)");
      if (std::find(c.projections.begin(), c.projections.end(), proj) != c.projections.end())
        p.fail("projections", "projection '" + name + "' listed twice");
      c.projections.push_back(proj);
    }
    if (c.projections.empty()) p.fail("projections", "expected at least one of xy, xz, yz, got none");
    return c;
  }
};

}  // namespace

FLDSIM_PLUGIN(observer, PairDistributionPlugin, "pair_distribution", "1.0.0",
              "front-view g(x,y) in the slab |z| < a, other projections and radial g(r) of body centres")
