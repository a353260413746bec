// The counter-based normals (fldsim/random.hpp, RandomStream::normal2, Marsaglia's polar method):
//  - a pair is a pure function of (seed, purpose, step, stage, object, index), and normals()
//    fills from the same pairs;
//  - 2^20 normals (2^19 pairs over many pair-like objects and indices) have the standard normal
//    distribution: mean, variance, fourth moment (3), the correlation of a pair's two values, the
//    fraction beyond |z| = 3 (2 (1 - Phi(3)) = 0.0026998), each within 3.3 standard errors, and
//    a chi-square over 50 equiprobable bins of Phi below the 0.1 % quantile of chi-square with 49
//    degrees of freedom (85.35, Wilson-Hilferty). Six comparisons at 0.1 % each: family-wise false
//    alarms below 1 %. The seeds are fixed, so the test is deterministic; the tolerances say how
//    unlikely a pass of a wrong sampler of this size would be.
//  - The same check applied to broken samplers must fail, so the check can fail: a polar method
//    that keeps the points outside the unit disc (pulled onto its rim instead of redrawn), and a
//    Box-Muller with one uniform for both the radius and the angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "fldsim/random.hpp"

namespace fldsim {
namespace {

using PairSampler = std::function<std::array<double, 2>(std::uint64_t object, std::uint32_t index)>;

struct NormalCheck {
  int failures = 0;
  std::string report;
};

NormalCheck check_standard_normal(const PairSampler& pair) {
  constexpr int kObjects = 4096, kIndices = 128, kBins = 50;
  const double n = 2.0 * kObjects * kIndices;
  double sum = 0, sum2 = 0, sum4 = 0, cross = 0, beyond3 = 0;
  std::vector<double> bins(kBins, 0.0);
  for (std::uint64_t o = 0; o < kObjects; ++o) {
    for (std::uint32_t i = 0; i < kIndices; ++i) {
      const auto g = pair((o << 32) | (o * 7 + 1), i);  // pair-like object ids (body_i << 32 | body_j)
      cross += g[0] * g[1];
      for (const double z : g) {
        sum += z;
        sum2 += z * z;
        sum4 += z * z * z * z;
        beyond3 += std::abs(z) > 3.0 ? 1.0 : 0.0;
        const double phi = 0.5 * std::erfc(-z / std::sqrt(2.0));
        bins[std::size_t(std::min(kBins - 1, int(phi * kBins)))] += 1.0;
      }
    }
  }
  NormalCheck c;
  auto expect_within = [&](const char* what, double value, double expected, double se) {
    const double z = (value - expected) / se;
    c.report += std::string(what) + " " + std::to_string(value) + " (z " + std::to_string(z) + "); ";
    if (std::abs(z) > 3.3) ++c.failures;
  };
  const double pairs = n / 2.0;
  expect_within("mean", sum / n, 0.0, 1.0 / std::sqrt(n));
  expect_within("variance", sum2 / n, 1.0, std::sqrt(2.0 / n));
  expect_within("fourth moment", sum4 / n, 3.0, std::sqrt((105.0 - 9.0) / n));
  expect_within("pair correlation", cross / pairs, 0.0, 1.0 / std::sqrt(pairs));
  const double p3 = std::erfc(3.0 / std::sqrt(2.0));  // 2 (1 - Phi(3))
  expect_within("P(|z| > 3)", beyond3 / n, p3, std::sqrt(p3 * (1.0 - p3) / n));
  double chi2 = 0.0;
  const double expected = n / kBins;
  for (const double b : bins) chi2 += (b - expected) * (b - expected) / expected;
  c.report += "chi-square(49) " + std::to_string(chi2);
  if (chi2 > 85.35) ++c.failures;
  return c;
}

TEST(RandomStream, NormalsArePureFunctionsOfTheirKey) {
  const RandomStream a(12345, RandomPurpose::PairNoise, 77, 1);
  const RandomStream b(12345, RandomPurpose::PairNoise, 77, 1);
  for (std::uint32_t i = 0; i < 64; ++i) EXPECT_EQ(a.normal2(99, i), b.normal2(99, i));
  double v[6];
  a.normals(99, v, 6);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(v[k], a.normal2(99, std::uint32_t(k / 2))[std::size_t(k % 2)]);
  // Another step, stage or purpose draws other numbers.
  EXPECT_NE(a.normal2(99, 0), RandomStream(12345, RandomPurpose::PairNoise, 78, 1).normal2(99, 0));
  EXPECT_NE(a.normal2(99, 0), RandomStream(12345, RandomPurpose::PairNoise, 77, 0).normal2(99, 0));
  EXPECT_NE(a.normal2(99, 0), RandomStream(12345, RandomPurpose::BodyNoise, 77, 1).normal2(99, 0));
}

TEST(RandomStream, NormalsHaveTheStandardNormalDistribution) {
  const RandomStream s(2026, RandomPurpose::PairNoise, 4242, 0);
  const NormalCheck c =
      check_standard_normal([&](std::uint64_t o, std::uint32_t i) { return s.normal2(o, i); });
  std::printf("%s\n", c.report.c_str());
  EXPECT_EQ(c.failures, 0) << c.report;
}

TEST(RandomStream, TheNormalityCheckFailsAPolarMethodWithoutRejection) {
  const RandomStream s(2026, RandomPurpose::PairNoise, 4242, 0);
  const NormalCheck c = check_standard_normal([&](std::uint64_t o, std::uint32_t i) {
    const auto b = s.bits(o, i);
    double u = RandomStream::to_signed_unit(b[0]), v = RandomStream::to_signed_unit(b[1]);
    double q = u * u + v * v;
    if (q >= 1.0) {  // the bug: the candidate is moved into the disc instead of rejected
      const double shrink = (1.0 - 1e-12) / std::sqrt(q);
      u *= shrink, v *= shrink, q = u * u + v * v;
    }
    const double f = std::sqrt(-2.0 * std::log(q) / q);
    return std::array<double, 2>{u * f, v * f};
  });
  std::printf("%s\n", c.report.c_str());
  EXPECT_GT(c.failures, 0) << c.report;
}

TEST(RandomStream, TheNormalityCheckFailsABrokenBoxMuller) {
  const RandomStream s(2026, RandomPurpose::PairNoise, 4242, 0);
  const NormalCheck c = check_standard_normal([&](std::uint64_t o, std::uint32_t i) {
    const double u = s.uniform2(o, i)[0];  // the radius' uniform reused for the angle
    const double r = std::sqrt(-2.0 * std::log(u)), t = 6.283185307179586 * u;
    return std::array<double, 2>{r * std::cos(t), r * std::sin(t)};
  });
  EXPECT_GT(c.failures, 0) << c.report;
}

}  // namespace
}  // namespace fldsim
