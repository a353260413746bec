// Stokes flow is time-reversible: two non-Brownian spheres without repulsion that pass each
// other in shear end with the same offset in the gradient direction they started with
// (Batchelor & Green 1972; the symmetric trajectories of Da Cunha & Hinch 1996 without
// roughness). A configuration-dependent symmetric resistance preserves this, so any residual
// offset is integration error: the issue asks for 1e-3 a.
#include <gtest/gtest.h>

#include <cmath>

#include "Scene.hpp"

namespace fldsim::testing {
namespace {

TEST(Reversibility, GlancingPairInShearRecoversItsGradientOffset) {
  Physics ph;
  ph.kT = 0.0;
  ph.shear_rate = 1.0;
  const double L = 40.0;
  Scene scene(make<Shape>("shape", "sphere"), 2, L, ph);
  auto& s = *scene.system;
  const double dy0 = 0.8, dz0 = 0.4, dx0 = -6.0;
  s.positions()[0] = Vec3(20.0, 20.0, 20.0);
  s.positions()[1] = Vec3(20.0 + dx0, 20.0 + dy0, 20.0 + dz0);
  scene.finish(make<HydroModel>("hydro", "lubrication", "{tolerance: 1e-12}"), {},
               HydroRequest{false, true, false});
  RungeKutta3 rk(2);
  const double dt = 2e-3;
  double min_gap = 1e9;
  // Relative x velocity ~ dy; run until the pair has passed by the same distance.
  for (int k = 0; k < 200000; ++k) {
    rk.step(s, *scene.evaluator, dt, false);
    const Vec3 r = s.box().minimum_image(s.positions()[1] - s.positions()[0]);
    min_gap = std::min(min_gap, r.norm() - 2.0);
    if (r.x() > -dx0) {
      EXPECT_NEAR(r.y(), dy0, 1e-3) << "after " << k << " steps, min gap " << min_gap;
      EXPECT_NEAR(r.z(), dz0, 1e-3);
      EXPECT_LT(min_gap, 0.2);  // the pair really came close: lubrication was active
      return;
    }
  }
  FAIL() << "the pair never passed";
}

}  // namespace
}  // namespace fldsim::testing
