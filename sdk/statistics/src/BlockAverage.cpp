#include "fldsim-sdk/statistics/BlockAverage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fldsim::observers {

double BlockAverage::mean() const {
  if (samples_.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(samples_.begin(), samples_.end(), 0.0) / static_cast<double>(samples_.size());
}

std::vector<BlockingLevel> BlockAverage::levels() const {
  std::vector<BlockingLevel> out;
  if (samples_.size() < 2) return out;
  std::vector<double> x = samples_;
  std::size_t block = 1;
  const double mu = mean();
  while (x.size() >= 2 && (out.empty() || x.size() >= kMinBlocks)) {
    const double n = static_cast<double>(x.size());
    double ss = 0.0;
    for (double v : x) ss += (v - mu) * (v - mu);
    // Flyvbjerg–Petersen eq. (28): sigma^2(mean) ~ c0 / (n - 1), with c0 the variance of the block means.
    const double se = std::sqrt(ss / n / (n - 1.0));
    out.push_back({block, x.size(), se, se / std::sqrt(2.0 * (n - 1.0))});
    // Pair neighbouring blocks (an odd last sample is dropped at this level).
    std::vector<double> y(x.size() / 2);
    for (std::size_t i = 0; i < y.size(); ++i) y[i] = 0.5 * (x[2 * i] + x[2 * i + 1]);
    x.swap(y);
    block *= 2;
  }
  return out;
}

std::size_t BlockAverage::plateau_level(const std::vector<BlockingLevel>& lv) const {
  for (std::size_t l = 0; l < lv.size(); ++l) {
    bool flat = true;
    for (std::size_t k = l + 1; k < lv.size() && flat; ++k)
      flat = lv[k].stderr_value <= lv[l].stderr_value + lv[l].stderr_error + lv[k].stderr_error;
    // The last level is only a plateau if a previous level confirms it.
    if (flat && l + 1 < lv.size()) return l;
  }
  return lv.size();
}

double BlockAverage::stderr_mean() const {
  const auto lv = levels();
  if (lv.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t l = plateau_level(lv);
  if (l < lv.size()) return lv[l].stderr_value;
  double best = 0.0;
  for (const auto& v : lv) best = std::max(best, v.stderr_value);
  return best;
}

double BlockAverage::correlation_samples() const {
  const auto lv = levels();
  if (lv.empty() || lv.front().stderr_value <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  // Level 0 holds the naive SE^2 = var / (n - 1); the ratio of the variances is s.
  const double ratio = stderr_mean() / lv.front().stderr_value;
  return ratio * ratio;
}

bool BlockAverage::converged() const {
  const auto lv = levels();
  return !lv.empty() && plateau_level(lv) < lv.size();
}

}  // namespace fldsim::observers
