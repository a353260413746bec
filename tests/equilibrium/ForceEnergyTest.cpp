// Every built-in force plugin that declares a pair energy (fldsim::PairEnergy) must apply exactly
// its negative gradient, or the Monte Carlo oracle samples another potential than the dynamics
// feels. Checked by central finite differences (error O(h^2 U''') plus round-off eps U / h):
//   1. two spheres along a line, surface gaps from -0.05 a (overlap) to beyond the range, on a
//      geometric grid through the law's small-gap region: F(r) = -dU/dr;
//   2. two dicolloids (c/a = 1) at random orientations near contact: body force -dU/dX and torque
//      -dU/dtheta (rotation about each axis), which also checks the node-pair sum with offsets.
// Tolerance: 1e-5 |F| + 1e-9 max|F| with h = 1e-4 max(|gap|, 1e-4 a) (relative curvature error (h/gap)^2 <=
// 1e-6 for the 1/gap forces; round-off eps U / h below 1e-9 of F). The sphere grid avoids the force's kinks
// (see below); there a central difference is the mean of two slopes, not a defect. A law without an energy is
// listed and skipped; the test fails if no law declares one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dynamics/Scene.hpp"
#include "fldsim/force.hpp"
#include "fldsim/rigid.hpp"
#include "oracle/PairVirial.hpp"

namespace fldsim::testing {
namespace {

double total_energy(const System& s, const PairEnergy& energy, double range) {
  const std::size_t m = s.nodes_per_body();
  double u = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b) {
          const Vec3 r = s.box().minimum_image(s.node_positions()[j * m + b] - s.node_positions()[i * m + a]);
          const double d = r.norm();
          if (d < range + 1.0)  // beyond the range too: the energy must be zero there by itself
            u += energy.pair_energy(
                s, {std::uint32_t(i), std::uint32_t(j), std::uint16_t(a), std::uint16_t(b), r, d});
        }
  return u;
}

std::vector<double> wrench_of(const System& s, const ForceLaw& law) {
  CellNeighbourList list;
  list.configure(law.range(s), 0.0);
  list.update(s);
  std::vector<double> w(6 * s.size(), 0.0);
  law.add(s, list.pairs(), w.data(), nullptr);
  return w;
}

Physics brownian_physics() {
  Physics ph;
  ph.kT = 1.0;
  ph.volume_fraction = 0.3;
  return ph;
}

std::vector<std::string> force_plugin_names() {
  std::vector<std::string> names;
  for (const auto& p : registry().plugins())
    if (p.kind == "force") names.push_back(p.name);
  return names;
}

TEST(ForceEnergy, EveryDeclaredEnergyIsThePotentialOfItsForceBetweenSpheres) {
  int with_energy = 0;
  // Every plugin with its defaults, and the repulsion's earlier continuation into overlaps.
  std::vector<std::pair<std::string, std::string>> laws;
  for (const auto& name : force_plugin_names()) laws.emplace_back(name, "{}");
  laws.emplace_back("repulsion", "{overlap: wall}");
  laws.emplace_back("repulsion", "{overlap: wall, wall_length: 1e-6, wall_factor: 100}");
  for (const auto& [name, params] : laws) {
    SCOPED_TRACE(name + params);
    auto law = make<ForceLaw>("force", name, params);
    const PairEnergy* energy = pair_energy_of(*law);
    if (!energy) {
      std::cout << "force " << name << ": no pair energy declared (skipped)\n";
      continue;
    }
    ++with_energy;
    auto shape = make<Shape>("shape", "sphere");
    System s(shape, 2, 20.0, brownian_physics());
    const double range = law->range(s), reach = range - 2.0;
    auto at = [&](double r) {
      s.positions()[0] = Vec3(5.0, 5.0, 5.0);
      s.positions()[1] = Vec3(5.0 + r, 5.0, 5.0);
      s.update_nodes();
    };
    // Gaps: overlaps -0.05..-1e-7, then 1e-7 .. 1.2 * reach, geometric (16 per decade), offset by
    // half a step so that no point sits within h of a round parameter value (a kink of the force,
    // e.g. the clamp at delta_num = 1e-5, where a central difference averages two slopes).
    std::vector<double> gaps;
    const double ratio = std::pow(10.0, 1.0 / 16.0), offset = std::sqrt(ratio);
    for (double g = 0.05 * offset; g > 1e-7; g /= ratio) gaps.push_back(-g);
    for (double g = 1e-7 * offset; g < 1.2 * reach; g *= ratio) gaps.push_back(g);
    double fmax = 0.0;
    std::vector<double> f_coded(gaps.size());
    for (std::size_t k = 0; k < gaps.size(); ++k) {
      at(2.0 + gaps[k]);
      f_coded[k] = wrench_of(s, *law)[6];  // x force on body 1, pushed along +x if repulsive
      fmax = std::max(fmax, std::abs(f_coded[k]));
    }
    ASSERT_GT(fmax, 0.0);
    for (std::size_t k = 0; k < gaps.size(); ++k) {
      // h >= 1e-8 a: positions near 5 a carry 1e-15 a of round-off, 1e-7 of such an h.
      const double r = 2.0 + gaps[k], h = 1e-4 * std::max(std::abs(gaps[k]), 1e-4);
      at(r + h);
      const double up = total_energy(s, *energy, range);
      at(r - h);
      const double down = total_energy(s, *energy, range);
      const double f_fd = -(up - down) / (2.0 * h);
      EXPECT_NEAR(f_coded[k], f_fd, 1e-5 * std::abs(f_coded[k]) + 1e-9 * fmax) << "gap " << gaps[k];
    }
    at(range + 1e-9);
    EXPECT_EQ(total_energy(s, *energy, range), 0.0) << "energy beyond range()";
  }
  EXPECT_GT(with_energy, 0) << "no force plugin declares a pair energy";
}

// The repulsion's continuation into overlaps (ShortRangeRepulsion.hpp): with the defaults, at
// Pe = 0, F(delta_num = 1e-5 a) = C_p (delta_min/delta_num) (eta - eta^2/2)^3 = 166.6 kT/a, and
// overlaps feel the same (`overlap: plateau`, the default); `overlap: wall` adds F(delta_num) per
// 1e-4 a of overlap up to 10 F(delta_num) (reached at 9e-4 a); 0 <= gap < delta_num is the
// paper's clamp either way.
TEST(ForceEnergy, RepulsionOverlapsMeetTheWallOrThePlateau) {
  auto shape = make<Shape>("shape", "sphere");
  System s(shape, 2, 20.0, brownian_physics());
  const double eta = 1.0 - 1e-5 / 1e-3, g = eta - 0.5 * eta * eta;
  const double f_num = 10.0 * 8.0 * M_PI * s.physics().viscosity * 1e2 * g * g * g;  // D0/a^2 = 1/(6 pi mu)
  EXPECT_NEAR(f_num, 166.6, 0.1);
  auto force_at = [&](const ForceLaw& law, double gap) {
    s.positions()[0] = Vec3(5.0, 5.0, 5.0);
    s.positions()[1] = Vec3(7.0 + gap, 5.0, 5.0);
    s.update_nodes();
    return wrench_of(s, law)[6];
  };
  auto wall = make<ForceLaw>("force", "repulsion", "{overlap: wall}");
  auto plateau = make<ForceLaw>("force", "repulsion");
  for (double gap : {5e-6, 0.0}) {  // the paper's clamp, unchanged
    EXPECT_NEAR(force_at(*wall, gap), f_num, 1e-9 * f_num) << "gap " << gap;
    EXPECT_NEAR(force_at(*plateau, gap), f_num, 1e-9 * f_num) << "gap " << gap;
  }
  for (double overlap : {2e-6, 5e-5, 8.9e-4, 1e-3, 0.3}) {
    const double wall_factor = std::min(1.0 + overlap / 1e-4, 10.0);
    EXPECT_NEAR(force_at(*wall, -overlap), wall_factor * f_num, 1e-6 * f_num) << "overlap " << overlap;
    EXPECT_NEAR(force_at(*plateau, -overlap), f_num, 1e-6 * f_num) << "overlap " << overlap;
  }
}

TEST(ForceEnergy, BodyForceAndTorqueOfDicolloidsAreMinusTheEnergyGradient) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& name : force_plugin_names()) {
    SCOPED_TRACE(name);
    auto law = make<ForceLaw>("force", name);
    const PairEnergy* energy = pair_energy_of(*law);
    if (!energy) continue;
    auto shape = make<Shape>("shape", "dicolloid", "{a: 1, b: 1, c: 1}");
    System s(shape, 2, 30.0, brownian_physics());
    const double range = law->range(s), reach = range - 2.0;
    int tested = 0;
    for (int trial = 0; trial < 400 && tested < 40; ++trial) {
      // Random orientations; place body 1 along a random direction at the distance where the
      // closest node pair has a gap drawn in [-0.3, 1.2] x reach (or a small overlap).
      s.orientations()[0] = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
      s.orientations()[1] = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      const double target = (trial % 4 == 0 ? -0.01 : 0.0) + (0.5 * u(rng) + 0.55) * 1.2 * reach;
      // Bisection on the centre distance for the smallest node gap = target.
      double lo = 0.5, hi = 6.0;
      for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        s.positions()[0] = Vec3(15, 15, 15);
        s.positions()[1] = Vec3(15, 15, 15) + mid * dir;
        s.update_nodes();
        double gmin = 1e9;
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b)
            gmin = std::min(gmin, (s.node_positions()[2 + b] - s.node_positions()[a]).norm() - 2.0);
        (gmin < target ? lo : hi) = mid;
      }
      const std::vector<double> w = wrench_of(s, *law);
      const double scale = Eigen::Map<const Eigen::VectorXd>(w.data(), 12).cwiseAbs().maxCoeff();
      if (scale == 0.0) continue;
      ++tested;
      const Vec3 x1 = s.positions()[1];
      const Quat q1 = s.orientations()[1];
      const double h = 1e-4 * std::max(std::abs(target), 1e-4);
      for (int k = 0; k < 3; ++k) {
        auto energy_at = [&](double step, bool rotate) {
          s.positions()[1] = x1;
          s.orientations()[1] = q1;
          if (rotate)
            s.orientations()[1] = Quat(Eigen::AngleAxisd(step, Vec3::Unit(k))) * q1;
          else
            s.positions()[1][k] += step;
          s.update_nodes();
          return total_energy(s, *energy, range);
        };
        const double force = -(energy_at(h, false) - energy_at(-h, false)) / (2 * h);
        const double torque = -(energy_at(h, true) - energy_at(-h, true)) / (2 * h);
        EXPECT_NEAR(w[6 + k], force, 1e-5 * scale) << "trial " << trial << " force " << k;
        EXPECT_NEAR(w[9 + k], torque, 1e-5 * scale) << "trial " << trial << " torque " << k;
      }
      s.positions()[1] = x1;
      s.orientations()[1] = q1;
    }
    EXPECT_GE(tested, 20);
  }
}

// The virial a force law reports (ForceLaw::add, API 3) is the molecular one, sum R (x) f_j with R
// the bodies' centre separation: checked for every built-in force against oracle::PairVirial, which
// gets each node pair's force from add()'s wrench alone, on dicolloids (c/a = 1) near contact, where
// the node-node virial differs. Round-off tolerance (the same sums in another order).
TEST(ForceVirial, EveryForceReportsTheMolecularVirialOfRigidBodies) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& name : force_plugin_names()) {
    SCOPED_TRACE(name);
    auto law = make<ForceLaw>("force", name);
    auto shape = make<Shape>("shape", "dicolloid", "{a: 1, b: 1, c: 1}");
    const double L = 7.0;
    System s(shape, 12, L, brownian_physics());
    // Random orientations; bodies on a loose lattice squeezed until some node pairs overlap slightly.
    for (std::size_t i = 0; i < s.size(); ++i) {
      s.positions()[i] = Vec3(double(i % 3) * 2.3 + u(rng) * 0.2, double((i / 3) % 2) * 3.0 + u(rng) * 0.2,
                              double(i / 6) * 3.0 + u(rng) * 0.2);
      s.orientations()[i] = Quat(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    }
    s.update_nodes();
    CellNeighbourList list;
    list.configure(law->range(s), 0.0);
    list.update(s);
    std::vector<double> w(6 * s.size(), 0.0);
    Eigen::Matrix3d reported = Eigen::Matrix3d::Zero();
    law->add(s, list.pairs(), w.data(), &reported);
    oracle::PairVirial independent(s, {law.get()});
    const oracle::Virials v = independent.measure(s);
    ASSERT_GT(v.body.norm(), 0.0) << "no pair within the force's range: the test checks nothing";
    EXPECT_GT((v.node - v.body).norm(), 1e-3 * v.body.norm()) << "node and body virials coincide here";
    EXPECT_LT((reported - v.body).norm(), 1e-10 * v.body.norm()) << "reported\n"
                                                                 << reported << "\nmolecular\n"
                                                                 << v.body;
  }
}

}  // namespace
}  // namespace fldsim::testing
