// Statistics for equilibrium comparisons from block means of a correlated run.
//  - mean and standard error of B block means: SE = sd / sqrt(B), valid once the blocks are longer
//    than the correlation time (block_error_ratio() compares SE with B/2 blocks of twice the
//    length: about 1 on the plateau, > 1 if the blocks are still too short);
//  - Student's t two-sided tail and the Welch-Satterthwaite degrees of freedom for the difference
//    of two such means (Welch, Biometrika 34, 28 (1947));
//  - the standard normal quantile and the chi-square upper tail, for family-wise rules.
// The special functions are the regularised incomplete beta (continued fraction, modified Lentz)
// and gamma (series / continued fraction), Abramowitz & Stegun 26.5.8 and 6.5.29-31.
#pragma once

#include <vector>

namespace fldsim::oracle {

struct MeanError {
  double mean = 0.0;
  double se = 0.0;  // standard error of the mean from the block means
  int blocks = 0;   // B; the SE has B - 1 degrees of freedom
};

MeanError block_mean(const std::vector<double>& block_values);
// SE from B/2 blocks (neighbouring pairs merged) over SE from B blocks; NaN for B < 4.
double block_error_ratio(const std::vector<double>& block_values);

// P(|T| > t) for Student's t with nu degrees of freedom (nu may be fractional, > 0).
double student_t_two_sided(double t, double nu);
// Welch-Satterthwaite degrees of freedom of a difference of means with SEs s1, s2 estimated with
// nu1, nu2 degrees of freedom.
double welch_dof(double s1, int nu1, double s2, int nu2);
// x with P(Z > x) = p for the standard normal (0 < p < 1).
double normal_upper_quantile(double p);
// P(X > x) for chi-square with k degrees of freedom.
double chi_square_upper(double x, double k);

}  // namespace fldsim::oracle
