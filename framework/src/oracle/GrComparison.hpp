// Bin-by-bin comparison of two blocked g(r) (a Brownian run against the Monte Carlo oracle):
//   z_k = (g_a - g_b) / sqrt(se_a^2 + se_b^2)          per bin, block errors on both sides
// Under the null hypothesis (same distribution) z_k follows Student's t with the Welch-Satterthwaite
// degrees of freedom of the two block SEs. Two family-wise rules, each at level alpha/2 so that
// together a correct model fails with probability <= alpha (default 0.01):
//   Bonferroni  every compared bin has two-sided p_k > alpha / (2 m) (m compared bins): catches a
//               local artifact (contact excess, cutoff spike);
//   chi-square  X = sum z'_k^2 with z'_k the normal score of p_k, against chi-square with m degrees
//               of freedom: catches a small deviation spread over many bins.
// The bins are treated as independent (neighbouring thin bins are only weakly correlated); a bin
// is compared only if both sides counted at least `min_count` pairs in it (fewer make the block
// SE meaningless); the table lists the skipped ones too.
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
  bool bonferroni_pass = true, chi_square_pass = true;
  bool pass() const { return bonferroni_pass && chi_square_pass; }
  std::string table(const GrComparisonOptions& opt) const;
};

// a and b must have the same bins (width and range).
GrComparison compare_gr(const RadialHistogram& a, const RadialHistogram& b, const GrComparisonOptions& opt);
// The two family-wise rules over bins already compared (those with `compared` set), e.g. a
// histogram against exact values.
GrComparison judge_bins(std::vector<BinComparison> bins, double alpha);

// The two-sided p and Welch z of the difference of two block means (for shells and scalars).
BinComparison compare_means(const MeanError& a, const MeanError& b);

}  // namespace fldsim::oracle
