// The Monte Carlo oracle against exact results (docs/equilibrium-oracle.md, "Validation"):
//  1. Two bodies in a periodic box: the separation R is distributed exactly as
//     w(R) / Z_box, w(R) = <exp(-U(R, Omega_1, Omega_2)/kT)> over orientations and directions,
//     Z_box = V - int (1 - w) d^3R; so g(R) = V w(R) / Z_box with no approximation. Spheres: w by
//     quadrature, in 0.005 a bins through the overlap and repulsion region 1.97-2.01 a, and 0.05 a
//     bins to 3 a. Dicolloids (c/a = 1, rotations): w by Monte Carlo integration over random
//     orientations (its own standard error enters z). The same comparison with a wrong acceptance
//     rule (exp(-dU/2kT)) must fail: the test can fail.
//  2. Dilute hard-sphere-like limit: spheres at phi = 0.1 against the virial series of hard spheres
//     (B2..B8) at the Barker-Henderson diameter of the potential, d = int (1 - exp(-U/kT)) dr,
//     which reproduces B2 exactly; the softness changes Z by -0.006 here.
//  3. phi = 0.3 spheres: Z against the hard-sphere equation of state of Kolafa, Labik & Malijevsky
//     (Phys. Chem. Chem. Phys. 6, 2335 (2004); it agrees with the virial series to B10 within 0.03 %
//     here, Carnahan-Starling is 0.26 % lower) at the Barker-Henderson phi; contact value g(2a+)
//     against (Z_HS - 1)/(4 phi_BH) moved from d to 2a along the hard-sphere g.
// Tolerances: per bin, Bonferroni over the bins at family-wise 1 % (t quantile of the block
// errors); for Z, 3 block SEs combined with the stated uncertainty of the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "dynamics/Scene.hpp"
#include "oracle/EquilibriumOracle.hpp"
#include "oracle/GrComparison.hpp"

namespace fldsim::testing {
namespace {

using oracle::MeanError;
using oracle::OracleOptions;
using oracle::OracleResult;
constexpr double kPi = std::numbers::pi;

Physics brownian(double phi) {
  Physics ph;
  ph.kT = 1.0;
  ph.volume_fraction = phi;
  return ph;
}

// U/kT of two unit spheres at centre distance r, from the plugin's own energy.
double sphere_pair_energy(const ForceLaw& law, const System& s, double r) {
  const NodePair p{0, 1, 0, 0, Vec3(r, 0, 0), r};
  return pair_energy_of(law)->pair_energy(s, p) / s.physics().kT;
}

// Simpson integral of f on [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int k = 1; k < n; ++k) sum += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

// int_0^inf (1 - exp(-U(r)/kT)) g(r) dr pieces for spheres: the potential acts below `reach`.
struct SphereIntegrals {
  double d_bh;      // Barker-Henderson diameter int_0^reach (1 - e^-U) dr
  double excluded;  // int_0^reach 4 pi r^2 (1 - e^-U) dr = 2 B2
};
SphereIntegrals sphere_integrals(const ForceLaw& law, const System& s, double reach) {
  auto f = [&](double r) { return -std::expm1(-sphere_pair_energy(law, s, r)); };
  // Fine grid near contact (the overlap ramp is ~0.01 a wide), coarse inside (f = 1 to 1e-140).
  const double split = 1.9;
  SphereIntegrals out{};
  out.d_bh = split + simpson(f, split, reach, 400000);
  out.excluded = 4.0 / 3.0 * kPi * std::pow(split, 3) +
                 simpson([&](double r) { return 4 * kPi * r * r * f(r); }, split, reach, 400000);
  return out;
}

// Hard-sphere compressibility factors.
double z_klm(double phi) {
  const double e = phi;
  return (1 + e + e * e - 2.0 / 3.0 * e * e * e * (1 + e)) / std::pow(1 - e, 3);
}
double z_virial_series(double phi) {  // Z = 1 + sum c_k phi^k, B2..B10 (Clisby & McCoy 2006) [R]
  const double c[] = {4.0, 10.0, 18.3648, 28.2245, 39.8151, 53.3444, 68.538, 85.813, 105.77};
  double z = 1.0, p = 1.0;
  for (double ck : c) z += ck * (p *= phi);
  return z;
}

// Two-body comparison: the oracle's blocked g against the exact g (with the SE of its quadrature),
// judged by the same family-wise rules as the Brownian comparisons (oracle/GrComparison.hpp).
oracle::GrComparison compare_with_exact(const oracle::RadialHistogram& h, const std::vector<double>& exact,
                                        const std::vector<double>& exact_se, double r_from, double r_to) {
  std::vector<oracle::BinComparison> bins;
  for (int k = 0; k < h.bins(); ++k) {
    const double lo = h.lower_edge(k);
    if (lo < r_from - 1e-9 || lo >= r_to - 1e-9) continue;
    // The reference's SE is a Monte Carlo integral over 4e4 points: its dof are effectively infinite.
    oracle::BinComparison c =
        oracle::compare_means(h.g(k), MeanError{exact[std::size_t(k)], exact_se[std::size_t(k)], 1 << 20});
    c.r_lo = lo;
    c.r_hi = lo + h.bin_width();
    c.compared = h.total_count(k) >= 20;
    bins.push_back(c);
  }
  return oracle::judge_bins(std::move(bins), 0.01);
}

struct TwoBodyRun {
  oracle::RadialHistogram fine{oracle::PairPoints::BodyCentres, 0.005, 3.5};
  oracle::RadialHistogram coarse{oracle::PairPoints::BodyCentres, 0.05, 3.5};
};

TwoBodyRun two_body_chain(System& s, const ForceLaw& law, oracle::AcceptanceRule rule, std::int64_t sweeps,
                          int blocks, bool hard_core = false) {
  s.positions()[0] = Vec3(1, 1, 1);
  s.positions()[1] = Vec3(4.5, 4.5, 4.5);
  s.orientations()[0] = s.orientations()[1] = Quat::Identity();
  s.update_nodes();
  oracle::MetropolisSampler mc(s, {pair_energy_of(law)}, law.range(s), 11, rule);
  mc.set_hard_core(hard_core);
  mc.set_steps(2.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    mc.sweep();
    mc.adapt_steps(0.4);
  }
  TwoBodyRun run;
  for (int b = 0; b < blocks; ++b) {
    for (std::int64_t k = 0; k < sweeps / blocks; ++k) {
      mc.sweep();
      run.fine.add_sample(s);
      run.coarse.add_sample(s);
    }
    run.fine.end_block();
    run.coarse.end_block();
  }
  return run;
}

// Exact two-sphere g per bin: V w / Z_box averaged over the shell. With a hard core, w = 0 below
// contact (R < 2 a): Z_box loses the overlaps' weight, int_0^2 exp(-U/kT) 4 pi R^2 dR.
std::vector<double> two_sphere_exact(const oracle::RadialHistogram& h, const ForceLaw& law, const System& s,
                                     bool hard_core = false) {
  const double reach = law.range(s), V = s.box().volume();
  auto weight = [&](double r) { return 4 * kPi * r * r * std::exp(-sphere_pair_energy(law, s, r)); };
  double zbox = V - sphere_integrals(law, s, reach).excluded;
  if (hard_core) zbox -= simpson(weight, 1.9, 2.0, 400000);  // below 1.9 a: exp(-U/kT) < 1e-7
  std::vector<double> g(std::size_t(h.bins()));
  for (int k = 0; k < h.bins(); ++k) {
    const double lo = h.lower_edge(k), hi = lo + h.bin_width();
    const double shell = 4.0 / 3.0 * kPi * (hi * hi * hi - lo * lo * lo);
    const double from = hard_core ? std::max(lo, 2.0) : lo;
    const double w = from < hi ? simpson(weight, from, hi, 2000) : 0.0;
    g[std::size_t(k)] = V * w / zbox / shell;
  }
  return g;
}

double half_acceptance(double beta_dU) {
  return beta_dU <= 0.0 ? 1.0 : std::exp(-0.5 * beta_dU);
}

TEST(Oracle, TwoSpheresSampleExactlyTheBoltzmannFactorOfThePotential) {
  auto law = make<ForceLaw>("force", "repulsion");
  System s(make<Shape>("shape", "sphere"), 2, 8.0, brownian(0.01));
  const int blocks = 40;
  const TwoBodyRun run = two_body_chain(s, *law, oracle::metropolis_acceptance, 400000, blocks);
  const auto fine = two_sphere_exact(run.fine, *law, s), coarse = two_sphere_exact(run.coarse, *law, s);
  const std::vector<double> zero_fine(fine.size(), 0.0), zero_coarse(coarse.size(), 0.0);
  const auto near = compare_with_exact(run.fine, fine, zero_fine, 1.97, 2.01);
  const auto far = compare_with_exact(run.coarse, coarse, zero_coarse, 2.0, 3.0);
  oracle::GrComparisonOptions o;
  o.label_a = "MC";
  o.label_b = "exact";
  std::cout << "two spheres, L = 8 a, " << 400000 << " sweeps in " << blocks << " blocks:\n"
            << near.table(o) << far.table(o);
  EXPECT_TRUE(near.pass());
  EXPECT_TRUE(far.pass());
  EXPECT_GE(near.compared, 6);  // the overlap bins are populated and compared

  // The broken acceptance rule samples exp(-U/2kT): the overlap bins must fail the same test.
  const TwoBodyRun broken = two_body_chain(s, *law, half_acceptance, 400000, blocks);
  const auto wrong = compare_with_exact(broken.fine, fine, zero_fine, 1.97, 2.01);
  std::cout << "with acceptance exp(-dU/2kT):\n" << wrong.table(o);
  EXPECT_FALSE(wrong.pass()) << "the two-body test cannot detect a wrong acceptance rule";
}

// The hard core (OracleOptions::hard_core, the reference for lubricated dynamics): the same two
// spheres sample exp(-U/kT) restricted to R >= 2 a: no pair below contact, and above it the exact
// g of the restricted distribution (in the 0.005 a bins of 2.00-2.01 a and the 0.05 a bins to
// 3 a). (For two bodies in 512 a^3 the restriction changes g above contact by only 0.06 %; that
// the hard core acts is the empty overlap bins, which the chain without it populates.)
TEST(Oracle, TwoSpheresWithAHardCoreSampleTheRestrictedBoltzmannFactor) {
  auto law = make<ForceLaw>("force", "repulsion");
  System s(make<Shape>("shape", "sphere"), 2, 8.0, brownian(0.01));
  const int blocks = 40;
  const TwoBodyRun run = two_body_chain(s, *law, oracle::metropolis_acceptance, 400000, blocks, true);
  for (int k = 0; k < run.fine.bins() && run.fine.lower_edge(k) + run.fine.bin_width() <= 2.0; ++k)
    EXPECT_EQ(run.fine.g(k).mean, 0.0) << "a pair below contact at " << run.fine.lower_edge(k) << " a";
  const auto fine = two_sphere_exact(run.fine, *law, s, true),
             coarse = two_sphere_exact(run.coarse, *law, s, true);
  const std::vector<double> zero_fine(fine.size(), 0.0), zero_coarse(coarse.size(), 0.0);
  const auto near = compare_with_exact(run.fine, fine, zero_fine, 2.0, 2.01);
  const auto far = compare_with_exact(run.coarse, coarse, zero_coarse, 2.0, 3.0);
  oracle::GrComparisonOptions o;
  o.label_a = "MC";
  o.label_b = "exact";
  std::cout << "two spheres with a hard core, L = 8 a:\n" << near.table(o) << far.table(o);
  EXPECT_TRUE(near.pass());
  EXPECT_TRUE(far.pass());
  EXPECT_GE(near.compared, 2);
  // Without the hard core the same chain does put pairs below contact (g about 0.7 there).
  const TwoBodyRun soft = two_body_chain(s, *law, oracle::metropolis_acceptance, 40000, 4, false);
  double below = 0.0;
  for (int k = 0; k < soft.fine.bins() && soft.fine.lower_edge(k) + soft.fine.bin_width() <= 2.0; ++k)
    below += soft.fine.g(k).mean;
  EXPECT_GT(below, 0.1) << "the zero-below-contact check cannot fail";
}

TEST(Oracle, TwoDicolloidsSampleTheOrientationAveragedBoltzmannFactor) {
  auto law = make<ForceLaw>("force", "repulsion");
  auto shape = make<Shape>("shape", "dicolloid", "{a: 1, b: 1, c: 1}");
  System s(shape, 2, 8.0, brownian(0.01));
  const int blocks = 40;
  const TwoBodyRun run = two_body_chain(s, *law, oracle::metropolis_acceptance, 400000, blocks);

  // w(R) by Monte Carlo integration: random orientations and directions at random R in each bin.
  const auto& h = run.coarse;
  System probe(shape, 2, 8.0, brownian(0.01));
  const PairEnergy& e = *pair_energy_of(*law);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uni;
  auto random_unit = [&] {
    Vec3 v(gauss(rng), gauss(rng), gauss(rng));
    return Vec3(v.normalized());
  };
  auto boltzmann = [&](double R) {
    probe.positions()[0] = Vec3(4, 4, 4);
    probe.positions()[1] = Vec3(4, 4, 4) + R * random_unit();
    probe.orientations()[0] = Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
    probe.orientations()[1] = Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
    probe.update_nodes();
    double u = 0.0;
    for (std::uint16_t a = 0; a < 2; ++a)
      for (std::uint16_t b = 0; b < 2; ++b) {
        const Vec3 r = probe.node_positions()[2 + b] - probe.node_positions()[a];
        u += e.pair_energy(probe, {0, 1, a, b, r, r.norm()});
      }
    return std::exp(-u);
  };
  // Z_box = V - int (1 - w) d^3R over R < 3.2 a (w = 1 beyond the reach c + 2a + delta_min).
  const double rc = 3.2, V = s.box().volume();
  const int n_excluded = 400000;
  double excluded = 0.0;
  for (int k = 0; k < n_excluded; ++k) excluded += 1.0 - boltzmann(rc * std::cbrt(uni(rng)));
  excluded *= 4.0 / 3.0 * kPi * rc * rc * rc / n_excluded;
  const double zbox = V - excluded;
  std::vector<double> exact(std::size_t(h.bins()), 0.0), exact_se(std::size_t(h.bins()), 0.0);
  const int n_bin = 40000;
  for (int k = 0; k < h.bins(); ++k) {
    const double lo = h.lower_edge(k), hi = lo + h.bin_width();
    if (lo < 1.5 || lo >= 3.3) continue;
    double sum = 0.0, sum2 = 0.0;
    for (int j = 0; j < n_bin; ++j) {  // R uniform in the shell volume
      const double R = std::cbrt(lo * lo * lo + uni(rng) * (hi * hi * hi - lo * lo * lo));
      const double w = boltzmann(R);
      sum += w;
      sum2 += w * w;
    }
    const double mean = sum / n_bin, var = std::max(0.0, sum2 / n_bin - mean * mean);
    exact[std::size_t(k)] = V * mean / zbox;
    exact_se[std::size_t(k)] = V * std::sqrt(var / n_bin) / zbox;
  }
  const auto cmp = compare_with_exact(h, exact, exact_se, 1.5, 3.3);
  oracle::GrComparisonOptions o;
  o.label_a = "MC";
  o.label_b = "exact";
  std::cout << "two dicolloids c/a = 1, L = 8 a:\n" << cmp.table(o);
  EXPECT_TRUE(cmp.pass());
  EXPECT_GE(cmp.compared, 20);
}

OracleResult spheres(double phi, std::size_t n, const OracleOptions& opt) {
  auto shape = make<Shape>("shape", "sphere");
  System s(shape, n, std::cbrt(double(n) * shape->volume() / phi), brownian(phi));
  return oracle::run_oracle(s, {make<ForceLaw>("force", "repulsion")}, opt);
}

TEST(Oracle, DiluteSpheresFollowTheVirialSeriesAtTheBarkerHendersonDiameter) {
  auto law = make<ForceLaw>("force", "repulsion");
  System probe(make<Shape>("shape", "sphere"), 2, 20.0, brownian(0.1));
  const double d = sphere_integrals(*law, probe, law->range(probe)).d_bh;
  const double phi = 0.1, phi_bh = phi * std::pow(d / 2.0, 3);
  OracleOptions opt;
  opt.sweeps = 20000;
  opt.blocks = 40;
  opt.node_distribution = false;
  const OracleResult r = spheres(phi, 343, opt);
  const double expected = z_virial_series(phi_bh);
  std::cout << "phi = 0.1, N = 343: Z = " << r.Z.mean << " +- " << r.Z.se << " (block ratio "
            << r.Z_block_ratio << "); hard spheres at d_BH = " << d << ": " << expected
            << " (at d = 2a: " << z_virial_series(phi) << ")\n";
  EXPECT_NEAR(r.Z.mean, expected, 3.0 * r.Z.se);
}

TEST(Oracle, SpheresAtPhi03MatchTheHardSphereEquationOfStateWithTheSoftnessCorrection) {
  auto law = make<ForceLaw>("force", "repulsion");
  System probe(make<Shape>("shape", "sphere"), 2, 20.0, brownian(0.3));
  const double d = sphere_integrals(*law, probe, law->range(probe)).d_bh;
  const double phi = 0.3, phi_bh = phi * std::pow(d / 2.0, 3);
  const double z_hs = z_klm(phi_bh);
  // Contact: y(d) = (Z - 1)/(4 phi_BH), moved from d to 2a with the hard-sphere slope of ln g at
  // contact, -2.7/sigma at phi = 0.3 (Verlet-Weis g, research notes 3b: g(1.05 sigma)/g(sigma)).
  const double y_contact = (z_hs - 1.0) / (4.0 * phi_bh) * std::exp(-2.67 * (2.0 - d) / 2.0);
  OracleOptions opt;
  opt.sweeps = 6000;
  opt.blocks = 30;
  const OracleResult r = spheres(phi, 500, opt);
  std::cout << "phi = 0.3, N = 500: Z = " << r.Z.mean << " +- " << r.Z.se << " (block ratio "
            << r.Z_block_ratio << "), node-node " << r.Z_node.mean << "; hard spheres at d_BH = " << d
            << " (phi " << phi_bh << "): KLM " << z_hs << ", virial series " << z_virial_series(phi_bh)
            << "; at d = 2a: KLM " << z_klm(phi) << ", CS 3.9738\n"
            << "contact g(2a+) = " << r.contact.mean << " +- " << r.contact.se << " (expected " << y_contact
            << "; hard spheres at 2a: " << (z_klm(phi) - 1) / (4 * phi) << ")\n";
  // Reference uncertainty 0.2 % of Z (finite N = 500 and the O(softness^2) Barker-Henderson error,
  // both estimated below 0.1 %; KLM vs the virial series 0.03 %).
  EXPECT_NEAR(r.Z.mean, z_hs, 3.0 * std::hypot(r.Z.se, 0.002 * z_hs));
  // Contact: the slope correction is itself uncertain by ~0.5 %.
  EXPECT_NEAR(r.contact.mean, y_contact, 3.0 * std::hypot(r.contact.se, 0.005 * y_contact));
  // Spheres: the node and body virials are the same quantity.
  EXPECT_NEAR(r.Z_node.mean, r.Z.mean, 1e-9);
}

}  // namespace
}  // namespace fldsim::testing
