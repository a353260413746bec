// fldsim_twobody: free-pair functions (G, H, A, B, C, Xr, Yr; tests/hydro/TwoSphereFreePair.hpp)
// of two isolated equal spheres under a hydro plugin, for every combination of the pair-model
// conventions the plugin declares (strain_arm, lever, pump, twist, taper), at the centre distances
// given on the command line. Prints CSV for bench/twobody/error_table.py.
//
//   fldsim_twobody [--plugin lubrication] s1 s2 ...
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "TwoSphereFreePair.hpp"

using namespace fldsim;
using namespace fldsim::hydro::test;

namespace {

struct Axis {
  std::string name;
  std::vector<ParamValue> values;
};

std::string text(const ParamValue& v) {
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* d = std::get_if<double>(&v)) return std::to_string(*d);
  return "?";
}

}  // namespace

int main(int argc, char** argv) {
  std::string plugin = "lubrication";
  std::vector<double> distances;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--plugin" && k + 1 < argc)
      plugin = argv[++k];
    else
      distances.push_back(std::atof(argv[k]));
  }
  if (distances.empty()) {
    std::fprintf(stderr,
                 "usage: fldsim_twobody [--plugin lubrication|fld] s1 s2 ... (centre distances in a)\n");
    return 2;
  }
  const char* dir = std::getenv("FLDSIM_PLUGIN_PATH");
  const PluginRegistry registry({dir ? dir : FLDSIM_TEST_PLUGIN_DIR});
  const ParamSchema& schema = registry.find("hydro", plugin).schema;

  // The convention axes; an option the plugin does not declare keeps its (absent) default.
  std::vector<Axis> axes;
  auto add = [&](const std::string& name, std::vector<ParamValue> values) {
    if (const ParamSpec* spec = schema.find(name)) {
      if (spec->type == ParamType::Choice) {
        values.clear();
        for (const auto& c : spec->choices) values.emplace_back(c);
      }
      axes.push_back({name, values});
    }
  };
  add("strain_arm", {});
  add("lever", {});
  add("pump", {});
  add("twist", {true, false});
  add("taper", {});

  std::printf("plugin,convention,s,G,H,A,B,C,Xr,Yr\n");
  std::vector<std::size_t> index(axes.size(), 0);
  for (;;) {
    PluginOptions options;
    std::string label;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      options.emplace_back(axes[a].name, axes[a].values[index[a]]);
      label += (a ? ";" : "") + axes[a].name + "=" + text(axes[a].values[index[a]]);
    }
    for (double s : distances) {
      const FreePair f = free_pair(registry, plugin, options, s);
      std::printf("%s,%s,%.6f,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", plugin.c_str(), label.c_str(), s,
                  f.G, f.H, f.A, f.B, f.C, f.Xr, f.Yr);
    }
    std::size_t a = 0;
    while (a < axes.size() && ++index[a] == axes[a].values.size()) index[a++] = 0;
    if (a == axes.size()) break;
  }
  return 0;
}
