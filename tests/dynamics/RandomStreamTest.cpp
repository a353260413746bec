// The counter-based normals (fldsim/random.hpp, RandomStream::normal2, the ziggurat method):
//  - a pair is a pure function of (seed, purpose, step, stage, object, index), and normals()
//    fills from the same pairs;
//  - 2^20 normals (2^19 pairs over many pair-like objects and indices) have the standard normal
//    distribution: mean, variance, fourth moment (3), the correlation of a pair's two values, the
//    fractions beyond |z| = 3 (2 (1 - Phi(3)) = 0.0026998) and beyond |z| = 3.5 (4.653e-4, inside
//    the ziggurat's tail, which starts at 3.4426), each within 3.3 standard errors, and a
//    chi-square over 50 equiprobable bins of Phi below the 0.1 % quantile of chi-square with 49
//    degrees of freedom (85.35, Wilson-Hilferty). Seven comparisons at 0.1 % each: family-wise
//    false alarms below 1 %. The seeds are fixed, so the test is deterministic; the tolerances say
//    how unlikely a pass of a wrong sampler of this size would be.
//  - The same check applied to broken samplers must fail, so the check can fail: a polar method
//    that keeps the points outside the unit disc (pulled onto its rim instead of redrawn), a
//    Box-Muller with one uniform for both the radius and the angle, and a ziggurat (tables built
//    here, independently of random.hpp's) that accepts its wedges untested, or that puts its tail
//    at r.
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
  double sum = 0, sum2 = 0, sum4 = 0, cross = 0, beyond3 = 0, beyond35 = 0;
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
        beyond35 += std::abs(z) > 3.5 ? 1.0 : 0.0;
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
  const double p35 = std::erfc(3.5 / std::sqrt(2.0));
  expect_within("P(|z| > 3.5)", beyond35 / n, p35, std::sqrt(p35 * (1.0 - p35) / n));
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

// A ziggurat of 128 layers (Marsaglia & Tsang 2000) with its own tables, one attempt per block
// (position from word 0, layer from word 1, wedge height from word 1's upper bits), optionally
// broken: wedge points accepted without their test, or tail points put at +-r.
std::array<double, 2> test_ziggurat(const RandomStream& s, std::uint64_t object, std::uint32_t index,
                                    bool wedge_test, bool tail) {
  static const auto tables = [] {
    constexpr double r = 3.442619855899, v = 9.91256303526217e-3;
    std::array<double, 129> x{};
    x[1] = r;
    for (int i = 1; i < 128; ++i) {
      const double y = v / x[i] + std::exp(-0.5 * x[i] * x[i]);
      x[i + 1] = y < 1.0 ? std::sqrt(-2.0 * std::log(y)) : 0.0;
    }
    x[0] = v / std::exp(-0.5 * r * r);  // the base strip's width
    x[128] = 0.0;
    return x;
  }();
  const double r = tables[1];
  auto f = [](double x) { return std::exp(-0.5 * x * x); };
  std::array<double, 2> out{};
  int have = 0;
  for (std::uint32_t k = 0; have < 2; ++k) {
    const auto b = s.bits(object, index + (k << 20));
    const int i = int(b[1] & 127u);
    const double u = RandomStream::to_signed_unit(b[0]), x = u * tables[std::size_t(i)];
    const double inner = i == 0 ? r : tables[std::size_t(i) + 1];
    if (std::abs(x) < inner) {
      out[std::size_t(have++)] = x;
    } else if (i == 0) {
      if (!tail) {
        out[std::size_t(have++)] = u > 0 ? r : -r;
        continue;
      }
      for (std::uint32_t t = 1;; ++t) {
        const auto w = s.bits(object ^ 0x5A5A5A5A5A5A5A5Aull, index + (k << 20) + t);
        const double e = -std::log(RandomStream::to_unit(w[0], w[1])) / r;
        if (-2.0 * std::log(RandomStream::to_unit(w[2], w[3])) > e * e) {
          out[std::size_t(have++)] = u > 0 ? r + e : -(r + e);
          break;
        }
      }
    } else {
      const double h =
          f(tables[std::size_t(i)]) + (double(b[1] >> 7) + 0.5) / 33554432.0 *
                                          (f(tables[std::size_t(i) + 1]) - f(tables[std::size_t(i)]));
      if (!wedge_test || h < f(x)) out[std::size_t(have++)] = x;
    }
  }
  return out;
}

TEST(RandomStream, TheNormalityCheckPassesTheTestZigguratAndFailsItsBrokenVariants) {
  const RandomStream s(2026, RandomPurpose::PairNoise, 4242, 0);
  const NormalCheck good = check_standard_normal(
      [&](std::uint64_t o, std::uint32_t i) { return test_ziggurat(s, o, i, true, true); });
  std::printf("reference ziggurat: %s\n", good.report.c_str());
  EXPECT_EQ(good.failures, 0) << good.report;
  const NormalCheck no_wedge = check_standard_normal(
      [&](std::uint64_t o, std::uint32_t i) { return test_ziggurat(s, o, i, false, true); });
  std::printf("wedges untested: %s\n", no_wedge.report.c_str());
  EXPECT_GT(no_wedge.failures, 0) << no_wedge.report;
  const NormalCheck no_tail = check_standard_normal(
      [&](std::uint64_t o, std::uint32_t i) { return test_ziggurat(s, o, i, true, false); });
  std::printf("tail at r: %s\n", no_tail.report.c_str());
  EXPECT_GT(no_tail.failures, 0) << no_tail.report;
}

}  // namespace
}  // namespace fldsim
