// The osmotic pressure of rigid bodies (issue 11 part 6): Z = 1 + Pi_interparticle/(n kT) from the
// `stress` observer of a Pe = 0 Brownian run must equal the Monte Carlo oracle's Z of the same
// potential, whose estimator is the molecular virial sum (X_j - X_i) (x) f_j of body-centre
// separations and node-pair forces (docs/equilibrium-oracle.md): spheres and fused dumbbells
// (c/a = 1) at phi = 0.3, N = 125 (make validate: N = 500, also c/a = 0.2).
// What is tested is the pressure estimator, so the run must be accurate at its time step: the
// repulsion is widened to a range of 0.1 a (prefactor 20, delta_min 0.1 a, delta_num 0.02 a: the
// overlap ramp is 14.7 kT/a, 1 kT per 0.068 a), which free-draining Euler-Maruyama resolves at
// dt = 1e-4 a^2/D0 (relative rms step 0.02 a; Z at dt 1e-4, 5e-5 and 2.5e-5 agrees within its
// 0.7-1 % errors, commit message). The default repulsion (1 kT per 0.006 a below contact) needs
// dt << 1e-5 for that (at 1e-5 its Z is 6 % high). The step loop's overlap guard is off: overlaps
// of 0.1-0.6 a belong to this potential's equilibrium, and rejecting them would bias it.
// Rule, per shape: |z| < 3, z the Welch difference with block errors on both sides (observer:
// Flyvbjerg-Petersen blocking of its samples; oracle: 20 blocks). Two shapes with ~20 degrees of
// freedom: about 1.5 % family-wise false alarms (seeds are fixed: a given build passes or fails
// reproducibly). Power: the run must be long enough that 3 combined SE < 3 % of Z (the CI size
// resolves about +-2.5 %; the 2 % is checked with power by make validate). With the
// node-node virial instead (plugin API 2) the dumbbells' Z is 11 % low and the test fails by far
// (commit message).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

void check_pressure(const std::string& shape, const std::string& params, double duration) {
  EquilibriumScene scene;
  scene.shape = shape;
  scene.shape_params = params;
  scene.hydro = "free_draining";
  scene.force_params = "{prefactor: 20, delta_min: 0.1, delta_num: 0.02}";
  scene.count = 125;
  scene.phi = 0.3;
  oracle::OracleOptions mc_opt;
  mc_opt.sweeps = 20000;
  mc_opt.blocks = 20;
  mc_opt.node_distribution = false;
  const auto mc = run_scene_oracle(scene, mc_opt);
  BrownianOptions bd_opt;
  bd_opt.dt = 1e-4;
  bd_opt.equilibrate = 0.2;
  bd_opt.duration = duration;
  bd_opt.sample_every = 20;
  bd_opt.stress_every = 20;
  bd_opt.blocks = 20;
  bd_opt.max_overlap = INFINITY;  // overlaps of 0.1-0.6 a belong to this potential's equilibrium
  const auto bd = run_brownian(scene, bd_opt);
  const oracle::MeanError observer{bd.Z_observer, bd.Z_observer_se, bd_opt.blocks};
  const auto c = oracle::compare_means(observer, mc.Z);
  std::cout << scene.describe() << ": Z stress observer " << bd.Z_observer << " +- " << bd.Z_observer_se
            << " (configurations " << bd.Z.mean << " +- " << bd.Z.se << "), oracle " << mc.Z.mean << " +- "
            << mc.Z.se << " (node-node virial " << mc.Z_node.mean << "); ratio " << c.ratio << ", z " << c.z
            << "\n";
  ASSERT_EQ(bd.rejected, 0) << "the step loop rejected steps: not the fixed-step dynamics";
  const double combined = std::hypot(bd.Z_observer_se, mc.Z.se) / mc.Z.mean;
  ASSERT_LT(3.0 * combined, 0.03) << "too short to resolve 3 %";
  EXPECT_LT(std::abs(c.z), 3.0);
}

// Durations (a^2/D0): the dumbbells' pressure fluctuates more and relaxes more slowly.
TEST(OsmoticPressure, SpheresMatchTheOracle) {
  check_pressure("sphere", "{}", 4.0);
}
TEST(OsmoticPressure, FusedDumbbellsMatchTheOracle) {
  check_pressure("dicolloid", "{a: 1, b: 1, c: 1}", 8.0);
}

}  // namespace
}  // namespace fldsim::testing
