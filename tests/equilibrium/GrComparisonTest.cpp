// The chi-square rule of oracle/GrComparison.hpp on bins whose law is known exactly: every block
// holds m bin values made of a moving average of w independent normals, so neighbouring bins are
// correlated with rho_d = (w - d)/w for d < w (a g(r) block fluctuates coherently over a few bins
// the same way: docs/equilibrium-oracle.md, "Correlated bins"). Both sides have the same law (the
// null hypothesis), so the rule's false-alarm rate must be its nominal level. With the bin
// correlation scale it is; without it (the rule as it was, bins taken as independent) it is not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "oracle/GrComparison.hpp"

namespace {

using fldsim::oracle::bin_correlation_scale;
using fldsim::oracle::BinComparison;
using fldsim::oracle::block_mean;
using fldsim::oracle::compare_means;
using fldsim::oracle::judge_bins;

// blocks[k][j]: block j of bin k; bin values are a moving average of `width` normals.
std::vector<std::vector<double>> correlated_blocks(std::mt19937_64& rng, int bins, int blocks, int width) {
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> v(static_cast<std::size_t>(bins),
                                     std::vector<double>(static_cast<std::size_t>(blocks)));
  std::vector<double> e(static_cast<std::size_t>(bins + width));
  for (int j = 0; j < blocks; ++j) {
    for (double& x : e) x = normal(rng);
    for (int k = 0; k < bins; ++k) {
      double s = 0.0;
      for (int i = 0; i < width; ++i) s += e[std::size_t(k + i)];
      v[std::size_t(k)][std::size_t(j)] = 1.0 + s / std::sqrt(double(width));
    }
  }
  return v;
}

struct FalseAlarms {
  double corrected = 0.0, uncorrected = 0.0;  // rates of the chi-square rule
  double mean_scale = 0.0;                    // mean estimated c
};

// `trials` comparisons of two independent sides of the same law (50 bins, 32 against 20 blocks,
// as make validate's 32 runs against the oracle's 20 blocks), chi-square rule at level 0.05.
FalseAlarms false_alarms(int width, int trials) {
  std::mt19937_64 rng(20261204);
  const int bins = 50;
  const double alpha = 0.1;  // judge_bins gives each rule alpha / 2
  FalseAlarms f;
  for (int t = 0; t < trials; ++t) {
    const auto a = correlated_blocks(rng, bins, 32, width), b = correlated_blocks(rng, bins, 20, width);
    std::vector<BinComparison> cmp;
    for (int k = 0; k < bins; ++k) {
      BinComparison c = compare_means(block_mean(a[std::size_t(k)]), block_mean(b[std::size_t(k)]));
      c.compared = true;
      cmp.push_back(c);
    }
    const double scale = bin_correlation_scale(a, b);
    f.mean_scale += scale / trials;
    f.corrected += judge_bins(cmp, alpha, scale).chi_square_pass ? 0.0 : 1.0 / trials;
    f.uncorrected += judge_bins(cmp, alpha, 1.0).chi_square_pass ? 0.0 : 1.0 / trials;
  }
  return f;
}

// Three binomial standard errors of a rate p over n trials.
double three_se(double p, int n) {
  return 3.0 * std::sqrt(p * (1.0 - p) / n);
}

}  // namespace

// Exact c = tr(C^2)/m = 1 + (2/m) sum_d (m - d) rho_d^2: 2.70 for width 4 (rho 0.75, 0.5, 0.25).
TEST(GrComparison, CorrelatedBinsKeepTheNominalFalseAlarmRate) {
  const int trials = 2000;
  const FalseAlarms f = false_alarms(4, trials);
  const double exact = 1.0 + 2.0 * (49.0 * 0.5625 + 48.0 * 0.25 + 47.0 * 0.0625) / 50.0;
  std::cout << "moving average of 4: c estimated " << f.mean_scale << " (exact " << exact
            << "); false alarms at level 0.05: " << f.corrected << " with c, " << f.uncorrected
            << " with bins taken as independent\n";
  EXPECT_NEAR(f.corrected, 0.05, three_se(0.05, trials));
  // The rule as it was (c = 1) is the broken variant: it must fail the same check.
  EXPECT_GT(f.uncorrected, 0.05 + three_se(0.05, trials)) << "the check cannot see correlated bins";
  // c itself is estimated within 10 % (its sampling error over 32 and 20 blocks).
  EXPECT_NEAR(f.mean_scale, exact, 0.1 * exact);
}

// Independent bins: c stays near 1 and the rate at its nominal level.
TEST(GrComparison, IndependentBinsKeepTheirDegreesOfFreedom) {
  const int trials = 2000;
  const FalseAlarms f = false_alarms(1, trials);
  std::cout << "independent bins: c estimated " << f.mean_scale << "; false alarms " << f.corrected
            << " with c, " << f.uncorrected << " without\n";
  EXPECT_NEAR(f.corrected, 0.05, three_se(0.05, trials));
  EXPECT_LT(f.mean_scale, 1.1);
}
