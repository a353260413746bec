// Dynamics driven through the hydro models: the lubrication squeeze law, free-draining bodies in
// shear (sphere, Jeffery orbit of a dicolloid), the Einstein viscosity from the stresslets, and
// the FLD R_0(phi) mobility.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "HydroTestSupport.hpp"
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"

using namespace fldsim;
using namespace fldsim::hydro;
using namespace fldsim::hydro::test;

namespace {

ModelSettings free_draining() {
  ModelSettings s;
  s.lubrication = false;
  s.isotropic = IsotropicForm::NodeSum;
  return s;
}

HydroRequest deterministic(bool shear, bool stresslets) {
  HydroRequest r;
  r.brownian = false;
  r.shear = shear;
  r.stresslets = stresslets;
  return r;
}

// Squeeze law of two equal unit spheres under equal and opposite forces F along the line of
// centres: (6 pi mu a + 2 c_sq(h)) dh/dt = -2F with c_sq = 6 pi mu a (1/(4h) + (9/40) ln(1/h))
// (X^A leading terms, Jeffrey & Onishi 1984). With 6 pi mu a = 1:
//   t(h) = int_h^h0 [1/2 + 1/(4h') + (9/40) ln(1/h')] dh' / F
//        = [(h0 - h)/2 + (1/4) ln(h0/h) + (9/40)(h0 (1 + ln(1/h0)) - h (1 + ln(1/h)))] / F.
double squeeze_time(double h0, double h, double F) {
  auto prim = [](double x) { return x * (1.0 + std::log(1.0 / x)); };
  return ((h0 - h) / 2.0 + 0.25 * std::log(h0 / h) + 9.0 / 40.0 * (prim(h0) - prim(h))) / F;
}

}  // namespace

TEST(LubricationModel, SqueezeFollowsJeffreyOnishiLawOverThreeDecades) {
  System s(sphere_shape(), 2, 30.0, physics(0.0, 0.0, 0.0));
  const double h0 = 0.1, F = 1.0;
  s.positions()[0] = Vec3(10, 10, 10);
  s.positions()[1] = Vec3(12 + h0, 10, 10);
  s.update_nodes();
  ModelSettings settings;
  settings.tolerance = 1e-12;
  ResistanceModel model(settings);
  model.configure(s, deterministic(false, false));
  const double range = model.pair_range(s);
  const double force[12] = {F, 0, 0, 0, 0, 0, -F, 0, 0, 0, 0, 0};
  // Relative velocity of sphere 1 towards sphere 0 at the current configuration.
  auto gap_rate = [&](System& sys) {
    sys.update_nodes();
    const NodePairList pairs = brute_force_pairs(sys, range);
    model.assemble(sys, pairs);
    double dU[12] = {0};
    model.solve(sys, force, dU);
    return dU[6] - dU[0];
  };
  auto gap = [&](const System& sys) { return (sys.positions()[1] - sys.positions()[0]).norm() - 2.0; };

  double t = 0.0;
  const double targets[] = {1e-2, 1e-3, 1e-4};
  int next = 0;
  while (next < 3) {
    // Midpoint rule with steps of 0.5% of the gap (local error O((dh/h)^3), far below 1%).
    const double h = gap(s);
    const double v1 = gap_rate(s);
    const double dt = 5e-3 * h / std::abs(v1);
    System mid = s;
    mid.positions()[1].x() += 0.5 * dt * v1;
    const double v2 = gap_rate(mid);
    s.positions()[1].x() += dt * v2;
    const double h_new = gap(s);
    while (next < 3 && h_new <= targets[next]) {
      const double t_cross = t + dt * (h - targets[next]) / (h - h_new);
      const double ref = squeeze_time(h0, targets[next], F);
      EXPECT_NEAR(t_cross / ref, 1.0, 0.01)
          << "gap " << targets[next] << ": t = " << t_cross << ", JO " << ref;
      std::printf("squeeze: gap %.0e reached at t = %.6f, JO law %.6f (ratio %.6f)\n", targets[next], t_cross,
                  ref, t_cross / ref);
      ++next;
    }
    t += dt;
  }
}

TEST(FreeDraining, SpheresFollowTheShearAndGiveEinsteinViscosity) {
  // Dilute force-free spheres in u = gammadot y e_x: U = gammadot y e_x, Omega = -gammadot/2 e_z
  // exactly (reference §5), and the stresslet (20/3) pi mu a^3 E per sphere gives
  // sigma_xy = mu gammadot (1 + 2.5 phi) (Einstein).
  const std::size_t n = 20;
  const double L = 30.0, gd = 0.7;
  System s(sphere_shape(), n, L, physics(0.0, gd, 0.0));
  random_configuration(s, 1.0, 8);
  ResistanceModel model(free_draining());
  model.configure(s, deterministic(true, true));
  model.assemble(s, NodePairList{});
  std::vector<double> F(6 * n, 0.0), dU(6 * n, 1.0);
  model.solve(s, F.data(), dU.data());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 U = s.flow_velocity(s.positions()[i]) + Eigen::Map<const Vec3>(dU.data() + 6 * i);
    const Vec3 W = s.flow_vorticity() + Eigen::Map<const Vec3>(dU.data() + 6 * i + 3);
    EXPECT_NEAR((U - Vec3(gd * s.positions()[i].y(), 0, 0)).norm(), 0.0, 1e-14);
    EXPECT_NEAR((W - Vec3(0, 0, -0.5 * gd)).norm(), 0.0, 1e-15);
  }
  const Eigen::Matrix3d S = model.stresslet_sum(s, NodePairList{}, dU.data());
  const double mu = s.physics().viscosity, V = L * L * L;
  const double phi = n * 4.0 / 3.0 * kPi / V;
  EXPECT_NEAR(1.0 + S(0, 1) / (V * mu * gd), 1.0 + 2.5 * phi, 1e-13);
  EXPECT_NEAR(S(0, 0), 0.0, 1e-15);
}

TEST(FreeDraining, DicolloidJefferyOrbitPeriod) {
  // Free-draining homonuclear dicolloid c/a = 1: friction perpendicular 16 pi mu a^3 + 3 pi mu a c^2,
  // Bretherton constant B = 1.5 (c/a)^2/(1.5 (c/a)^2 + 8), r_e = sqrt((1+B)/(1-B)), Jeffery period
  // T gammadot = 2 pi (r_e + 1/r_e) = 12.726 (reference §5). RK4 on the director in the flow-gradient
  // plane with the model's solve; the period is the time for the in-plane angle to turn by 2 pi.
  const double c = 1.0, gd = 1.0;
  System s(dicolloid_shape(c), 1, 30.0, physics(0.0, gd, 0.0));
  ResistanceModel model(free_draining());
  model.configure(s, deterministic(true, false));
  const double F[6] = {0, 0, 0, 0, 0, 0};
  auto rate = [&](const Vec3& n) {
    s.orientations()[0] = Quat::FromTwoVectors(Vec3::UnitZ(), n.normalized());
    s.update_nodes();
    model.assemble(s, NodePairList{});
    double dU[6] = {0};
    model.solve(s, F, dU);
    const Vec3 Omega = s.flow_vorticity() + Eigen::Map<const Vec3>(dU + 3);
    return Vec3(Omega.cross(n));
  };
  Vec3 n = Vec3::UnitX();
  double t = 0.0, angle = 0.0, period = 0.0;
  const double dt = 0.005;
  while (period == 0.0) {
    const Vec3 k1 = rate(n), k2 = rate(n + 0.5 * dt * k1), k3 = rate(n + 0.5 * dt * k2),
               k4 = rate(n + dt * k3);
    const Vec3 next = (n + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)).normalized();
    const double step = std::atan2(n.cross(next).z(), n.dot(next));  // signed turn (clockwise < 0)
    if (angle + step <= -2.0 * kPi) period = t + dt * (-2.0 * kPi - angle) / step;
    angle += step;
    t += dt;
    n = next;
    ASSERT_LT(t, 100.0);
  }
  const double B = 1.5 * c * c / (1.5 * c * c + 8.0);
  const double re = std::sqrt((1.0 + B) / (1.0 - B));
  const double expected = 2.0 * kPi * (re + 1.0 / re) / gd;
  EXPECT_NEAR(expected, 12.726, 5e-4);  // the tabulated value
  EXPECT_NEAR(period / expected, 1.0, 1e-3) << "period " << period;
  std::printf("Jeffery period: %.6f, expected %.6f\n", period, expected);
}

TEST(FldModel, IsolatedSphereMobilityFollowsKumarHigdonFit) {
  // R_0 = 6 pi mu a (1 + 2.725 phi - 6.583 phi^2), RT0 = 8 pi mu a^3 (1 + 0.749 phi - 2.469 phi^2);
  // at phi = 0.3 the factors are 1.2250 and 1.0025 (reference §1a, 4 decimals). An isolated sphere
  // (no pairs) under a unit force and torque moves with 1/R_0 and 1/RT0.
  System s(sphere_shape(), 1, 30.0, physics(0.0, 0.0, 0.3));
  ModelSettings settings;
  settings.fit = IsotropicFit::KumarHigdon;
  ResistanceModel model(settings);
  model.configure(s, deterministic(false, false));
  model.assemble(s, NodePairList{});
  const double F[6] = {1, 0, 0, 0, 0, 1};
  double dU[6] = {0};
  model.solve(s, F, dU);
  EXPECT_NEAR(1.0 / dU[0], 1.2250, 5e-5);
  EXPECT_NEAR(1.0 / (dU[5] * 8.0 * kPi * s.physics().viscosity), 1.0025, 5e-5);
}

TEST(LubricationModel, PairStressletOfSpheresOnTheCompressionalAxis) {
  // Two force-free unit spheres at centre distance R along the compressional axis
  // d = (1,-1,0)/sqrt(2) of u = gammadot y e_x. With the strain arm L (L = R for strain_arm centre,
  // the contact distance 2a for contact), the ambient relative velocity E L d = -(gammadot L/2) d is
  // purely normal, so only the squeeze mode acts. Force balance on each sphere,
  // R_0 dU_j = -c (u + e) d with u the relative normal velocity and e = -gammadot L/2, gives
  // u = -2 c e/(R_0 + 2c) and the pair force on j F_j = -c e R_0/(R_0 + 2c) d (repulsive). The pair
  // stresslet -sym(L (x) F_j) then has xy component L^2 gammadot c R_0/(4 (R_0 + 2c)) > 0, added to
  // the two isolated-sphere stresslets 2 (20/3) pi mu a^3 gammadot/2.
  const double gd = 1.3, R = 2.01;
  for (const StrainArm arm : {StrainArm::Centre, StrainArm::Contact}) {
    SCOPED_TRACE(arm == StrainArm::Centre ? "centre" : "contact");
    System s(sphere_shape(), 2, 30.0, physics(0.0, gd, 0.0));
    const Vec3 d = Vec3(1, -1, 0).normalized();
    s.positions()[0] = Vec3(15, 15, 15);
    s.positions()[1] = s.positions()[0] + R * d;
    s.update_nodes();
    ModelSettings settings;
    settings.lub.strain_arm = arm;
    ResistanceModel model(settings);
    model.configure(s, deterministic(true, true));
    const NodePairList pairs = brute_force_pairs(s, model.pair_range(s));
    model.assemble(s, pairs);
    std::vector<double> F(12, 0.0), dU(12, 0.0);
    model.solve(s, F.data(), dU.data());
    const double mu = s.physics().viscosity, R0 = 6 * kPi * mu, L = arm == StrainArm::Centre ? R : 2.0;
    const double c = LubricationPair::coefficients(1.0, 1.0, R, mu, LubricationOptions{}).squeeze;
    const double expected = 2 * 20.0 / 3.0 * kPi * mu * 0.5 * gd + L * L * gd * c * R0 / (4 * (R0 + 2 * c));
    const Eigen::Matrix3d S = model.stresslet_sum(s, pairs, dU.data());
    // The CG tolerance 1e-6 bounds the relative error of dU and hence of the pair force.
    EXPECT_NEAR(S(0, 1), expected, 1e-5 * expected);
    EXPECT_NEAR(S(1, 0), S(0, 1), 1e-15 * expected);
    // The relative normal velocity: the squeeze resists the approach L gammadot/2 at the arm.
    const Vec3 rel = Eigen::Map<const Vec3>(dU.data() + 6) - Eigen::Map<const Vec3>(dU.data());
    EXPECT_NEAR(rel.dot(d), 2 * c * (gd * L / 2) / (R0 + 2 * c), 1e-5 * gd);
  }
}

namespace {

// Two force- and torque-free unit-node dicolloids (c = 1) in u = gammadot y e_x (kT = 0): node a
// of body 0 and node b of body 1 at gap xi along d. Returns the nodes' normal approach speed
// -d.(V_b - V_a) (lab velocities, V = U_inf(X) + dU + (Omega_inf + dW) x offset), or NaN when
// another node pair of the two bodies is as close (the pair would then not be "the" contact).
double node_approach_speed(const Quat& q0, const Quat& q1, int a, int b, const Vec3& d, double xi,
                           StrainArm arm) {
  System s(dicolloid_shape(1.0), 2, 30.0, physics(0.0, 1.0, 0.0));
  s.positions()[0] = Vec3(15, 15, 15);
  s.orientations()[0] = q0;
  s.orientations()[1] = q1;
  s.update_nodes();
  const Vec3 node_a = s.node_positions()[a];
  const Vec3 node_b = node_a + (2.0 + xi) * d;
  s.positions()[1] = node_b - q1 * dicolloid_shape(1.0)->nodes()[b].position;
  s.update_nodes();
  EXPECT_NEAR((s.node_positions()[2 + b] - node_a).norm(), 2.0 + xi, 1e-12);
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q)
      if ((p != a || q != b) && (s.node_positions()[2 + q] - s.node_positions()[p]).norm() <= 2.0 + xi)
        return std::nan("");
  ModelSettings settings;
  settings.lub.strain_arm = arm;
  settings.tolerance = 1e-14;
  ResistanceModel model(settings);
  model.configure(s, deterministic(true, false));
  model.assemble(s, brute_force_pairs(s, model.pair_range(s)));
  std::vector<double> F(12, 0.0), dU(12, 0.0);
  model.solve(s, F.data(), dU.data());
  auto velocity = [&](int body, const Vec3& node) {
    const Vec3 X = s.positions()[body];
    const Vec3 U = s.flow_velocity(X) + Eigen::Map<const Vec3>(dU.data() + 6 * body);
    const Vec3 W = s.flow_vorticity() + Eigen::Map<const Vec3>(dU.data() + 6 * body + 3);
    return Vec3(U + W.cross(node - X));
  };
  return -(velocity(1, node_b) - velocity(0, node_a)).dot(d);
}

}  // namespace

TEST(LubricationModel, EndToEndDumbbellsOnTheCompressionalAxisApproachAsTheSqueezeLawSays) {
  // Fused dumbbells (c = a) end to end along the compressional axis d = (1,-1,0)/sqrt(2), touching
  // node to node at gap xi: body centres R = (3 + xi) d, E.d = -(gammadot/2) d, so the ambient
  // motion is purely normal, no torque arises (every node on the line), and only the squeeze acts.
  // Per body R_0 U = -+ c m d with the mode velocity m = d.(U_1 - U_0) + d.E.L, L the strain arm
  // (centre: R; contact: R - xi d = 3 d). Hence m = e R_0/(R_0 + 2c) with e = d.E.L, and the nodes'
  // approach speed -d.(V_1 - V_0) = -(m - e) - d.E.R = -m - (gammadot/2) xi [contact] or -m [centre]:
  //   contact: 1.5 gammadot R_0/(R_0 + 2c) + gammadot xi/2,   centre: (3 + xi)(gammadot/2) R_0/(R_0 + 2c),
  // both O(xi) since c ~ 6 pi mu a/(4 xi). The CG tolerance 1e-14 (node_approach_speed) makes the
  // approach speed exact to ~1e-14 of the O(1) velocities it is the difference of (at 1e-12 the
  // single-precision IC(0) sweeps left 6.5e-13 at xi 1e-4, about twice the 1e-9 relative asserted).
  const Vec3 d = Vec3(1, -1, 0).normalized();
  const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), d);  // body z (node 1 at +c/2) along d
  const double mu = Physics{}.viscosity, R0 = 6 * kPi * mu;
  for (const StrainArm arm : {StrainArm::Centre, StrainArm::Contact})
    for (const double xi : {1e-2, 1e-3, 1e-4, 1e-5}) {
      SCOPED_TRACE(std::string(arm == StrainArm::Centre ? "centre" : "contact") + " xi " +
                   std::to_string(xi));
      const double c = LubricationPair::coefficients(1.0, 1.0, 2.0 + xi, mu, LubricationOptions{}).squeeze;
      const double expected = arm == StrainArm::Contact ? 1.5 * R0 / (R0 + 2 * c) + 0.5 * xi
                                                        : 0.5 * (3.0 + xi) * R0 / (R0 + 2 * c);
      const double v = node_approach_speed(q, q, 1, 0, d, xi, arm);
      EXPECT_NEAR(v, expected, 1e-9 * expected);
      EXPECT_LT(v, 4.0 * xi);  // O(xi): 3.5 xi (contact), 3 xi (centre) to leading order
    }
}

TEST(LubricationModel, TouchingNodesOfFreeDicolloidsStopApproachingWithEitherStrainArm) {
  // Two free fused dumbbells touching node to node (gap xi), random orientations and contact
  // directions, only configurations in which the touching pair is the closest one (else another
  // pair is the contact). The squeeze (~ 1/xi) must bring the nodes' normal approach speed to zero
  // with the gap, for either strain arm: the velocity balance of the end-to-end case above gives
  // |v| <~ (|d.E.L| R_0/(2 c) + |d.E.d| xi) ~ 3.5 xi gammadot a for arms |L| <= 3 a, and the
  // remaining modes only redistribute it (measured: at most 3.25 xi over 300 configurations).
  // Asserted: |v| <= 5 xi at xi = 1e-3, 1e-4, 1e-5, and v(1e-5)/v(1e-4) between 0.08 and 0.125:
  // linear in xi up to the logarithms of the shear and pump modes (xi ln(1/xi) would give 0.125,
  // a finite approach 1).
  // A test dropped in e7bad11 found 0.07-0.14 gammadot a here: its second body was placed with its
  // other node inside the first body (overlap 0.53 a), a pair that dominates the solve; the nan
  // return above refuses such a geometry. An arm that ignores the node offsets, (a_a + a_b) d
  // alone, gives O(gammadot a) approach and fails this test.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  for (const StrainArm arm : {StrainArm::Centre, StrainArm::Contact}) {
    SCOPED_TRACE(arm == StrainArm::Centre ? "centre" : "contact");
    int tested = 0;
    double worst = 0.0, lo = 1.0, hi = 0.0;
    while (tested < 60) {
      Quat q0(g(rng), g(rng), g(rng), g(rng)), q1(g(rng), g(rng), g(rng), g(rng));
      q0.normalize();
      q1.normalize();
      const Vec3 d = Vec3(g(rng), g(rng), g(rng)).normalized();
      const int a = int(rng() % 2), b = int(rng() % 2);
      const double v3 = node_approach_speed(q0, q1, a, b, d, 1e-3, arm);
      if (std::isnan(v3)) continue;
      const double v4 = node_approach_speed(q0, q1, a, b, d, 1e-4, arm);
      const double v5 = node_approach_speed(q0, q1, a, b, d, 1e-5, arm);
      ++tested;
      EXPECT_LE(std::abs(v3), 5e-3);
      EXPECT_LE(std::abs(v4), 5e-4);
      EXPECT_LE(std::abs(v5), 5e-5);
      worst = std::max(worst, std::abs(v4) / 1e-4);
      // v ~ xi (ratio 0.1) up to the logarithms: v ~ xi ln(1/xi) would give 0.125; O(1) gives 1.
      // Where the O(xi) coefficient nearly cancels (|v| < 0.1 xi) the higher orders decide the
      // ratio, and the bound above already holds tenfold.
      if (std::abs(v4) < 1e-5) continue;
      EXPECT_GT(v5 / v4, 0.08) << "v(1e-4) " << v4 << ", v(1e-5) " << v5;
      EXPECT_LT(v5 / v4, 0.125) << "v(1e-4) " << v4 << ", v(1e-5) " << v5;
      lo = std::min(lo, v5 / v4);
      hi = std::max(hi, v5 / v4);
    }
    std::printf(
        "%s arm, 60 configurations: max |approach| / (xi gammadot a) at xi 1e-4 %.3f; "
        "v(1e-5)/v(1e-4) from %.4f to %.4f where |v(1e-4)| > 0.1 xi\n",
        arm == StrainArm::Centre ? "centre" : "contact", worst, lo, hi);
  }
}
