// The Leimkuhler-Matthews scheme (run.integrator: leimkuhler_matthews; dynamics/TimeIntegrator.hpp)
// against the Monte Carlo oracle of the same potential: free-draining spheres, phi = 0.3, N = 125,
// Pe = 0, the default repulsion with its overlaps (the hard case of AdaptiveEquilibriumTest.cpp:
// exp(-U/kT) decays over 0.006 a of overlap, which an isolated sphere's Brownian step of 1e-4
// a^2/D0, rms 0.017 a per axis, jumps over). For a constant mobility the scheme's equilibrium is
// exact to O(dt^2) (Leimkuhler & Matthews, Appl. Math. Res. Express 2013, 34), Euler-Maruyama's
// to O(dt).
// Checks, as AdaptiveEquilibriumTest.cpp's: body-centre g(r) in 0.02 a bins over [1.98, 3.0) a by
// the family-wise rule of oracle/GrComparison.hpp (alpha 1 % for a correct model), and Z of the
// sampled configurations within 3 combined standard errors of the oracle's. Errors from 32
// independent runs (seeds 201-232, each 0.03 a^2/D0 unsampled, then 0.1 sampled every 1e-3), as
// the measurement in docs/time_steps.md ("Leimkuhler-Matthews for a constant mobility").
// Measured (fldsim_validate_equilibrium spheres n=125 'hydro_params={}' hydro=free_draining
// hard_core=0 runs=32 seed=201 equilibrate=0.03 duration=0.1 adaptive=0 dt=DT every=K
// integrator=I): Z / Z_MC and the 2.00-3.00 a comparison,
//   leimkuhler_matthews 1e-4: 0.9997 (z -0.02), g fails (2.00-2.02 a 0.76, z -24);
//                       5e-5: 1.003 (z 0.3), g fails (max |z| 8.8); 2.5e-5: 0.990 (z -0.8), g passes
//                       (max |z| 2.86, chi-square p 0.096); 1.25e-5: 1.000, passes (max |z| 2.36);
//   euler_maruyama (midpoint) 1e-4: 1.364 (z 23); 5e-5: 1.224; 2.5e-5: 1.114 (z 8.5); 1.25e-5: 1.072
//                       (z 5.8; g passes, the overlap bin 1.98-2.00 a 0.78 against 0.71, z 5.9).
// (At N = 1000, whose 16 runs resolve 2.8x finer, 2.5e-5's contact bin reads 2.6 % low and fails; 1.25e-5
// passes there: docs/time_steps.md.) So the test runs at 2.5e-5, and its broken variant is
// Euler-Maruyama at the same step, which must fail the same comparison (Z 11 % high). Power: the
// combined SE of Z is about 1.2 %, so a bias above about 3.6 % fails. About 25 CPU s for the
// scheme, 30 for the broken variant, 7 for the oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

constexpr int kRuns = 32;
constexpr std::uint64_t kFirstSeed = 201;
constexpr double kDt = 2.5e-5;

const oracle::OracleResult& sphere_oracle() {
  static const oracle::OracleResult r =
      run_scene_oracle(free_draining_spheres(), comparison_oracle_options(false));
  return r;
}

struct Verdict {
  oracle::GrComparison g;
  oracle::BinComparison Z;
  bool agrees() const { return g.pass() && std::fabs(Z.z) < 3.0; }
};

Verdict compare(bool leimkuhler_matthews, const std::string& what) {
  BrownianOptions opt;
  opt.dt = kDt;
  opt.leimkuhler_matthews = leimkuhler_matthews;
  opt.seed = kFirstSeed;
  opt.equilibrate = 0.03;
  opt.duration = 0.1;
  opt.sample_every = 40;
  const BrownianEquilibrium bd = run_brownian_replicas(free_draining_spheres(), opt, kRuns);
  const oracle::OracleResult& mc = sphere_oracle();
  oracle::GrComparisonOptions range;
  range.r_from = 1.98;
  range.r_to = 3.0;
  Verdict v;
  v.g = oracle::compare_gr(bd.g.rebinned(2), mc.bodies.rebinned(2), range);
  v.Z = oracle::compare_means(bd.Z, mc.Z);
  std::cout << what << ": " << kRuns << " runs, " << bd.accepted << " steps, smallest gap " << bd.min_gap
            << " a\n  Z = " << bd.Z.mean << " +- " << bd.Z.se << " against the oracle's " << mc.Z.mean
            << " +- " << mc.Z.se << " (ratio " << v.Z.ratio << ", z " << v.Z.z << ")\n"
            << v.g.table(range);
  return v;
}

TEST(LeimkuhlerMatthewsEquilibrium, FreeDrainingSpheresMatchTheOracle) {
  const Verdict v = compare(true, "leimkuhler_matthews, dt 2.5e-5");
  EXPECT_TRUE(v.g.pass()) << "g(r) differs from the oracle";
  EXPECT_LT(std::fabs(v.Z.z), 3.0) << "Z differs from the oracle's by more than 3 standard errors";
}

TEST(LeimkuhlerMatthewsEquilibrium, EulerMaruyamaAtTheSameStepFails) {
  EXPECT_FALSE(compare(false, "euler_maruyama (midpoint), dt 2.5e-5").agrees())
      << "the comparison cannot tell the first-order scheme at this step";
}

}  // namespace
}  // namespace fldsim::testing
