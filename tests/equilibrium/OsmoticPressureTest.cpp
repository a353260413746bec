// The osmotic pressure of rigid bodies (issue 11 part 6): Z = 1 + Pi_interparticle/(n kT) from the
// `stress` observer of a Pe = 0 Brownian run must equal the Monte Carlo oracle's Z of the same
// potential, whose estimator is the molecular virial sum (X_j - X_i) (x) f_j of body-centre
// separations and node-pair forces (docs/equilibrium-oracle.md): spheres, homonuclear dicolloids
// (c/a = 0.2) and fused dumbbells (c/a = 1) at phi = 0.3, N = 125 (make validate: N = 500).
// What is tested is the pressure estimator, so the run must be accurate at its time step: the
// repulsion is widened to a range of 0.1 a (prefactor 20, delta_min 0.1 a, delta_num 0.02 a: the
// overlap ramp is 14.7 kT/a, 1 kT per 0.068 a), which free-draining Euler-Maruyama resolves at
// dt = 1e-4 a^2/D0 (relative rms step 0.02 a; Z at dt 1e-4, 5e-5 and 2.5e-5 agrees within its
// 0.7-1 % errors, commit message). The default repulsion (1 kT per 0.006 a below contact) needs
// dt << 1e-5 for that (at 1e-5 its Z is 6 % high). The step loop's overlap guard is off: overlaps
// of 0.1-0.6 a belong to this potential's equilibrium, and rejecting them would bias it.
// Errors: independent runs as the blocks (as EquilibriumComparisonTest): run k has seed 1 + k, its
// own hard-body Monte Carlo start and noise, relaxes 0.2 a^2/D0 unsampled and is sampled for
// 0.9 (spheres, 12 runs) or 1.0 a^2/D0 (dumbbells, 16 runs; fused dumbbells 64, below); the
// observer's SE is the standard
// deviation of the run means / sqrt(runs); the oracle's is over 20 blocks of its chain.
// Rule, per shape: |z| < 3, z the Welch difference of the two means (Welch dof about 11 and 15:
// two-sided P(|t| > 3) = 1.2 % and 0.9 %, about 2 % family-wise false alarms; seeds are fixed, so
// a given build passes or fails reproducibly). Power: the runs must be long enough that 3 combined
// SE < 3 % of Z (asserted).
// Why not blocks of one trajectory (the test before): the observer's Flyvbjerg-Petersen SE of one
// run understated the error. Per unit of sampled time the run-to-run scatter is about 1.4x
// (spheres) and 1.3x (dumbbells) the blocked estimate of one run (each ratio uncertain by about
// 20 %): seed 1, one run of 4 (8) a^2/D0 gave SE 0.023 (0.028), i.e. 0.046 (0.078) per
// sqrt(a^2/D0); 12 (16) independent runs over 10.8 (16) a^2/D0 give SE 0.020 (0.025), i.e. 0.066
// (0.099) per sqrt(a^2/D0). At the old lengths with 8 runs (8 x 0.4 and 8 x 0.8 a^2/D0) 3 SE were
// 4.7 % and 3.2 % of Z, above the 3 % asserted, so the runs are longer now: about 56 CPU s for the
// two tests together (was 28; the c/a = 0.2 test adds about 43; `/usr/bin/time test_equilibrium_dynamics
// --gtest_filter='OsmoticPressure.*'`, oracle included).
// Measured (this build, seeds 1..R): spheres Z 3.652 +- 0.020 against the oracle's 3.687 +- 0.006
// (ratio 0.990, z -1.7); dumbbells 4.157 +- 0.025 against 4.116 +- 0.007 (ratio 1.010, z 1.6).
// Broken variant, measured once with these runs: the repulsion reporting the node-node virial
// r (x) f_j instead of the molecular one (plugin API 2; a one-line edit of ShortRangeRepulsion.cpp)
// gives the dumbbells' observer Z = 3.677 +- 0.022 against 4.116 +- 0.007 (ratio 0.893, z -19.3):
// the test fails by far (spheres, whose node is the centre, are unchanged).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

// Independent runs as the blocks (BrownianEquilibrium.hpp): run k = 0..runs-1 has seed 1 + k, its
// own hard-body Monte Carlo start and noise; the SE of the observer's Z is the standard deviation of
// the run means / sqrt(runs).
void check_pressure(const std::string& shape, const std::string& params, int runs, double equilibrate,
                    double duration) {
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
  bd_opt.equilibrate = equilibrate;
  bd_opt.duration = duration;
  bd_opt.sample_every = 100;  // g(r) and the configurational Z: printed only
  bd_opt.stress_every = 20;
  bd_opt.max_overlap = INFINITY;  // overlaps of 0.1-0.6 a belong to this potential's equilibrium
  const auto bd = run_brownian_replicas(scene, bd_opt, runs);
  const oracle::MeanError observer{bd.Z_observer, bd.Z_observer_se, runs};
  const auto c = oracle::compare_means(observer, mc.Z);
  std::cout << scene.describe() << ", " << runs << " runs of " << equilibrate << " + " << duration
            << " a^2/D0, " << bd.seconds << " s: Z stress observer " << bd.Z_observer << " +- "
            << bd.Z_observer_se << " (configurations " << bd.Z.mean << " +- " << bd.Z.se << "), oracle "
            << mc.Z.mean << " +- " << mc.Z.se << " (node-node virial " << mc.Z_node.mean << "); ratio "
            << c.ratio << ", z " << c.z << "\n  the runs' observer Z:";
  for (double z : bd.Z_observer_blocks) std::cout << " " << z;
  std::cout << "\n";
  ASSERT_EQ(bd.rejected, 0) << "the step loop rejected steps: not the fixed-step dynamics";
  const double combined = std::hypot(bd.Z_observer_se, mc.Z.se) / mc.Z.mean;
  ASSERT_LT(3.0 * combined, 0.03) << "too short to resolve 3 %";
  EXPECT_LT(std::abs(c.z), 3.0);
}

// Runs and their lengths (a^2/D0), see above: the dumbbells' pressure fluctuates more.
TEST(OsmoticPressure, SpheresMatchTheOracle) {
  check_pressure("sphere", "{}", 12, 0.2, 0.9);
}
// 64 runs since the Monte Carlo start compresses in overlapping steps (the dumbbells' lattice is
// looser than phi 0.3, so their starts are compressed): with the new starts, seeds 1..16 gave
// 4.036 +- 0.018 against 4.115 +- 0.010 (z -3.8), seeds 1..64 4.080 +- 0.015 (z -1.9); the old
// starts gave 4.091 +- 0.014 (16 runs, z -1.6) and 4.103 +- 0.012 (64 runs, z -0.9). The two start
// rules differ by 1.2 combined SE at 64 runs, and 100 starts of each have the same close-pair
// counts and orientation correlations as a long hard-body chain (within 1 SE): the 16-run sample
// was a 2 % tail, and the 4x longer test (about 100 CPU s) resolves 1.3 % at 3 SE.
TEST(OsmoticPressure, FusedDumbbellsMatchTheOracle) {
  check_pressure("dicolloid", "{a: 1, b: 1, c: 1}", 64, 0.2, 1.0);
}
// Homonuclear dicolloids (c/a = 0.2), the paper's other shape. Measured (seeds 1..16): observer Z
// 3.864 +- 0.027 against the oracle's 3.856 +- 0.008 (z 0.3; 43 CPU s). Here the node-node virial
// is 2.9 % below the molecular one (oracle: 3.744), about 4 combined SE: the broken variant above
// (node-node virial reported) gives Z 3.753 +- 0.026, z -3.8, and fails.
TEST(OsmoticPressure, HomonuclearDicolloidsMatchTheOracle) {
  check_pressure("dicolloid", "{a: 1, b: 1, c: 0.2}", 16, 0.2, 1.0);
}

// The whole particle pressure of a lubricated run (issue 11). FLD's lubrication keeps pairs out of
// the default repulsion's overlaps, so it samples exp(-U/kT) restricted to no overlaps (the oracle's
// hard core, docs/equilibrium-oracle.md), and the hard core's contact pressure is carried by the
// Brownian stress kT div(R_SU R_FU^-1) (Brady, J. Chem. Phys. 98, 3335 (1993)). Reference: the
// restricted system's equation of state from the oracle, per block (oracle/HardCoreContact.hpp)
//   Z_hc = Z_virial + Z_contact,   Z_contact = 4 phi g(2a+) (N - 1)/N e^(-U(0)/kT) for spheres,
// the contact density extrapolated over [2, 2.1) a (outside the repulsion's 1e-3 a range; at the
// wall it is lower by e^(-U(0)/kT)). Observer: `stress/Z_particle` with the
// Brownian stress of the random-difference probe (run.brownian_stress's default). Spheres, FLD
// defaults, phi 0.3, N 125, dt 2.5e-4 (the step at which g(r) matches the hard core bin by bin,
// docs/equilibrium-oracle.md), 16 runs of 0.2 + 0.8 a^2/D0 sampled every 4 steps (about 55 CPU s);
// oracle 100 000 sweeps in 40 blocks (about 18 s). Rule and power as above (|z| < 3; 3 combined SE
// < 3 % asserted).
// Measured (this build, seeds 1..16): Z_particle 3.988 +- 0.017 against 3.969 +- 0.010 (z 1.0).
// Broken variant, measured once on the same runs: the midpoint-stage estimate of the Brownian
// stress (run.brownian_stress: midpoint; O(dt) biased near contact, where a step moves a pair by
// about its own gap) gives 3.898 +- 0.017, z -3.6, and fails.
// Homonuclear dicolloids (c/a 0.2, the paper's sharp visibility) agree too (12 runs: 3.996 +- 0.034
// against 3.980 +- 0.016, z 0.4) but are not a CI test: their midpoint variant (3.905 +- 0.024, z -2.6)
// is not resolved at that length (docs/equilibrium-oracle.md); make validate's pressure_fld_dicolloid02
// (32 runs) gives 4.001 +- 0.017 against 3.987 +- 0.009 (z 0.7).
void check_particle_pressure(const EquilibriumScene& scene, int runs, std::int64_t oracle_sweeps) {
  oracle::OracleOptions mc_opt = comparison_oracle_options(true);
  mc_opt.sweeps = oracle_sweeps;
  const auto mc = run_scene_oracle(scene, mc_opt);
  const oracle::MeanError& reference = mc.Z_hard_core;

  BrownianOptions opt;
  opt.dt = 2.5e-4;
  opt.equilibrate = 0.2;
  opt.duration = 0.8;
  opt.sample_every = 400;  // g(r): not compared here
  opt.stress_every = 4;
  const auto bd = run_brownian_replicas(scene, opt, runs);
  const oracle::MeanError observer{bd.Z_particle, bd.Z_particle_se, runs};
  const auto c = oracle::compare_means(observer, reference);
  std::cout << scene.describe() << ", " << runs << " runs of 0.2 + 0.8 a^2/D0 at dt 2.5e-4, " << bd.seconds
            << " s: Z_particle " << bd.Z_particle << " +- " << bd.Z_particle_se << " (interparticle only "
            << bd.Z_observer << "), hard-core equation of state " << reference.mean << " +- " << reference.se
            << " (Z_virial " << mc.Z.mean << ", contact term " << mc.Z_contact.mean << " with e^-U(0) "
            << mc.boltzmann_at_contact << "); ratio " << c.ratio << ", z " << c.z
            << "\n  the runs' Z_particle:";
  for (double z : bd.Z_particle_blocks) std::cout << " " << z;
  std::cout << "\n";
  ASSERT_EQ(bd.rejected, 0) << "the step loop rejected steps: not the fixed-step dynamics";
  ASSERT_LT(3.0 * std::hypot(bd.Z_particle_se, reference.se) / reference.mean, 0.03)
      << "too short to resolve 3 %";
  EXPECT_LT(std::abs(c.z), 3.0);
}

TEST(OsmoticPressure, FldSpheresMatchTheHardCoreEquationOfState) {
  check_particle_pressure(EquilibriumScene{}, 16, 100000);  // spheres, fld, default repulsion, N 125
}

// Fused dumbbells (c/a 1), where the orientation is part of the configuration and the Brownian stress
// has a rotational divergence (for spheres it has none): make validate's pressure_fld_dicolloid1
// (32 runs), no longer a CI test (it cost about 110 CPU s of CI's 20 minutes). Measured as a CI test
// (24 runs, oracle 40 000 sweeps): Z_particle 4.375 +- 0.017 against 4.378 +- 0.017 (z -0.1). The bug
// it found (BodyMotion.cpp's move_from rotated bodies only for h > 0, so the probe counted half the
// rotational divergence: 4.277 +- 0.016, z -4.3) is caught in CI by the deterministic
// BrownianStress.RandomDifferenceEqualsDivergenceForRotatingDumbbells (trace of the divergence near
// contact -108.2 +- 1.5 with the bug against -62.8, commit 42b29c2).

}  // namespace
}  // namespace fldsim::testing
