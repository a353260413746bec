// At Pe = 0 the distribution of the bodies must not depend on the hydrodynamic model: a Brownian
// run of FLD must reproduce the Monte Carlo oracle of the same potential (the thermal drift
// kT div M makes exp(-U/kT) stationary: Ermak & McCammon, J. Chem. Phys. 69, 1352 (1978)).
// Body-centre g(r) in 0.02 a bins from contact (2.00 a) to 3.0 a, block errors on both sides, the
// family-wise rule of oracle/GrComparison.hpp (Bonferroni over the bins and chi-square, together
// 1 % false alarms for a correct model; seeds are fixed, so a build passes or fails reproducibly).
//
// The potential: the default repulsion, and the oracle's hard core as the reference (issue 11
// part 4, docs/equilibrium-oracle.md, "The reference for FLD: the hard core"). The repulsion's
// Boltzmann distribution has an overlap population (1 kT per 0.006 a of overlap; g(1.98-2.00 a) =
// 0.71 at phi 0.3) that FLD does not reach at any practical step (g_FLD = 0.004-0.005 there at
// dt 1e-3 ... 2.5e-4: the squeeze mobility vanishes as the gap, so a midpoint step from a gap x
// lands at (sqrt(x) + s xi)^2 + s^2 xi^2 >= 0 with s^2 = 2 D0 dt / a, far above the 1e-5 a gap
// clamp; without the clamp contact is never reached in continuous time either). So FLD samples
// exp(-U/kT) restricted to no overlaps, which the oracle's hard core samples; against the full
// distribution the first shell is 1-5 % high (1.5 % of it the oracles' own difference). With the
// hard core the contact shell 2.00-2.05 a is 0.997 +- 0.005 at dt 2.5e-4 (40 a^2/D0).
//
// The step: dt = 2.5e-4 a^2/D0. The midpoint drift scheme leaves an O(dt) bias where the taper
// (2.2-2.5 a) bends the mobility: with the hard repulsion (delta_num 1e-7 a, the reference before
// the hard-core oracle) at dt 1e-3 (N = 125, 40 a^2/D0) g is +1.5..+3.4 %
// high over 2.24-2.38 a and 2.3..3.2 % low over 2.42-2.48 a (z up to 6, the comparison fails); at
// 2.5e-4 no 0.02 a bin is off by more than 1.5 % (a dip of 1-1.5 % at 2.42-2.48 a, seen with two
// seeds over 40 a^2/D0 at bin SE 0.5 %: chi-square p 8e-5 and 0.16), and at 1.25e-4 the dip is gone
// (p 0.63). That last percent is below the resolution of the CI length here (bin SE about 1.5 %),
// so the positive test passes for that reason. The dt study is in
// docs/lubrication-taper.md; make validate (fldsim_validate_equilibrium) runs the long versions.
//
// The blocks are independent runs (compare_replicas): 8 runs of 0.5 + 1 a^2/D0, each from its own
// Monte Carlo start and noise seed (about 35 s on one core). Blocks of one trajectory are not
// independent at CI length: one 8 a^2/D0 run in 20 or 8 blocks failed the chi-square for one of
// five noise seeds (p 1e-5: g 3-6 % low at contact and 1-4 % high beyond 2.3 a for the whole run);
// with replicas the seed sets tried pass (against the hard-core oracle, default repulsion: seeds
// 1-8 max |z| 3.9, chi-square p 0.08, contact shell 1.026 +- 0.018; seeds 9-16 max |z| 2.5, p 0.98,
// shell 1.010 +- 0.011). Resolution: bin SE 1.5-2 %, so the taper window's time-step bias at
// dt 1e-3 (about 3 %) is not resolved here; make validate (spheres_dt1e-3) and
// docs/lubrication-taper.md resolve it. The contact shell is also asserted (|z| < 3, the Welch z of
// the block means; with about 8 degrees of freedom that is a 2 % false-alarm level, fixed seeds).
//
// Homonuclear dicolloids (c/a 0.2, phi 0.3, N 125) the same way, with 16 shorter runs of
// 0.25 + 0.5 a^2/D0 (about 50 s): the earlier attempt (6 runs of 1.5 a^2/D0 against the hard
// repulsion) passed for one seed set and failed for another (isolated bins at z 4.5: six blocks
// make the per-bin SE too uncertain for the Welch degrees of freedom); 16 blocks pass for the five
// seed sets tried (seeds 1-16, 17-32, 33-48, 49-64, 65-80: max |z| 2.2, 2.8, 4.1, 2.2, 4.0;
// chi-square p 0.98, 0.39, 0.35, 0.96, 0.011; `fldsim_validate_equilibrium dicolloid02 n=125
// runs=16 duration=0.5 equilibrate=0.25 dt=2.5e-4 every=40 oracle_sweeps=20000 seed=S`). The same
// without the thermal drift (drift=none) fails by far: max |z| 42, chi-square 3209 on 50 bins.
// Body-centre g of c/a 0.2 rises from 0.03 at 2.00 a (side by side) to its peak near 2.2 a (end
// to end), so there is no sphere-like contact shell to assert; the 0.02 a bins cover it.
//
// Must fail the same comparison: the run without the thermal drift (drift: none), and the abrupt
// lubrication cutoff (taper: none), whose spike inside 2.5 a and hole outside it must be where the
// comparison fails worst.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

using oracle::GrComparison;
using oracle::GrComparisonOptions;

// The step at which FLD's equilibrium is exact within these tests' resolution (see above).
constexpr double kDt = 2.5e-4;
// The dicolloid test's size, runs and their length (see above).
constexpr std::size_t kDicolloids = 125;
constexpr int kDicolloidRuns = 16;
constexpr double kDicolloidEquilibrate = 0.25, kDicolloidDuration = 0.5;

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
  return s;
}

oracle::OracleResult oracle_of(const EquilibriumScene& scene) {
  // FLD's steps do not reach the repulsion's overlaps (see above): the hard core.
  return run_scene_oracle(scene, comparison_oracle_options(true));
}

const oracle::OracleResult& sphere_oracle() {
  static const oracle::OracleResult r = oracle_of(spheres());
  return r;
}

EquilibriumScene dicolloids() {
  EquilibriumScene s;
  s.shape = "dicolloid";
  s.shape_params = "{a: 1, b: 1, c: 0.2}";
  s.count = kDicolloids;
  s.phi = 0.3;
  return s;
}

const oracle::OracleResult& dicolloid_oracle() {
  static const oracle::OracleResult r = oracle_of(dicolloids());
  return r;
}

// Bins of rebin x 0.01 a.
GrComparison judge(const oracle::RadialHistogram& g, const oracle::OracleResult& mc, int rebin = 2) {
  return oracle::compare_gr(g.rebinned(rebin), mc.bodies.rebinned(rebin), comparison_range());
}

void print(const GrComparison& c, const std::string& what, const EquilibriumScene& scene,
           const std::string& run, const oracle::OracleResult& mc) {
  std::cout << what << ": " << scene.describe() << "\n  " << run << "; oracle " << mc.samples << " samples\n"
            << c.table(comparison_range());
}

// The contact shell 2.00-2.05 a: g_BD / g_MC of the shell and the Welch z of the block means.
oracle::BinComparison contact_shell(const oracle::RadialHistogram& g, const oracle::OracleResult& mc) {
  const auto shell = oracle::compare_means(oracle::block_mean(g.shell_block_values(2.0, 2.05)),
                                           oracle::block_mean(mc.bodies.shell_block_values(2.0, 2.05)));
  std::printf("  contact shell 2.00-2.05 a: g_BD %.4f +- %.4f, g_MC %.4f +- %.4f, ratio %.4f, z %.2f\n",
              shell.a.mean, shell.a.se, shell.b.mean, shell.b.se, shell.ratio, shell.z);
  return shell;
}

// One trajectory in blocks (for the variants that must fail).
GrComparison compare(const EquilibriumScene& scene, const BrownianOptions& opt,
                     const oracle::OracleResult& mc, const std::string& what,
                     oracle::BinComparison* shell = nullptr) {
  const BrownianEquilibrium bd = run_brownian(scene, opt);
  const GrComparison c = judge(bd.g, mc);
  print(c, what, scene,
        std::to_string(bd.steps) + " steps of " + std::to_string(opt.dt) + ", " + std::to_string(bd.seconds) +
            " s",
        mc);
  if (shell) *shell = contact_shell(bd.g, mc);
  return c;
}

// Independent runs as the blocks: run k starts from its own hard-body Monte Carlo configuration (an
// equilibrium sample of the hard-body fluid this potential nearly is) with noise seed k, relaxes
// for `equilibrate` and is sampled for `duration`, one block each (see the top of the file).
GrComparison compare_replicas(const EquilibriumScene& scene, BrownianOptions opt, int runs,
                              const oracle::OracleResult& mc, const std::string& what,
                              oracle::BinComparison* shell = nullptr, int rebin = 2) {
  const BrownianEquilibrium bd = run_brownian_replicas(scene, opt, runs);
  const GrComparison c = judge(bd.g, mc, rebin);
  print(c, what, scene,
        std::to_string(runs) + " runs, " + std::to_string(bd.steps) + " steps of " + std::to_string(opt.dt) +
            ", " + std::to_string(bd.seconds) + " s, smallest gap " + std::to_string(bd.min_gap) + " a",
        mc);
  if (shell) *shell = contact_shell(bd.g, mc);
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
  oracle::BinComparison shell;
  const GrComparison c =
      compare_replicas(spheres(), exact_step(1.0), 8, sphere_oracle(), "FLD spheres phi 0.3", &shell);
  EXPECT_TRUE(c.pass()) << "g(r) of FLD spheres differs from the oracle";
  EXPECT_LT(std::fabs(shell.z), 3.0) << "the contact shell 2.00-2.05 a differs from the oracle's by "
                                     << shell.ratio - 1.0 << " (z " << shell.z << ")";
}

TEST(EquilibriumStructure, FldDicolloidsMatchTheOracle) {
  BrownianOptions opt = exact_step(kDicolloidDuration);
  opt.equilibrate = kDicolloidEquilibrate;
  const GrComparison c = compare_replicas(dicolloids(), opt, kDicolloidRuns, dicolloid_oracle(),
                                          "FLD dicolloids c/a 0.2 phi 0.3");
  EXPECT_TRUE(c.pass()) << "g(r) of FLD dicolloids differs from the oracle";
}

TEST(EquilibriumStructure, FldSpheresWithoutDriftFailTheComparison) {
  BrownianOptions opt;
  opt.drift = DriftScheme::None;
  opt.duration = 2.0;
  opt.equilibrate = 0.5;
  opt.blocks = 20;
  oracle::BinComparison shell;
  const GrComparison c = compare(spheres(), opt, sphere_oracle(), "drift: none", &shell);
  EXPECT_FALSE(c.pass()) << "the comparison cannot see a missing thermal drift";
  EXPECT_GT(std::fabs(shell.z), 3.0) << "the contact-shell check cannot see a missing thermal drift";
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
