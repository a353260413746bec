// Shapes: volumes and centroids against closed forms, the reference table and independent
// numerical integration.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "ClusterShape.hpp"
#include "DicolloidShape.hpp"
#include "SphereShape.hpp"
#include "fldsim/error.hpp"

using namespace fldsim;
using namespace fldsim::shapes;

namespace {

constexpr double pi = std::numbers::pi;

// Volume and z centroid of a union of balls centred on the z axis, by composite Simpson in z of
// the cross-section area pi * max_k(r_k^2 - (z - z_k)^2). The area is piecewise quadratic with
// kinks only where the sphere surfaces cross, so with 2e5 panels the error is below 1e-9.
struct AxialResult {
  double volume, centroid;
};
AxialResult axial_union(const std::vector<std::pair<double, double>>& z_and_r) {
  double lo = 1e300, hi = -1e300;
  for (auto [z, r] : z_and_r) {
    lo = std::min(lo, z - r);
    hi = std::max(hi, z + r);
  }
  auto area = [&](double z) {
    double rho2 = 0.0;
    for (auto [zk, r] : z_and_r) rho2 = std::max(rho2, r * r - (z - zk) * (z - zk));
    return pi * rho2;
  };
  const int n = 200000;  // even
  const double h = (hi - lo) / n;
  double v = 0.0, m = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double z = lo + k * h, w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    v += w * area(z);
    m += w * z * area(z);
  }
  return {v * h / 3.0, m / v};
}

}  // namespace

TEST(SphereShape, VolumeAndNodes) {
  const SphereShape s(1.5);
  EXPECT_NEAR(s.volume(), 4.0 / 3.0 * pi * 1.5 * 1.5 * 1.5, 1e-12);
  ASSERT_EQ(s.nodes().size(), 1u);
  EXPECT_FALSE(s.anisotropic());
  EXPECT_EQ(s.director(), Vec3::UnitZ());
  EXPECT_THROW(SphereShape(0.0), Error);
}

// physics-reference-values.md §6: V/a^3 = 4.815014 (c/a = 0.2) and 7.068583 (c/a = 1), given to
// 7 significant figures, so the tolerance is half a unit of the last digit.
TEST(DicolloidShape, VolumesMatchReferenceTable) {
  EXPECT_NEAR(DicolloidShape(1, 1, 0.2).volume(), 4.815014, 5e-7);
  EXPECT_NEAR(DicolloidShape(1, 1, 1.0).volume(), 7.068583, 5e-7);
  // Closed form for equal radii (same section): V = (4/3) pi a^3 (1 + 3c/4a - c^3/16a^3).
  for (double c : {0.05, 0.2, 0.7, 1.0, 1.6, 1.99}) {
    const double v = 4.0 / 3.0 * pi * (1.0 + 0.75 * c - c * c * c / 16.0);
    EXPECT_NEAR(DicolloidShape(1, 1, c).volume(), v, 1e-12 * v) << "c = " << c;
  }
}

// Same table: L = (N V / phi)^(1/3) = 25.2247 a for N = 1000, c/a = 0.2, phi = 0.3 (4 decimals).
TEST(DicolloidShape, BoxEdgeMatchesReferenceTable) {
  const double L = std::cbrt(1000.0 * DicolloidShape(1, 1, 0.2).volume() / 0.3);
  EXPECT_NEAR(L, 25.2247, 5e-5);
  EXPECT_NEAR(std::cbrt(1000.0 * DicolloidShape(1, 1, 1.0).volume() / 0.5), 24.1799, 5e-5);
}

TEST(DicolloidShape, SymmetricNodesAreCentred) {
  const DicolloidShape d(1, 1, 1.0);
  EXPECT_NEAR(d.nodes()[0].position.z(), -0.5, 1e-14);
  EXPECT_NEAR(d.nodes()[1].position.z(), 0.5, 1e-14);
  EXPECT_TRUE(d.anisotropic());
  EXPECT_NEAR(d.bounding_radius(), 1.5, 1e-14);
}

// Unequal radii: the centroid of the union placed by the lens formulas must be the origin when
// checked by direct numerical integration of the actual union, and the volume must agree.
TEST(DicolloidShape, UnequalCentroidMatchesNumericalIntegration) {
  for (auto [a, b, c] : {std::array<double, 3>{1.0, 0.6, 1.1}, {1.0, 0.5, 0.6}, {0.7, 1.3, 1.5}}) {
    const DicolloidShape d(a, b, c);
    const double z0 = d.nodes()[0].position.z(), z1 = d.nodes()[1].position.z();
    EXPECT_NEAR(z1 - z0, c, 1e-14);
    const AxialResult num = axial_union({{z0, a}, {z1, b}});
    EXPECT_NEAR(d.volume(), num.volume, 1e-9) << a << " " << b << " " << c;
    EXPECT_NEAR(num.centroid, 0.0, 1e-9) << a << " " << b << " " << c;
    // Node 0 (the larger sphere here or not) sits on the side of the director's tail.
    EXPECT_LT(z0, z1);
  }
}

TEST(DicolloidShape, RejectsInvalidGeometry) {
  EXPECT_THROW(DicolloidShape(1, 1, 2.0), Error);    // c = a + b: not fused
  EXPECT_THROW(DicolloidShape(1, 0.5, 0.5), Error);  // c = |a - b|: sphere inside the other
  EXPECT_THROW(DicolloidShape(1, 0.5, 0.2), Error);
  EXPECT_NO_THROW(DicolloidShape(1, 1, 0.0));  // degenerate: a sphere
  EXPECT_NEAR(DicolloidShape(1, 1, 0.0).volume(), 4.0 / 3.0 * pi, 1e-12);
}

TEST(ClusterShape, TwoSpheresEqualTheDicolloid) {
  const ClusterShape cl({{Vec3(0.3, -0.2, 0.1), 1.0}, {Vec3(0.3, -0.2, 0.1) + Vec3(0.6, 0.0, 0.8), 1.0}});
  EXPECT_TRUE(cl.geometry().exact);
  EXPECT_NEAR(cl.volume(), DicolloidShape(1, 1, 1.0).volume(), 1e-12);
  EXPECT_NEAR(cl.director().dot(Vec3(0.6, 0.0, 0.8)), 1.0, 1e-12);
  EXPECT_NEAR((cl.nodes()[0].position + cl.nodes()[1].position).norm(), 0.0, 1e-12);
}

// A straight chain with a triple overlap takes the numerical route; its exact volume and
// centroid come from the axial integral, and the error must lie within the reported bound.
TEST(ClusterShape, TripleOverlapUsesNumericalIntegrationWithinItsBound) {
  const std::vector<Ball> balls{{Vec3(0, 0, 0), 1.0}, {Vec3(0, 0, 0.7), 0.8}, {Vec3(0, 0, 1.3), 1.0}};
  const ClusterShape cl(balls);
  EXPECT_FALSE(cl.geometry().exact);
  const AxialResult ref = axial_union({{0.0, 1.0}, {0.7, 0.8}, {1.3, 1.0}});
  EXPECT_LE(std::abs(cl.volume() - ref.volume), cl.geometry().error_bound);
  EXPECT_LT(cl.geometry().error_bound, 1e-3 * ref.volume);
  // Nodes were shifted by the centroid: node 0 is at -z_c.
  EXPECT_NEAR(-cl.nodes()[0].position.z(), ref.centroid, 1e-3);
  EXPECT_NEAR(std::abs(cl.director().z()), 1.0, 1e-12);
}

// A triangle of pairwise-overlapping spheres whose three lenses do not meet is exact by
// inclusion-exclusion; the numerical integration must agree within its error bound.
TEST(ClusterShape, ExactPairwiseAgreesWithNumericalIntegration) {
  const double s = 1.9;  // side: spheres of radius 1 overlap pairwise; the triangle's centre is
                         // s/sqrt(3) = 1.097 > 1 from each centre, so no triple point exists
  const std::vector<Ball> balls{
      {Vec3(0, 0, 0), 1.0}, {Vec3(s, 0, 0), 1.0}, {Vec3(s / 2, s * std::sqrt(3.0) / 2, 0), 1.0}};
  const VolumeAndCentroid exact = union_volume_centroid({balls[0], balls[1]});
  EXPECT_TRUE(exact.exact);
  // Force the pairwise route by checking the formulas directly: V = 3 V_ball - 3 V_lens(s).
  const double v_pairwise = 3.0 * 4.0 / 3.0 * pi - 3.0 * lens_volume(1.0, 1.0, s);
  const VolumeAndCentroid num = integrate_union(balls);
  EXPECT_LE(std::abs(num.volume - v_pairwise), num.error_bound + 1e-12);
  EXPECT_NEAR(num.centroid.x(), s / 2, 1e-4);
  EXPECT_NEAR(num.centroid.y(), s / (2 * std::sqrt(3.0)), 1e-4);
}

TEST(ClusterShape, GivenDirectorIsNormalised) {
  const ClusterShape cl({{Vec3(0, 0, 0), 1.0}, {Vec3(1, 0, 0), 1.0}}, Vec3(0, 2, 0));
  EXPECT_NEAR((cl.director() - Vec3::UnitY()).norm(), 0.0, 1e-15);
}
