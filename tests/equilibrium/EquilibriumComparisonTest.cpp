// At Pe = 0 the distribution of the bodies must not depend on the hydrodynamic model: a Brownian
// run of FLD must reproduce the Monte Carlo oracle of the same potential (the thermal drift
// kT div M makes exp(-U/kT) stationary: Ermak & McCammon, J. Chem. Phys. 69, 1352 (1978)).
// Body-centre g(r) in 0.02 a bins from 1.98 a (overlaps of the soft repulsion) to 3.0 a, block
// errors on both sides, the family-wise rule of oracle/GrComparison.hpp (Bonferroni over the bins
// and chi-square, together 1 % false alarms). Reduced size for CI (make validate runs the long
// versions). The same comparison must fail without the drift (the test can fail), and the
// abrupt lubrication cutoff (hydro `taper: none`) must show its artifact at 2.5 a.
#include <gtest/gtest.h>

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

EquilibriumScene spheres() {
  EquilibriumScene s;
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
    return run_scene_oracle(spheres(), o);
  }();
  return r;
}

GrComparison compare(const BrownianEquilibrium& bd, const oracle::OracleResult& mc, const std::string& what) {
  const auto o = comparison_range();
  const GrComparison c = oracle::compare_gr(bd.g.rebinned(2), mc.bodies.rebinned(2), o);
  std::cout << what << " (" << bd.steps << " steps, " << bd.seconds << " s; oracle " << mc.samples
            << " samples):\n"
            << c.table(o);
  return c;
}

TEST(EquilibriumStructure, FldSpheresWithoutDriftFailTheComparison) {
  BrownianOptions opt;
  opt.drift = DriftScheme::None;
  opt.duration = 2.0;
  opt.equilibrate = 0.5;
  opt.blocks = 20;
  const auto bd = run_brownian(spheres(), opt);
  const GrComparison c = compare(bd, sphere_oracle(), "FLD spheres phi 0.3, drift: none");
  EXPECT_FALSE(c.pass()) << "the comparison cannot see a missing thermal drift";
}

}  // namespace
}  // namespace fldsim::testing
