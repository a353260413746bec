#include "oracle/GrComparison.hpp"

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

GrComparison compare_gr(const RadialHistogram& a, const RadialHistogram& b, const GrComparisonOptions& opt) {
  if (a.bins() != b.bins() || std::abs(a.bin_width() - b.bin_width()) > 1e-12)
    throw Error("g(r) comparison: the two histograms have different bins");
  std::vector<BinComparison> bins;
  for (int k = 0; k < a.bins(); ++k) {
    const double lo = a.lower_edge(k);
    if (lo < opt.r_from - 1e-9 || lo >= opt.r_to - 1e-9) continue;
    BinComparison c = compare_means(a.g(k), b.g(k));
    c.r_lo = lo;
    c.r_hi = lo + a.bin_width();
    c.compared = a.total_count(k) >= opt.min_count && b.total_count(k) >= opt.min_count;
    bins.push_back(c);
  }
  return judge_bins(std::move(bins), opt.alpha);
}

GrComparison judge_bins(std::vector<BinComparison> bins, double alpha) {
  GrComparison out;
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
  out.chi_square_p = chi_square_upper(out.chi_square, out.compared);
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
  std::snprintf(line, sizeof line,
                "%d bins compared; Bonferroni: every p > %.1e (family-wise %.3g): %s (max |z| %.2f); "
                "chi-square %.1f on %d dof, p = %.2e (> %.3g): %s\n",
                compared, p_bin_threshold, 0.5 * alpha, bonferroni_pass ? "pass" : "FAIL", max_abs_z,
                chi_square, compared, chi_square_p, 0.5 * alpha, chi_square_pass ? "pass" : "FAIL");
  o << line;
  return o.str();
}

}  // namespace fldsim::oracle
