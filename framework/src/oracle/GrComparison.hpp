// Bin-by-bin comparison of two blocked g(r) (a Brownian run against the Monte Carlo oracle):
//   z_k = (g_a - g_b) / sqrt(se_a^2 + se_b^2)          per bin, block errors on both sides
// Under the null hypothesis (same distribution) z_k follows Student's t with the Welch-Satterthwaite
// degrees of freedom of the two block SEs. Two family-wise rules, each at level alpha/2 so that
// together a correct model fails with probability <= alpha (default 0.01):
//   Bonferroni  every compared bin has two-sided p_k > alpha / (2 m) (m compared bins): catches a
//               local artifact (contact excess, cutoff spike);
//   chi-square  X = sum z'_k^2 with z'_k the normal score of p_k, judged as X/c against chi-square
//               with m/c degrees of freedom: catches a small deviation spread over many bins.
// Neighbouring bins are not independent (one block's structure fluctuates coherently over a few
// tenths of a: docs/equilibrium-oracle.md, "Correlated bins"); with correlated z_k, X has the mean
// m but the variance 2 tr(C^2) > 2m, C their correlation matrix. c = tr(C^2)/m matches both
// moments (Box, Ann. Math. Stat. 25, 290 (1954)); compare_gr estimates it from the blocks
// (bin_correlation_scale), judge_bins, which has no blocks, keeps c = 1.
// A bin is compared only if both sides counted at least `min_count` pairs in it (fewer make the
// block SE meaningless); the table lists the skipped ones too.
#pragma once

#include <string>
#include <vector>

#include "oracle/RadialHistogram.hpp"

namespace fldsim::oracle {

struct BinComparison {
  double r_lo = 0.0, r_hi = 0.0;
  MeanError a, b;
  double ratio = 0.0;  // g_a / g_b
  double z = 0.0;
  double dof = 0.0;
  double p = 1.0;  // two-sided
  bool compared = false;
};

struct GrComparisonOptions {
  double r_from = 2.0, r_to = 3.0;  // bins whose lower edge lies in [r_from, r_to)
  double alpha = 0.01;              // family-wise false-alarm probability of both rules together
  double min_count = 20.0;
  std::string label_a = "BD", label_b = "MC";
};

struct GrComparison {
  std::vector<BinComparison> bins;
  int compared = 0;
  double alpha = 0.01;
  double p_bin_threshold = 0.0;  // alpha / (2 m)
  double max_abs_z = 0.0;
  int worst_bin = -1;
  double chi_square = 0.0, chi_square_p = 1.0;
  double correlation_scale = 1.0;  // c = tr(C^2)/m (1: independent bins); m/c effective bins
  bool bonferroni_pass = true, chi_square_pass = true;
  bool pass() const { return bonferroni_pass && chi_square_pass; }
  std::string table(const GrComparisonOptions& opt) const;
};

// a and b must have the same bins (width and range).
GrComparison compare_gr(const RadialHistogram& a, const RadialHistogram& b, const GrComparisonOptions& opt);
// c = tr(C^2)/m of the z_k of m compared bins from their block values (a[k], b[k]: the blocks of
// compared bin k on each side; 1 for fewer than 2 bins or 4 blocks), with
// cov(z_k, z_l) = (cov_a(k,l)/B_a + cov_b(k,l)/B_b) / (se_k se_l) averaged per bin lag d into rho_d
// and tr(C^2) = m + 2 sum_d n_d rho_d^2 over d = 1, 2, ... up to the first lag whose rho_d is
// within twice its sampling error 1/sqrt(B n_d) (longer lags, mostly noise, could only raise c:
// leaving them out keeps the rule on the strict side).
double bin_correlation_scale(const std::vector<std::vector<double>>& a,
                             const std::vector<std::vector<double>>& b);

// The two family-wise rules over bins already compared (those with `compared` set), e.g. a
// histogram against exact values; correlation_scale: c above (1 = independent bins).
GrComparison judge_bins(std::vector<BinComparison> bins, double alpha, double correlation_scale = 1.0);

// The two-sided p and Welch z of the difference of two block means (for shells and scalars).
BinComparison compare_means(const MeanError& a, const MeanError& b);

}  // namespace fldsim::oracle
