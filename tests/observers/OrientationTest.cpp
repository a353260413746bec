// Orientation statistics: isotropic directors (analytic variances), perfectly aligned ones, and
// hand-made directors that pin the sign conventions of phi.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "DirectorAngles.hpp"
#include "FakeSink.hpp"
#include "OrientationObserver.hpp"
#include "OrientationStatistics.hpp"
#include "StatCheck.hpp"

using namespace fldsim;
using namespace fldsim::observers;

namespace {

constexpr double kPi = std::numbers::pi;

std::vector<Vec3> isotropic_directors(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> d(n);
  for (auto& v : d) v = Vec3(g(rng), g(rng), g(rng)).normalized();  // Gaussian vectors are isotropic
  return d;
}

// Two touching nodes on the body z axis: director (0, 0, 1).
class RodShape : public Shape {
 public:
  explicit RodShape(int nodes) {
    for (int k = 0; k < nodes; ++k) nodes_.push_back({Vec3(0, 0, nodes == 1 ? 0.0 : (k - 0.5)), 1.0});
  }
  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override { return 4.0 / 3.0 * kPi * nodes_.size(); }

 private:
  std::vector<Node> nodes_;
};

}  // namespace

TEST(DirectorAngles, SignConventionsAndFolding) {
  const double tol = 1e-12;
  // Extensional quadrant: n along (1, 1, 0) -> phi = +pi/4; compressional (-1, 1, 0) -> -pi/4.
  EXPECT_NEAR(director_angles(Vec3(1, 1, 0)).phi, kPi / 4, tol);
  EXPECT_NEAR(director_angles(Vec3(-1, 1, 0)).phi, -kPi / 4, tol);
  // Flow axis pi/2, gradient axis 0, vorticity axis theta = 0.
  EXPECT_NEAR(director_angles(Vec3(1, 0, 0)).phi, kPi / 2, tol);
  EXPECT_NEAR(director_angles(Vec3(0, 1, 0)).phi, 0.0, tol);
  EXPECT_NEAR(director_angles(Vec3(0, 0, 1)).theta, 0.0, tol);
  EXPECT_NEAR(director_angles(Vec3(1, 0, 0)).theta, kPi / 2, tol);
  // n and -n are the same body.
  for (const Vec3& n :
       {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0.5), Vec3(0.3, -0.2, -0.9), Vec3(0, -1, 0)}) {
    const auto a = director_angles(n), b = director_angles(-n);
    EXPECT_NEAR(a.theta, b.theta, tol);
    EXPECT_NEAR(a.phi, b.phi, tol);
  }
  // theta from |n_z|: 45 degrees out of the x-y plane.
  EXPECT_NEAR(director_angles(Vec3(1, 1, std::sqrt(2.0))).theta, kPi / 4, tol);
}

TEST(OrientationStatistics, IsotropicDirectorsGiveIsotropicValues) {
  const std::size_t n = 200000;
  OrientationStatistics st(18, 36);
  st.add_sample(isotropic_directors(n, 2024));
  const double nn = static_cast<double>(n);

  // Histograms: count in bin b is binomial(n, p_b), so SE(P_b) = sqrt((1 - p_b) / (n p_b)).
  auto check = [&](const std::vector<double>& p, auto weight) {
    std::vector<double> one(p.size(), 1.0), se(p.size());
    for (std::size_t b = 0; b < p.size(); ++b) se[b] = std::sqrt((1.0 - weight(b)) / (nn * weight(b)));
    const auto c = test::check_bins(p, one, se);
    EXPECT_LT(c.max_abs_z, test::bonferroni_bound(c.bins));
    EXPECT_NEAR(c.chi2, static_cast<double>(c.bins), 3.0 * std::sqrt(2.0 * c.bins));
  };
  check(st.p_theta(), [&](std::size_t b) { return st.theta_bin_weight(static_cast<int>(b)); });
  check(st.p_phi(), [&](std::size_t b) { return st.phi_bin_weight(static_cast<int>(b)); });

  // theta_m = 1 rad with Var(theta) = int (theta - 1)^2 sin(theta) = (pi - 2) - 1 = pi - 3.
  EXPECT_NEAR(st.theta_m().mean() - 1.0, 0.0, 3.0 * std::sqrt((kPi - 3.0) / nn));
  // |phi| uniform on [0, pi/2]: mean pi/4, variance (pi/2)^2 / 12.
  EXPECT_NEAR(st.phi_m().mean() - kPi / 4, 0.0, 3.0 * std::sqrt(kPi * kPi / 48.0 / nn));
  // S_ii = 3/2 n_i^2 - 1/2: Var(n_i^2) = <n_i^4> - 1/9 = 1/5 - 1/9 = 4/45, so Var(S) = 9/4 * 4/45 = 1/5.
  // Off-diagonal Q_ij = 3/2 n_i n_j: Var = 9/4 <n_i^2 n_j^2> = 9/4 * 1/15 = 3/20.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double var = i == j ? 0.2 : 0.15;
      EXPECT_NEAR(st.q(i, j).mean(), 0.0, 3.0 * std::sqrt(var / nn)) << i << j;
    }
  // The order tensor is traceless by construction (|n| = 1).
  EXPECT_NEAR(st.q_mean().trace(), 0.0, 1e-12);
  // Integrating the piecewise-constant histogram, sum_b P_b int_b theta sin(theta) dtheta, gives
  // each director the sin-weighted mean theta of its bin instead of its own theta: the result
  // differs from the sample mean theta_m by less than one bin width.
  const auto p = st.p_theta();
  double integral = 0.0;
  for (int b = 0; b < st.theta_bins(); ++b) {
    auto f = [](double t) { return std::sin(t) - t * std::cos(t); };  // antiderivative of t sin t
    integral += p[b] * (f(st.theta_edge(b + 1)) - f(st.theta_edge(b)));
  }
  EXPECT_LT(std::abs(integral - st.theta_m().mean()), st.theta_edge(1));
}

TEST(OrientationStatistics, AlignedWithFlowAxis) {
  OrientationStatistics st(18, 36);
  std::vector<Vec3> d(100, Vec3(1, 0, 0));
  for (std::size_t i = 0; i < d.size(); i += 2) d[i] = -d[i];  // half point the other way
  st.add_sample(d);
  const double tol = 1e-12;
  EXPECT_NEAR(st.q(0, 0).mean(), 1.0, tol);
  EXPECT_NEAR(st.q(1, 1).mean(), -0.5, tol);
  EXPECT_NEAR(st.q(2, 2).mean(), -0.5, tol);
  EXPECT_NEAR(st.phi_m().mean(), kPi / 2, tol);
  EXPECT_NEAR(st.theta_m().mean(), kPi / 2, tol);
  // Every director is in the last phi bin (flow axis) and last theta bin (theta = pi/2).
  EXPECT_NEAR(st.p_phi().back(), 1.0 / st.phi_bin_weight(0), tol);
  EXPECT_NEAR(st.p_theta().back(), 1.0 / st.theta_bin_weight(st.theta_bins() - 1), 1e-9);
}

TEST(OrientationStatistics, ExtensionalAndCompressionalQuadrants) {
  OrientationStatistics ext(18, 36), comp(18, 36);
  const Vec3 e = Vec3(1, 1, 0).normalized(), c = Vec3(-1, 1, 0).normalized();
  ext.add_sample({e, -e, e});
  comp.add_sample({c, -c});
  // phi_m is the mean |phi| = pi/4 for both; the sign shows in the histogram and in Q_xy.
  EXPECT_NEAR(ext.phi_m().mean(), kPi / 4, 1e-12);
  EXPECT_NEAR(comp.phi_m().mean(), kPi / 4, 1e-12);
  // Q_xy = 3/2 n_x n_y = +3/4 (extensional) and -3/4 (compressional).
  EXPECT_NEAR(ext.q(0, 1).mean(), 0.75, 1e-12);
  EXPECT_NEAR(comp.q(0, 1).mean(), -0.75, 1e-12);
  // phi = +pi/4 lies in bin 27 of 36 over [-pi/2, pi/2] (edges every 5 degrees: 45 deg = edge 27,
  // so bin 27 [45, 50) deg); -pi/4 lies in bin 9 ([-45, -40) deg).
  const auto pe = ext.p_phi(), pc = comp.p_phi();
  EXPECT_GT(pe[27] + pe[26], 0.0);
  EXPECT_DOUBLE_EQ(pe[9] + pe[8], 0.0);
  EXPECT_GT(pc[9] + pc[8], 0.0);
  EXPECT_DOUBLE_EQ(pc[27] + pc[26], 0.0);
}

TEST(OrientationObserver, WritesResultsThroughTheSink) {
  // 50 rods rotated so their director lies along x: S_xx = 1, delta_phi_m = pi/4, delta_theta_m = pi/2 - 1.
  auto shape = std::make_shared<RodShape>(2);
  System sys(shape, 50, 20.0, Physics{});
  for (auto& q : sys.orientations()) q = Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitX());
  RunInfo run;
  run.total_steps = 10;
  run.dt = 0.01;
  NodePairList pairs;
  OrientationObserver obs({18, 36});
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  for (int s = 0; s < 4; ++s) {
    sys.set_step(s);
    StepView view{sys, pairs, run, nullptr, nullptr, nullptr, {}, 0.0};
    obs.sample(view, sink);
  }
  obs.finish(run, sink);
  EXPECT_NEAR(sink.scalar("results/orientation/S_xx").value, 1.0, 1e-12);
  EXPECT_NEAR(sink.scalar("results/orientation/S_zz").value, -0.5, 1e-12);
  EXPECT_NEAR(sink.scalar("results/orientation/delta_phi_m").value, kPi / 4, 1e-12);
  EXPECT_NEAR(sink.scalar("results/orientation/delta_theta_m").value, kPi / 2 - 1.0, 1e-12);
  EXPECT_EQ(sink.series.at("timeseries/orientation/theta_m").steps.size(), 4u);
  // Largest eigenvalue 1 with eigenvector +-x.
  const auto& ev = sink.arrays.at("results/orientation/order_eigenvalues").data;
  const auto& vec = sink.arrays.at("results/orientation/order_eigenvectors").data;
  EXPECT_NEAR(ev[2], 1.0, 1e-12);
  EXPECT_NEAR(std::abs(vec[6]), 1.0, 1e-12);

  // A sphere has no director: the observer skips and writes no result.
  System spheres(std::make_shared<RodShape>(1), 10, 20.0, Physics{});
  OrientationObserver skip({18, 36});
  test::FakeSink sink2;
  skip.begin(spheres, run, sink2);
  StepView view{spheres, pairs, run, nullptr, nullptr, nullptr, {}, 0.0};
  skip.sample(view, sink2);
  skip.finish(run, sink2);
  EXPECT_TRUE(skip.skipped());
  EXPECT_TRUE(sink2.scalars.empty());
}
