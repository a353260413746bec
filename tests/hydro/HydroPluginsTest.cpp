// The three hydro plugins load through the real plugin loader, take their default parameters and
// give the isolated-sphere mobility each is defined by.
#include <gtest/gtest.h>

#include "HydroTestSupport.hpp"
#include "fldsim/hydro.hpp"
#include "plugins/PluginRegistry.hpp"

using namespace fldsim;
using namespace fldsim::hydro::test;

namespace {

Params defaults(const PluginInfo& info) {
  Params p("hydro", "test");
  for (const auto& spec : info.schema.specs())
    if (spec.default_value) p.set(spec.name, *spec.default_value, ParamOrigin{"test", "hydro." + spec.name});
  return p;
}

}  // namespace

TEST(HydroPlugins, LoadAndGiveTheirIsolatedSphereMobility) {
  const PluginRegistry registry({FLDSIM_TEST_PLUGIN_DIR});
  // Translational resistance of one isolated unit sphere, in units of 6 pi mu a: 1 for
  // free_draining and lubrication; for fld its default R_0 fit 1 + 0.5361 phi - 4.6621 phi^2 =
  // 0.741527 at phi = 0.3 (docs/fld-r0-fit.md).
  const std::pair<const char*, double> expected[] = {
      {"free_draining", 1.0}, {"lubrication", 1.0}, {"fld", 1.0 + 0.5361 * 0.3 - 4.6621 * 0.09}};
  for (const auto& [name, resistance] : expected) {
    SCOPED_TRACE(name);
    const auto model = registry.create<HydroModel>("hydro", name, defaults(registry.find("hydro", name)));
    System s(sphere_shape(), 1, 20.0, physics(0.0, 0.0, 0.3));
    HydroRequest req;
    req.brownian = false;
    req.shear = false;
    const auto skipped = model->configure(s, req);
    EXPECT_EQ(skipped.size(), 3u);  // no Brownian forces, no R_FE:E, no stresslets
    model->assemble(s, NodePairList{});
    const double F[6] = {1, 0, 0, 0, 0, 0};
    double dU[6] = {0};
    model->solve(s, F, dU);
    EXPECT_NEAR(1.0 / dU[0], resistance, 1e-12);
  }
}
