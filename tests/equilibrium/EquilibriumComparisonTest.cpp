// At Pe = 0 the distribution of the bodies must not depend on the hydrodynamic model: a Brownian
// run of FLD must reproduce the Monte Carlo oracle of the same potential (the thermal drift
// kT div M makes exp(-U/kT) stationary: Ermak & McCammon, J. Chem. Phys. 69, 1352 (1978)).
// Body-centre g(r) in 0.02 a bins from contact (2.00 a) to 3.0 a, block errors on both sides, the
// family-wise rule of oracle/GrComparison.hpp (Bonferroni over the bins and chi-square, together
// 1 % false alarms for a correct model; seeds are fixed, so a build passes or fails reproducibly).
//
// The potential: the repulsion with delta_num 1e-7 a (overlaps cost 1 kT per 6e-5 a; oracle
// g(1.98-2.00 a) = 0.007), i.e. the default one made hard at contact. The default repulsion
// (delta_num 1e-5: 1 kT per 0.006 a, oracle g(1.98-2.00 a) = 0.71) has an overlap population FLD
// does not reach at any practical step (g_FLD = 0.005 there at dt 1e-3 ... 2.5e-4; the squeeze
// mobility vanishes as the gap, so a midpoint step from a gap x lands at
// (sqrt(x) + s xi)^2 + s^2 xi^2 >= 0 with s^2 = 2 D0 dt / a, far above the 1e-5 a gap clamp:
// docs/equilibrium-oracle.md, "FLD near contact"); those pairs then crowd the first shell and the
// comparison fails there for a reason that is not the hydrodynamic drift tested here.
//
// The step: dt = 2.5e-4 a^2/D0. The midpoint drift scheme leaves an O(dt) bias where the taper
// (2.2-2.5 a) bends the mobility: with this potential at dt 1e-3 (N = 125, 40 a^2/D0) g is +1.5..+3.4 %
// high over 2.24-2.38 a and 2.3..3.2 % low over 2.42-2.48 a (z up to 6, the comparison fails); at
// 2.5e-4 no 0.02 a bin is off by more than 1.5 % (a dip of 1-1.5 % at 2.42-2.48 a, seen with two
// seeds over 40 a^2/D0 at bin SE 0.5 %: chi-square p 8e-5 and 0.16), and at 1.25e-4 the dip is gone
// (p 0.63). That last percent is below the resolution of the CI length here (bin SE about 1.5 %),
// so the positive test passes for that reason. The dt study is in
// docs/lubrication-taper.md; make validate (fldsim_validate_equilibrium) runs the long versions.
//
// The blocks are independent runs (compare_replicas): 8 runs of 0.5 + 1 a^2/D0, each from its own
// Monte Carlo start and noise seed (about 45 s on one core). Blocks of one trajectory are not
// independent at CI length: one 8 a^2/D0 run in 20 or 8 blocks failed the chi-square for one of
// five noise seeds (p 1e-5: g 3-6 % low at contact and 1-4 % high beyond 2.3 a for the whole run);
// with replicas the two seed sets tried pass (seeds 1-8 and 9-16: p 0.12 and 0.96). Resolution:
// bin SE 1.5-2 %, so the taper window's time-step bias at dt 1e-3 (about 3 %) is not resolved here
// (the same replicas at 1e-3 pass, chi-square p 0.025); make validate (spheres_dt1e-3) and
// docs/lubrication-taper.md resolve it.
// Homonuclear dicolloids (c/a 0.2) are compared in make validate only (dicolloid02, N = 500): at
// N = 125 with this step they pass over 20 a^2/D0 (max |z| 3.5, p 0.09), but a CI-length test is
// not reliable: single 6 a^2/D0 runs failed for one of three seeds (p 4e-7), and 6 replicas, the
// most that fit, passed for seeds 1-6 (p 0.59) and failed for 7-12 (p 6e-5, isolated bins at
// z 4.5: six blocks make the per-bin errors too uncertain for the Welch degrees of freedom).
//
// Must fail the same comparison: the run without the thermal drift (drift: none), and the abrupt
// lubrication cutoff (taper: none), whose spike inside 2.5 a and hole outside it must be where the
// comparison fails worst.
#include <gtest/gtest.h>

#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

using oracle::GrComparison;
using oracle::GrComparisonOptions;

// The repulsion made hard at contact (see above).
constexpr const char* kHardRepulsion = "{delta_num: 1e-7}";
// The step at which FLD's equilibrium is exact within these tests' resolution (see above).
constexpr double kDt = 2.5e-4;

GrComparisonOptions comparison_range() {
  GrComparisonOptions o;
  o.r_from = 2.0;
  o.r_to = 3.0;
  return o;
}

EquilibriumScene spheres() {
  EquilibriumScene s;
  s.count = 125;
  s.phi = 0.3;
  s.force_params = kHardRepulsion;
  return s;
}

oracle::OracleResult oracle_of(const EquilibriumScene& scene) {
  oracle::OracleOptions o;
  o.bin_width = 0.01;
  o.sweeps = 20000;
  o.blocks = 40;
  o.node_distribution = false;
  return run_scene_oracle(scene, o);
}

const oracle::OracleResult& sphere_oracle() {
  static const oracle::OracleResult r = oracle_of(spheres());
  return r;
}

GrComparison judge(const oracle::RadialHistogram& g, const oracle::OracleResult& mc) {
  return oracle::compare_gr(g.rebinned(2), mc.bodies.rebinned(2), comparison_range());
}

void print(const GrComparison& c, const std::string& what, const EquilibriumScene& scene,
           const std::string& run, const oracle::OracleResult& mc) {
  std::cout << what << ": " << scene.describe() << "\n  " << run << "; oracle " << mc.samples << " samples\n"
            << c.table(comparison_range());
}

// One trajectory in blocks (for the variants that must fail).
GrComparison compare(const EquilibriumScene& scene, const BrownianOptions& opt,
                     const oracle::OracleResult& mc, const std::string& what) {
  const BrownianEquilibrium bd = run_brownian(scene, opt);
  const GrComparison c = judge(bd.g, mc);
  print(c, what, scene,
        std::to_string(bd.steps) + " steps of " + std::to_string(opt.dt) + ", " + std::to_string(bd.seconds) +
            " s",
        mc);
  return c;
}

// Independent runs as the blocks: run k starts from its own hard-body Monte Carlo configuration (an
// equilibrium sample of the hard-body fluid this potential nearly is) with noise seed k, relaxes
// for `equilibrate` and is sampled for `duration`, one block each (see the top of the file).
GrComparison compare_replicas(const EquilibriumScene& scene, BrownianOptions opt, int runs,
                              const oracle::OracleResult& mc, const std::string& what) {
  oracle::RadialHistogram g(oracle::PairPoints::BodyCentres, opt.bin_width, opt.r_max);
  opt.blocks = 1;
  double seconds = 0.0;
  std::int64_t steps = 0;
  for (int k = 1; k <= runs; ++k) {
    opt.seed = std::uint64_t(k);
    const BrownianEquilibrium bd = run_brownian(scene, opt);
    g.append_blocks(bd.g);
    seconds += bd.seconds;
    steps += bd.steps;
  }
  const GrComparison c = judge(g, mc);
  print(c, what, scene,
        std::to_string(runs) + " runs, " + std::to_string(steps) + " steps of " + std::to_string(opt.dt) +
            ", " + std::to_string(seconds) + " s",
        mc);
  return c;
}

BrownianOptions exact_step(double duration) {
  BrownianOptions opt;
  opt.dt = kDt;
  opt.equilibrate = 0.5;
  opt.duration = duration;
  opt.sample_every = 40;
  opt.blocks = 20;
  return opt;
}

TEST(EquilibriumStructure, FldSpheresMatchTheOracle) {
  const GrComparison c =
      compare_replicas(spheres(), exact_step(1.0), 8, sphere_oracle(), "FLD spheres phi 0.3");
  EXPECT_TRUE(c.pass()) << "g(r) of FLD spheres differs from the oracle";
}

TEST(EquilibriumStructure, FldSpheresWithoutDriftFailTheComparison) {
  BrownianOptions opt;
  opt.drift = DriftScheme::None;
  opt.duration = 2.0;
  opt.equilibrate = 0.5;
  opt.blocks = 20;
  const GrComparison c = compare(spheres(), opt, sphere_oracle(), "drift: none");
  EXPECT_FALSE(c.pass()) << "the comparison cannot see a missing thermal drift";
}

TEST(EquilibriumStructure, AbruptCutoffShowsItsArtifact) {
  EquilibriumScene scene = spheres();
  scene.hydro_params = "{taper: none}";
  const GrComparison c = compare(scene, exact_step(2.0), sphere_oracle(), "taper: none");
  EXPECT_FALSE(c.pass()) << "the comparison cannot see the abrupt cutoff";
  ASSERT_GE(c.worst_bin, 0);
  const auto& worst = c.bins[std::size_t(c.worst_bin)];
  EXPECT_GE(worst.r_lo, 2.4) << "the worst bin is not at the cutoff";
  EXPECT_LE(worst.r_hi, 2.6) << "the worst bin is not at the cutoff";
}

}  // namespace
}  // namespace fldsim::testing
