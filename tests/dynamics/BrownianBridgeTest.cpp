// The Brownian path behind rejected steps (dynamics/BrownianBridge.hpp):
//  - a whole base interval is the fixed-step draw (one term, sqrt(H), stage 0);
//  - the two halves of any dyadic node add up to the node (one path, whatever is refined);
//  - the pieces of a non-uniform dyadic partition are independent N(0, h): sample variances
//    within 3.3 SE of h and correlations within 3.3/sqrt(n). Bonferroni over the 4 variances and
//    6 correlations (10 comparisons at 3.3 sigma, two-sided 0.1 % each) keeps the family-wise
//    false-alarm rate below 1 %. The same check applied to a broken bridge (halves P/2 without
//    the bridge's own noise) must fail, so the check can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "Scene.hpp"
#include "dynamics/BrownianBridge.hpp"
#include "fldsim/random.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"

namespace fldsim {
namespace {
using testing::make;

// W of `iv` for one Wiener component (object, index) of the path with `seed`.
double increment(const BrownianBridge& bridge, std::uint64_t seed, const NoiseInterval& iv,
                 std::uint64_t object) {
  BrownianBridge::Terms terms;
  const int n = bridge.terms(iv, terms);
  double w = 0.0;
  for (int j = 0; j < n; ++j) {
    const RandomStream stream(seed, RandomPurpose::BodyNoise, iv.base, terms[std::size_t(j)].stage);
    w += terms[std::size_t(j)].coefficient * stream.normal2(object, 0)[0];
  }
  return w;
}

TEST(BrownianBridge, WholeIntervalIsTheFixedStepDraw) {
  BrownianBridge bridge;
  BrownianBridge::Terms t;
  const NoiseInterval iv{17, 2.5e-3, 0, 0, 0};
  ASSERT_EQ(bridge.terms(iv, t), 1);
  EXPECT_EQ(t[0].stage, 0u);
  EXPECT_EQ(t[0].coefficient, std::sqrt(2.5e-3));
}

TEST(BrownianBridge, HalvesAddUpToTheirParent) {
  BrownianBridge bridge;
  const double H = 0.37;
  for (int d = 0; d < 12; ++d)
    for (std::uint64_t i : {std::uint64_t(0), (std::uint64_t(1) << d) - 1, (std::uint64_t(5) << d) / 7}) {
      const NoiseInterval parent{3, H, d, i, 0};
      const NoiseInterval left{3, H, d + 1, 2 * i, 0}, right{3, H, d + 1, 2 * i + 1, 0};
      for (std::uint64_t object : {0ull, 41ull, (7ull << 32) | 9ull}) {
        const double p = increment(bridge, 11, parent, object);
        const double sum = increment(bridge, 11, left, object) + increment(bridge, 11, right, object);
        EXPECT_NEAR(sum, p, 1e-13 * (1.0 + std::fabs(p))) << "depth " << d << " index " << i;
      }
    }
}

// Pieces [0, 1/2), [1/2, 5/8), [5/8, 3/4), [3/4, 1) of a base interval of length H.
struct PartitionCheck {
  double worst_variance_z = 0.0, worst_correlation_z = 0.0;
};

template <class Increment>
PartitionCheck check_partition(Increment w, double H, int samples) {
  const std::vector<NoiseInterval> pieces{{0, H, 1, 0, 0}, {0, H, 3, 4, 0}, {0, H, 3, 5, 0}, {0, H, 2, 3, 0}};
  const std::size_t m = pieces.size();
  std::vector<double> sum2(m * m, 0.0);
  std::vector<double> x(m);
  for (int s = 0; s < samples; ++s) {
    for (std::size_t a = 0; a < m; ++a) {
      NoiseInterval iv = pieces[a];
      iv.base = std::uint64_t(s % 97);
      x[a] = w(iv, std::uint64_t(s / 97)) / std::sqrt(iv.duration());  // N(0, 1) if right
    }
    for (std::size_t a = 0; a < m; ++a)
      for (std::size_t b = 0; b < m; ++b) sum2[a * m + b] += x[a] * x[b];
  }
  PartitionCheck c;
  const double n = double(samples);
  for (std::size_t a = 0; a < m; ++a) {
    // Var of a sample variance of N(0,1) data: 2/n.
    c.worst_variance_z =
        std::max(c.worst_variance_z, std::fabs(sum2[a * m + a] / n - 1.0) / std::sqrt(2.0 / n));
    for (std::size_t b = a + 1; b < m; ++b)
      c.worst_correlation_z = std::max(c.worst_correlation_z, std::fabs(sum2[a * m + b] / n) * std::sqrt(n));
  }
  return c;
}

TEST(BrownianBridge, PiecesOfAPartitionAreIndependentWithVarianceTheirLength) {
  const double H = 1e-3;
  const int samples = 40000;
  const BrownianBridge bridge;
  const auto good = check_partition(
      [&](const NoiseInterval& iv, std::uint64_t object) { return increment(bridge, 5, iv, object); }, H,
      samples);
  EXPECT_LT(good.worst_variance_z, 3.3);
  EXPECT_LT(good.worst_correlation_z, 3.3);

  // Broken bridge: each half is P/2 (the bridge's own noise left out). Same check, must fail.
  auto broken = [&](const NoiseInterval& iv, std::uint64_t object) {
    const RandomStream root(5, RandomPurpose::BodyNoise, iv.base, 0);
    return std::sqrt(iv.length) * root.normal2(object, 0)[0] * std::ldexp(1.0, -iv.depth);
  };
  const auto bad = check_partition(broken, H, samples);
  EXPECT_GT(std::max(bad.worst_variance_z, bad.worst_correlation_z), 3.3);
}

TEST(BrownianBridge, RedrawGivesEveryAttemptFreshNumbers) {
  const BrownianBridge redraw(RejectedNoise::Redraw);
  BrownianBridge::Terms t;
  ASSERT_EQ(redraw.terms(NoiseInterval{4, 1.0, 0, 0, 0}, t), 1);
  EXPECT_EQ(t[0].stage, 0u);  // the first attempt is the fixed-step draw
  ASSERT_EQ(redraw.terms(NoiseInterval{4, 1.0, 1, 0, 1}, t), 1);
  EXPECT_NE(t[0].stage, 0u);
  EXPECT_GE(t[0].stage, 0x80000000u);  // never a stage of the bridge
  EXPECT_DOUBLE_EQ(t[0].coefficient, std::sqrt(0.5));
}

// A stream standing for a NormalCombination draws sum_j c_j (the normals of stage j), for either
// purpose, and a one-term combination (stage 0, coefficient 1) is the plain stream bit for bit.
TEST(RandomStreamCombination, IsTheSumOfItsStagesNormals) {
  NormalCombination c;
  c.count = 4;
  c.stage = {0u, 1u, 3u, 6u};
  c.coefficient = {0.125, -0.3, 0.7, 0.05};
  const RandomStream base(5, RandomPurpose::BodyNoise, 123);
  for (RandomPurpose purpose : {RandomPurpose::BodyNoise, RandomPurpose::PairNoise}) {
    const RandomStream combined = base.combined(c).for_purpose(purpose);
    for (std::uint64_t object : {0ull, 17ull, (3ull << 32) | 4ull})
      for (std::uint32_t index = 0; index < 8; ++index) {
        std::array<double, 2> sum{0.0, 0.0};
        for (int j = 0; j < c.count; ++j) {
          const auto g = RandomStream(5, purpose, 123, c.stage[std::size_t(j)]).normal2(object, index);
          sum[0] += c.coefficient[std::size_t(j)] * g[0];
          sum[1] += c.coefficient[std::size_t(j)] * g[1];
        }
        const auto got = combined.normal2(object, index);
        EXPECT_EQ(got[0], sum[0]);
        EXPECT_EQ(got[1], sum[1]);
      }
  }
  NormalCombination one;
  one.count = 1;
  one.stage[0] = 0u;
  one.coefficient[0] = 1.0;
  double plain[6], through[6];
  base.normals(9, plain, 6);
  base.combined(one).normals(9, through, 6);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(through[k], plain[k]);
}

// draw_brownian at a dyadic piece of depth d calls the hydro model once with the combined stream
// (since 7 December 2026); it must give the F_B of the old d + 1 calls, one per stage, summed with
// the bridge's coefficients (the model's draw is linear in its normals): FLD on fused dumbbells,
// the pair noise of their node pairs and the R_0 noise of the bodies. Shown failing once with the
// combination's coefficients not divided by sqrt(h) (relative error 1 - sqrt(h)).
TEST(BrownianBridge, OneCombinedDrawEqualsTheSumOverStages) {
  Physics ph;
  ph.kT = 1.0;
  ph.volume_fraction = 0.3;
  auto shape = make<Shape>("shape", "dicolloid", "{a: 1, b: 1, c: 1}");
  const std::size_t n = 64;
  testing::Scene scene(shape, n, std::cbrt(double(n) * shape->volume() / 0.3), ph);
  geometry::MonteCarloOptions opt;
  opt.seed = 3;
  geometry::initialise_monte_carlo(*scene.system, opt);
  scene.finish(make<HydroModel>("hydro", "fld"), {}, HydroRequest{true, false, false});
  scene.evaluator->prepare(*scene.system, false);
  ASSERT_GT(scene.evaluator->pairs().pairs().size(), 0u);

  const BrownianBridge bridge;
  const std::uint64_t seed = 77;
  for (const NoiseInterval iv : {NoiseInterval{12, 1e-3, 1, 1, 0}, NoiseInterval{12, 1e-3, 4, 9, 0}}) {
    scene.evaluator->draw_brownian(*scene.system, seed, bridge, iv);
    const std::vector<double> got(scene.evaluator->brownian_force(),
                                  scene.evaluator->brownian_force() + 6 * n);
    BrownianBridge::Terms terms;
    const int m = bridge.terms(iv, terms);
    std::vector<double> expected(6 * n, 0.0);
    double scale = 0.0;
    for (int j = 0; j < m; ++j) {
      scene.evaluator->draw_brownian(
          *scene.system, RandomStream(seed, RandomPurpose::BodyNoise, iv.base, terms[std::size_t(j)].stage),
          1.0);
      const double* f = scene.evaluator->brownian_force();
      for (std::size_t k = 0; k < 6 * n; ++k)
        expected[k] += terms[std::size_t(j)].coefficient / iv.duration() * f[k];
    }
    for (double v : expected) scale = std::max(scale, std::fabs(v));
    for (std::size_t k = 0; k < 6 * n; ++k)
      EXPECT_NEAR(got[k], expected[k], 1e-12 * scale) << "depth " << iv.depth << ", component " << k;
  }
}

}  // namespace
}  // namespace fldsim
