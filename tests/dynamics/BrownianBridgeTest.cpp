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

#include "dynamics/BrownianBridge.hpp"
#include "fldsim/random.hpp"

namespace fldsim {
namespace {

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

}  // namespace
}  // namespace fldsim
