// Adaptive steps (`dt: auto`) against the Monte Carlo oracle of the same potential, at Pe = 0.
// Free-draining spheres at phi = 0.3 are the hard case: the mobility at contact is the isolated
// body's, so the repulsion (0 to 166.6 kT/a over gaps 1e-3 to 1e-5 a, then a constant force below
// 1e-5 a, overlaps included: exp(-U/kT) decays over 0.006 a of overlap) is stiff against the
// Brownian step, and at the examples' fixed dt = 1e-3 the structure is wrong (issue 13). At
// dt: auto (tolerance 5e-4 a: the default 1e-3 leaves Z about 5 % high here, docs/time_steps.md)
// the steps shrink where pairs touch, and the run must reproduce the oracle within its errors:
//   - body-centre g(r) in 0.02 a bins over [1.98, 3.0) a (overlap ramp included), block errors
//     on both sides, the family-wise rule of oracle/GrComparison.hpp (Bonferroni over the 51 bins
//     and a chi-square over all of them, together alpha = 1 % for a correct model);
//   - Z = 1 + tr(W)/(3 N kT) of the sampled configurations (molecular virial) within 3 combined
//     standard errors of the oracle's (block errors: 20 blocks of 0.04 a^2/D0, much longer than
//     a contact's life, ~ (0.1 a)^2 / D0).
// Multiple comparisons: the two checks together fail a correct model with probability below
// 1 % + 0.27 % (union bound); seeds are fixed, so the result is deterministic for a build.
// Power: the combined SE of Z is 1.8 %, so Z biases above about 5.5 % fail; the issue's "Z within
// 2 %" needs runs 10 times longer (fldsim_validate_equilibrium pressure_spheres_auto).
// Broken variants, measured once (commit message): the fixed step 1e-3 fails (below, in CI), and
// so does a 4x looser tolerance (2e-3: Z 8 % high, z = 4.3 in 1.5 a^2/D0); the controller on the root mean
// square over bodies (Z +5 %, z = 3.0 in 1 a^2/D0) and redraw-on-reject (+1 %) are not
// resolved at this length; tests/dynamics/AdaptiveStepTest.cpp catches the redraw.
// About 55 CPU seconds (N = 125, 0.8 a^2/D0, 190 000 steps, oracle included).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

using oracle::GrComparison;
using oracle::GrComparisonOptions;

GrComparisonOptions comparison_range() {
  GrComparisonOptions o;
  o.r_from = 1.98;
  o.r_to = 3.0;
  return o;
}

EquilibriumScene free_draining_spheres() {
  EquilibriumScene s;
  s.hydro = "free_draining";
  s.count = 125;
  s.phi = 0.3;
  return s;
}

const oracle::OracleResult& sphere_oracle() {
  static const oracle::OracleResult r = [] {
    oracle::OracleOptions o;
    o.bin_width = 0.01;
    o.sweeps = 20000;
    o.blocks = 40;
    o.node_distribution = false;
    return run_scene_oracle(free_draining_spheres(), o);
  }();
  return r;
}

struct Verdict {
  GrComparison g;
  oracle::BinComparison Z;
};

Verdict compare(const BrownianOptions& opt, const std::string& what) {
  const BrownianEquilibrium bd = run_brownian(free_draining_spheres(), opt);
  const oracle::OracleResult& mc = sphere_oracle();
  const auto o = comparison_range();
  Verdict v;
  v.g = oracle::compare_gr(bd.g.rebinned(2), mc.bodies.rebinned(2), o);
  v.Z = oracle::compare_means(bd.Z, mc.Z);
  std::cout << what << ": " << free_draining_spheres().describe() << "\n  " << bd.steps << " frames, "
            << bd.accepted << " steps, " << bd.rejected << " rejected, smallest gap " << bd.min_gap << " a, "
            << bd.seconds << " s\n  Z = " << bd.Z.mean << " +- " << bd.Z.se << " against the oracle's "
            << mc.Z.mean << " +- " << mc.Z.se << " (ratio " << v.Z.ratio << ", z " << v.Z.z << ")\n"
            << v.g.table(o);
  return v;
}

bool agrees(const Verdict& v) {
  return v.g.pass() && std::fabs(v.Z.z) < 3.0;
}

TEST(AdaptiveEquilibrium, FreeDrainingSpheresMatchTheOracle) {
  BrownianOptions opt;
  opt.adaptive = true;
  opt.dt = 1e-3;  // dt_max: the frame
  opt.tolerance = 5e-4;
  opt.equilibrate = 0.1;
  opt.duration = 0.8;
  opt.sample_every = 1;
  opt.blocks = 20;
  const Verdict v = compare(opt, "dt: auto, tolerance 5e-4 a");
  EXPECT_TRUE(v.g.pass()) << "g(r) differs from the oracle";
  EXPECT_LT(std::fabs(v.Z.z), 3.0) << "Z differs from the oracle's by more than 3 standard errors";
}

TEST(AdaptiveEquilibrium, FixedStepOfTheExamplesFailsTheSameComparison) {
  BrownianOptions fixed;
  fixed.dt = 1e-3;
  fixed.equilibrate = 0.1;
  fixed.duration = 0.5;
  fixed.sample_every = 2;
  EXPECT_FALSE(agrees(compare(fixed, "fixed dt 1e-3"))) << "the comparison cannot see a too long step";
}

}  // namespace
}  // namespace fldsim::testing
