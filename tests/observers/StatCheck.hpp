// Statistical checks for histogram tests. A histogram has many bins, so "every bin within 3 SE"
// fails by chance in ~0.27 % of bins; with k bins the per-bin bound is instead set so that the
// family-wise false-alarm rate is 0.27 % (Bonferroni: two-sided tail 0.0027/k per bin), and the
// bins are also tested jointly by chi^2 = sum z^2, which for k independent bins has mean k and
// standard deviation sqrt(2k) (accepted within 3 standard deviations).
#pragma once

#include <cmath>
#include <vector>

namespace fldsim::test {

// z such that the two-sided normal tail beyond |z| is p (bisection on erfc).
inline double normal_two_sided_quantile(double p) {
  double lo = 0.0, hi = 40.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The 3-sigma family-wise bound for k bins (3.0 for one bin).
inline double bonferroni_bound(std::size_t k) {
  return normal_two_sided_quantile(0.0027 / static_cast<double>(k));
}

struct BinCheck {
  double max_abs_z = 0.0;
  double chi2 = 0.0;
  std::size_t bins = 0;
};

inline BinCheck check_bins(const std::vector<double>& value, const std::vector<double>& expected,
                           const std::vector<double>& se) {
  BinCheck c;
  for (std::size_t b = 0; b < value.size(); ++b) {
    const double z = (value[b] - expected[b]) / se[b];
    c.max_abs_z = std::max(c.max_abs_z, std::abs(z));
    c.chi2 += z * z;
    ++c.bins;
  }
  return c;
}

}  // namespace fldsim::test
