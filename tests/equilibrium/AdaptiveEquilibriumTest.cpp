// Adaptive steps (`dt: auto`) against the Monte Carlo oracle of the same potential, at Pe = 0
// (FLD spheres against its hard core: the last tests, with their own comment).
// Free-draining spheres and homonuclear dicolloids (c/a 0.2, at the end) at phi = 0.3 are the
// hard case: the mobility at contact is the isolated
// body's, so the repulsion (0 to 166.6 kT/a over gaps 1e-3 to 1e-5 a, then a constant force below
// 1e-5 a, overlaps included: exp(-U/kT) decays over 0.006 a of overlap) is stiff against the
// Brownian step, and at the examples' fixed dt = 1e-3 the structure is wrong (issue 13). At
// dt: auto with the default tolerance (1e-4 a; 5e-4 leaves Z about 3 % high here and 1e-3
// about 5 %, docs/time_steps.md) the steps shrink where pairs touch, and the run must reproduce the oracle
// within its errors:
//   - body-centre g(r) in 0.02 a bins over [1.98, 3.0) a (overlap ramp included), block errors
//     on both sides, the family-wise rule of oracle/GrComparison.hpp (Bonferroni over the 51 bins
//     and a chi-square over all of them, together alpha = 1 % for a correct model);
//   - Z = 1 + tr(W)/(3 N kT) of the sampled configurations (molecular virial) within 3 combined
//     standard errors of the oracle's (Welch dof about 8: two-sided P(|t| > 3) = 1.7 %).
// Errors: independent runs as the blocks (as EquilibriumComparisonTest): 8 runs, run k with seed
// 1 + k (its own hard-body Monte Carlo start and noise), 0.03 a^2/D0 unsampled (a contact's life
// is ~ (0.1 a)^2 / D0 = 0.01; the overlap ramp relaxes in ~1e-4), then sampled every frame for
// 0.1 a^2/D0: the SE is the standard deviation of the 8 run means / sqrt(8). The oracle's are 40
// blocks of one Metropolis chain.
// Multiple comparisons: the two checks together fail a correct model with probability below
// 1 % + 1.7 % (union bound); seeds are fixed, so the result is deterministic for a build.
// Why not blocks of one trajectory (the test before: one run of 0.8 a^2/D0 after 0.1 in 20
// blocks): those blocks are correlated and the SE was too small. Z with the same sampled time
// (0.8 a^2/D0), `fldsim_validate_equilibrium pressure_spheres_auto n=125 force_params={}
// tolerance=5e-4 stress_every=0 max_overlap=0.1 hard_core=0 oracle_sweeps=20000 oracle_blocks=40
// equilibrate=0.03` plus `duration=0.8 blocks=20 seed=S` (one run) or `duration=0.1 runs=8
// seed=S` (8 runs, seeds S..S+7):
//   one run, seeds 1-4:       3.989 +- 0.068, 4.163 +- 0.065, 3.944 +- 0.056, 3.796 +- 0.086:
//                             the means scatter by 0.151 (sd), 2.2x their blocked SE (~0.07);
//                             seed 2 is 3.1 combined SE from this test's oracle (3.946 +- 0.026)
//   8 runs, seeds 1/9/17/25:  4.068 +- 0.107, 3.998 +- 0.095, 3.966 +- 0.100, 4.056 +- 0.097:
//                             the means scatter by 0.048 (sd), 0.5x their SE (~0.10; with 3 dof
//                             P(scatter this small | SE right) = 0.13: conservative at worst).
//   All eight means together: sd 0.107, as the independent-run SE says.
// The oracle's SE (40 blocks of one chain) is honest: `fldsim oracle` of this scene (--sweeps
// 20000 --blocks 40 --bin 0.01), seeds 1-21: Z sd 0.027 against a mean SE of 0.029; mean 3.908
// (seed 1, used here, is 3.946). Against that mean the eight 0.8 a^2/D0 means above (3.998,
// sd 0.107; not quite independent: one-run seeds 1-4 share starts and noise with runs 1-4 of
// seeds 1-8) are 2.3 % high, about 2.4 SE: tolerance 5e-4 may leave a bias of about 2 %, below
// this test's resolution.
// (The numbers above were taken at tolerance 5e-4, the test's tolerance until 4 December 2026.)
// The step bias, resolved with 32 runs from seed 201 (docs/time_steps.md, "How small a
// tolerance?"): Z / Z_MC 1.030 +- 0.012 at 5e-4, 1.020 +- 0.012 at 2.5e-4, 1.012 +- 0.012 at 1e-4
// (Box-Muller and polar normals alike). At 5e-4 the 8 runs here sat near the 3-SE edge (the polar
// normals put them at 1.062, z 3.09), so the test runs at the default, 1e-4, where the bias
// (about 1 %, 0.4 SE) leaves a correct model failing rarely.
// Measured (polar normals, tolerance 1e-4): Z 3.907 +- 0.047 against the oracle's 3.946 +-
// 0.026 (ratio 0.990, z -0.73), 851 255 steps: pass. With the ziggurat normals (5 December 2026,
// night): Z 3.885 +- 0.096 (ratio 0.985, z -0.61), g max |z| 2.46, chi-square p 0.69, 855 026 steps.
// Power: the combined SE of Z is 2.8 %, so Z biases above about 8.5 % fail (the one-run SE said
// 1.8 %, but that was too small); the "Z within 2 %" needs runs 20 times longer
// (fldsim_validate_equilibrium pressure_spheres_auto).
// Broken variants: the fixed step 1e-3 fails the same comparison with the same 8 runs (below, in
// CI: Z ratio 2.15, z 17.7; g max |z| 28.8, chi-square 271 on 51 bins). A 4x looser tolerance
// (2e-3) is no longer resolved: with these 8 runs Z = 4.200 +- 0.121 (ratio 1.064, z 2.1), g max
// |z| 1.8, the overlap bin 1.98-2.00 a 0.781 +- 0.031 against 0.720 +- 0.006 (the same
// fldsim_validate_equilibrium command with tolerance=2e-3 runs=8 seed=1 pressure=0); with one
// run and its too small blocked SE it had looked caught (Z 8 % high, z = 4.3 in 1.5 a^2/D0).
// Neither is the controller on the root mean square over bodies (Z +5 %) nor redraw-on-reject
// (+1 %); tests/dynamics/AdaptiveStepTest.cpp catches the redraw.
// About 200 CPU seconds (N = 125, 8 x 0.13 a^2/D0, 851 000 steps at tolerance 1e-4, 4x those of
// 5e-4; the 32-run check took 785 CPU s).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "BrownianEquilibrium.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

using oracle::GrComparison;
using oracle::GrComparisonOptions;

// Independent runs and their length (a^2/D0), see above.
constexpr int kRuns = 8;
constexpr double kEquilibrate = 0.03, kDuration = 0.1;
constexpr int kFldRuns = 16;                // FLD at dt: auto (its own comment below)
constexpr double kDefaultTolerance = 1e-4;  // run.tolerance's default (docs/time_steps.md)

GrComparisonOptions comparison_range() {
  GrComparisonOptions o;
  o.r_from = 1.98;
  o.r_to = 3.0;
  return o;
}

// Free draining reaches the repulsion's overlaps: the full potential, no hard core.
oracle::OracleResult oracle_of(const EquilibriumScene& scene) {
  return run_scene_oracle(scene, comparison_oracle_options(false));
}

const oracle::OracleResult& sphere_oracle() {
  static const oracle::OracleResult r = oracle_of(free_draining_spheres());
  return r;
}

// Homonuclear dicolloids (the paper's c/a = 0.2), the same fluid otherwise.
EquilibriumScene free_draining_dicolloids() {
  EquilibriumScene s = free_draining_spheres();
  s.shape = "dicolloid";
  s.shape_params = "{a: 1, b: 1, c: 0.2}";
  return s;
}

const oracle::OracleResult& dicolloid_oracle() {
  static const oracle::OracleResult r = oracle_of(free_draining_dicolloids());
  return r;
}

struct Verdict {
  GrComparison g;
  oracle::BinComparison Z;
};

// Independent runs as the blocks (BrownianEquilibrium.hpp): run k has seed opt.seed + k, its own
// hard-body Monte Carlo start and noise, and is one block of g and Z.
Verdict compare(const EquilibriumScene& scene, const oracle::OracleResult& mc, const BrownianOptions& opt,
                int runs, const std::string& what) {
  const BrownianEquilibrium bd = run_brownian_replicas(scene, opt, runs);
  const auto o = comparison_range();
  Verdict v;
  v.g = oracle::compare_gr(bd.g.rebinned(2), mc.bodies.rebinned(2), o);
  v.Z = oracle::compare_means(bd.Z, mc.Z);
  std::cout << what << ": " << scene.describe() << "\n  " << runs << " runs, " << bd.steps << " frames, "
            << bd.accepted << " steps, " << bd.rejected << " rejected, smallest gap " << bd.min_gap << " a, "
            << bd.seconds << " s\n  Z = " << bd.Z.mean << " +- " << bd.Z.se << " against the oracle's "
            << mc.Z.mean << " +- " << mc.Z.se << " (ratio " << v.Z.ratio << ", z " << v.Z.z << ")\n"
            << v.g.table(o);
  return v;
}

Verdict compare(const BrownianOptions& opt, int runs, const std::string& what) {
  return compare(free_draining_spheres(), sphere_oracle(), opt, runs, what);
}

BrownianOptions adaptive_options(double tolerance) {
  BrownianOptions opt;
  opt.adaptive = true;
  opt.dt = 1e-3;  // dt_max: the frame
  opt.tolerance = tolerance;
  opt.equilibrate = kEquilibrate;
  opt.duration = kDuration;
  opt.sample_every = 1;
  return opt;
}

bool agrees(const Verdict& v) {
  return v.g.pass() && std::fabs(v.Z.z) < 3.0;
}

TEST(AdaptiveEquilibrium, FreeDrainingSpheresMatchTheOracle) {
  const Verdict v =
      compare(adaptive_options(kDefaultTolerance), kRuns, "dt: auto, tolerance 1e-4 a (the default)");
  EXPECT_TRUE(v.g.pass()) << "g(r) differs from the oracle";
  EXPECT_LT(std::fabs(v.Z.z), 3.0) << "Z differs from the oracle's by more than 3 standard errors";
}

// The same for homonuclear dicolloids (body-centre g(r); Z from the molecular virial), each run
// relaxed for 0.15 a^2/D0 (0.03 is too short from the hard-body start here: with it the two bins
// 2.78-2.86 a came out 5 % low, z -4.2 and -4.0, chi-square p 0.04; with 0.15: max |z| 3.07,
// chi-square 40.4 on 50 bins, p 0.83, Z 4.053 +- 0.149 against 3.916 +- 0.032, z 0.9; about 55
// CPU s; at tolerance 5e-4, with Box-Muller normals). With the polar normals at 5e-4 these runs
// read Z 4.106 +- 0.071 against 3.916 +- 0.032 (ratio 1.049, z 2.43): near the edge as for
// spheres, so this test too runs at the default tolerance 1e-4: Z 4.014 +- 0.066 (ratio 1.025,
// z 1.34), g max |z| 2.64, chi-square p 0.51, 866 000 steps, about 225 CPU s (polar normals);
// with the ziggurat normals Z 4.015 +- 0.087 (ratio 1.025, z 1.07), g max |z| 2.63, chi-square
// p 0.63, 850 381 steps.
// Broken variant, measured once with these runs: the fixed step 1e-3 gives Z 10.6 +- 0.4 (ratio
// 2.71, z 16.1), g max |z| 13.4, chi-square 227 on 51 bins: fails.
TEST(AdaptiveEquilibrium, FreeDrainingDicolloidsMatchTheOracle) {
  BrownianOptions opt = adaptive_options(kDefaultTolerance);
  opt.equilibrate = 0.15;
  const Verdict v = compare(free_draining_dicolloids(), dicolloid_oracle(), opt, kRuns,
                            "dicolloids c/a 0.2, dt: auto, tolerance 1e-4 a (the default)");
  EXPECT_TRUE(v.g.pass()) << "g(r) differs from the oracle";
  EXPECT_LT(std::fabs(v.Z.z), 3.0) << "Z differs from the oracle's by more than 3 standard errors";
}

// FLD at dt: auto (issue 13 item 4). With lubrication the squeeze mobility vanishes with the gap,
// so the steps never reach the repulsion's overlap population and the reference is the oracle's
// hard core, as for the fixed-step FLD tests (EquilibriumComparisonTest.cpp): body-centre g(r) in
// 0.02 a bins from contact to 3 a (same family-wise rule), and the hard core's contact term
// f(0+)/(3N) of the sampled configurations against the oracle's (the contact density that issue 11
// part 4 is about; spheres also the contact shell 2.00-2.05 a), each |z| < 3. The molecular virial
// Z is not compared: the few shallow overlaps FLD does reach (smallest gap -1e-3 a) carry a
// heavy-tailed virial that the hard core has none of (32 runs: 1.167 +- 0.050 against 1.022).
// Tolerance 1e-3 a (frame 1e-3 a^2/D0): mean steps of 5e-5 a^2/D0 where pairs touch, about 5
// times the steps of the fixed 2.5e-4 the fixed-step tests use (docs/lubrication-taper.md: at
// Pe = 0 the fixed step is the cheaper exact route; this test is that the controller is exact).
// 16 independent runs of 0.03 + 0.1 a^2/D0 (the free-draining runs' length), about 50 CPU s.
// Measured (fldsim_validate_equilibrium spheres|dicolloid02 n=125 adaptive=1 dt=1e-3
// tolerance=1e-3 runs=16 seed=1 equilibrate=0.03|0.15 duration=0.1 every=1 oracle_sweeps=20000
// contact_term=1):
//   spheres, seeds 1-16: g max |z| 1.82, chi-square 38.2 on 50 bins (p 0.89); contact shell
//     1.003 +- 0.026; contact term 3.085 +- 0.113 against 2.950 +- 0.022 (ratio 1.046, z 1.2);
//     seeds 101-132 (32 runs): max |z| 2.23, p 0.73, shell 1.003 +- 0.019, contact term ratio 0.978
//     (z -0.7);
//   homonuclear dicolloids c/a 0.2, seeds 1-16 (relaxed 0.15): max |z| 1.90, p 0.88, contact term
//     ratio 1.024 +- 0.047, but 228 000 steps (mean 1.8e-5 a^2/D0): too long for CI, so only in
//     make validate (fld_auto_dicolloid02, 32 runs; fld_auto_spheres, 64 runs).
// Broken variant, measured once on the same seeds: without the thermal drift (dt: auto refuses
// drift: none, which has no embedded estimate, so at the fixed mean step 5e-5: spheres runs=16
// seed=1 drift=none dt=5e-5 every=20) the contact shell is 1.83 +- 0.02 (z 35), the contact term
// 4.5 times the oracle's (z 44), g(2.00-2.02) 3.3 times (z 43): fails.
EquilibriumScene fld_spheres() {
  EquilibriumScene s;  // fld with its defaults, the default repulsion
  s.count = 125;
  s.phi = 0.3;
  return s;
}

BrownianOptions fld_adaptive_options() {
  BrownianOptions opt = adaptive_options(1e-3);
  opt.contact_term = true;
  return opt;
}

struct HardCoreVerdict {
  GrComparison g;
  oracle::BinComparison shell, contact;
};

HardCoreVerdict compare_with_hard_core(const EquilibriumScene& scene, const BrownianOptions& opt,
                                       const std::string& what) {
  const oracle::OracleResult mc = run_scene_oracle(scene, comparison_oracle_options(true));
  const BrownianEquilibrium bd = run_brownian_replicas(scene, opt, kFldRuns);
  GrComparisonOptions o;
  o.r_from = 2.0;  // the hard core has no overlaps
  o.r_to = 3.0;
  HardCoreVerdict v;
  v.g = oracle::compare_gr(bd.g.rebinned(2), mc.bodies.rebinned(2), o);
  v.shell = oracle::compare_means(oracle::block_mean(bd.g.shell_block_values(2.0, 2.05)),
                                  oracle::block_mean(mc.bodies.shell_block_values(2.0, 2.05)));
  v.contact = oracle::compare_means(bd.Z_contact, contact_term_reference(mc));
  std::cout << what << ": " << scene.describe() << "\n  " << kFldRuns << " runs, " << bd.steps << " frames, "
            << bd.accepted << " steps, " << bd.rejected << " rejected, smallest gap " << bd.min_gap << " a, "
            << bd.seconds << " s\n  contact shell 2.00-2.05 a: ratio " << v.shell.ratio << ", z " << v.shell.z
            << "\n  hard core's contact term of the configurations " << bd.Z_contact.mean << " +- "
            << bd.Z_contact.se << " against the oracle's " << v.contact.b.mean << " +- " << v.contact.b.se
            << " (ratio " << v.contact.ratio << ", z " << v.contact.z << ")\n"
            << v.g.table(o);
  return v;
}

TEST(AdaptiveEquilibrium, FldSpheresMatchTheHardCoreOracle) {
  const HardCoreVerdict v = compare_with_hard_core(fld_spheres(), fld_adaptive_options(),
                                                   "fld spheres, dt: auto, tolerance 1e-3 a");
  EXPECT_TRUE(v.g.pass()) << "g(r) differs from the hard-core oracle";
  EXPECT_LT(std::fabs(v.shell.z), 3.0) << "the contact shell differs from the oracle's";
  EXPECT_LT(std::fabs(v.contact.z), 3.0) << "the contact density differs from the oracle's";
}

TEST(AdaptiveEquilibrium, FixedStepOfTheExamplesFailsTheSameComparison) {
  BrownianOptions fixed;
  fixed.dt = 1e-3;
  fixed.equilibrate = kEquilibrate;
  fixed.duration = kDuration;
  fixed.sample_every = 1;
  EXPECT_FALSE(agrees(compare(fixed, kRuns, "fixed dt 1e-3"))) << "the comparison cannot see a too long step";
}

}  // namespace
}  // namespace fldsim::testing
