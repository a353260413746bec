#include "oracle/GrComparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "fldsim/error.hpp"

namespace fldsim::oracle {

BinComparison compare_means(const MeanError& a, const MeanError& b) {
  BinComparison c;
  c.a = a;
  c.b = b;
  c.ratio = b.mean != 0.0 ? a.mean / b.mean : NAN;
  const double se = std::hypot(a.se, b.se);
  c.dof = welch_dof(a.se, a.blocks - 1, b.se, b.blocks - 1);
  if (se > 0.0) {
    c.z = (a.mean - b.mean) / se;
    c.p = student_t_two_sided(c.z, c.dof);
  } else {
    c.z = a.mean == b.mean ? 0.0 : INFINITY;
    c.p = a.mean == b.mean ? 1.0 : 0.0;
  }
  return c;
}

namespace {

// Sample covariance of the block values of bins k and l (B - 1 in the denominator).
double block_covariance(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2) return 0.0;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= double(n);
  my /= double(n);
  double c = 0.0;
  for (std::size_t i = 0; i < n; ++i) c += (x[i] - mx) * (y[i] - my);
  return c / double(n - 1);
}

}  // namespace

double bin_correlation_scale(const std::vector<std::vector<double>>& a,
                             const std::vector<std::vector<double>>& b) {
  const std::size_t m = a.size();
  if (m < 2 || b.size() != m) return 1.0;
  const std::size_t blocks = std::min(a[0].size(), b[0].size());
  if (blocks < 4) return 1.0;
  auto cov = [&](std::size_t k, std::size_t l) {
    return block_covariance(a[k], a[l]) / double(a[k].size()) +
           block_covariance(b[k], b[l]) / double(b[k].size());
  };
  std::vector<double> var(m);
  for (std::size_t k = 0; k < m; ++k) var[k] = cov(k, k);
  double trace = double(m);
  for (std::size_t d = 1; d < m; ++d) {
    double sum = 0.0;
    int pairs = 0;
    for (std::size_t k = 0; k + d < m; ++k) {
      const double s = var[k] * var[k + d];
      if (!(s > 0.0)) continue;
      sum += cov(k, k + d) / std::sqrt(s);
      ++pairs;
    }
    if (pairs == 0) break;
    const double rho = sum / pairs;
    if (std::abs(rho) <= 2.0 / std::sqrt(double(blocks) * pairs)) break;
    trace += 2.0 * pairs * rho * rho;
  }
  return trace / double(m);
}

GrComparison compare_gr(const RadialHistogram& a, const RadialHistogram& b, const GrComparisonOptions& opt) {
  if (a.bins() != b.bins() || std::abs(a.bin_width() - b.bin_width()) > 1e-12)
    throw Error("g(r) comparison: the two histograms have different bins");
  std::vector<BinComparison> bins;
  std::vector<std::vector<double>> blocks_a, blocks_b;  // block values of the compared bins
  for (int k = 0; k < a.bins(); ++k) {
    const double lo = a.lower_edge(k);
    if (lo < opt.r_from - 1e-9 || lo >= opt.r_to - 1e-9) continue;
    BinComparison c = compare_means(a.g(k), b.g(k));
    c.r_lo = lo;
    c.r_hi = lo + a.bin_width();
    c.compared = a.total_count(k) >= opt.min_count && b.total_count(k) >= opt.min_count;
    if (c.compared) {
      blocks_a.push_back(a.block_values(k));
      blocks_b.push_back(b.block_values(k));
    }
    bins.push_back(c);
  }
  return judge_bins(std::move(bins), opt.alpha, bin_correlation_scale(blocks_a, blocks_b));
}

GrComparison judge_bins(std::vector<BinComparison> bins, double alpha, double correlation_scale) {
  GrComparison out;
  out.correlation_scale = std::max(1.0, correlation_scale);
  out.bins = std::move(bins);
  for (const auto& c : out.bins) out.compared += c.compared ? 1 : 0;
  if (out.compared == 0) return out;
  out.p_bin_threshold = 0.5 * alpha / out.compared;
  out.alpha = alpha;
  for (std::size_t k = 0; k < out.bins.size(); ++k) {
    const BinComparison& c = out.bins[k];
    if (!c.compared) continue;
    if (std::abs(c.z) > out.max_abs_z) {
      out.max_abs_z = std::abs(c.z);
      out.worst_bin = int(k);
    }
    if (c.p <= out.p_bin_threshold) out.bonferroni_pass = false;
    // Normal score with the same two-sided tail probability.
    const double zn = c.p > 0.0 ? normal_upper_quantile(0.5 * c.p) : 40.0;
    out.chi_square += zn * zn;
  }
  const double c = out.correlation_scale;
  out.chi_square_p = chi_square_upper(out.chi_square / c, out.compared / c);
  out.chi_square_pass = out.chi_square_p > 0.5 * alpha;
  return out;
}

std::string GrComparison::table(const GrComparisonOptions& opt) const {
  std::ostringstream o;
  char line[256];
  std::snprintf(line, sizeof line, "%-13s %9s %7s %9s %7s %7s %7s %8s\n", "r/a", opt.label_a.c_str(), "SE",
                opt.label_b.c_str(), "SE", "ratio", "z", "p");
  o << line;
  const bool fine = !bins.empty() && bins.front().r_hi - bins.front().r_lo < 0.0099;
  for (const auto& c : bins) {
    std::snprintf(
        line, sizeof line,
        fine ? "%5.3f-%5.3f%9.4f %7.4f %9.4f %7.4f %7.3f %7.2f %8.1e%s\n"
             : "%5.2f-%5.2f  %9.4f %7.4f %9.4f %7.4f %7.3f %7.2f %8.1e%s\n",
        c.r_lo, c.r_hi, c.a.mean, c.a.se, c.b.mean, c.b.se, c.ratio, c.z, c.p,
        !c.compared ? "  (too few pairs: not compared)" : (c.p <= p_bin_threshold ? "  <-- FAILS" : ""));
    o << line;
  }
  std::snprintf(
      line, sizeof line,
      "%d bins compared; Bonferroni: every p > %.1e (family-wise %.3g): %s (max |z| %.2f); "
      "chi-square %.1f on %d bins, %.1f effective (bin correlation scale %.2f), p = %.2e (> %.3g): %s\n",
      compared, p_bin_threshold, 0.5 * alpha, bonferroni_pass ? "pass" : "FAIL", max_abs_z, chi_square,
      compared, compared / correlation_scale, correlation_scale, chi_square_p, 0.5 * alpha,
      chi_square_pass ? "pass" : "FAIL");
  o << line;
  return o.str();
}

}  // namespace fldsim::oracle
