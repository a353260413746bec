#include "oracle/BlockStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fldsim::oracle {
namespace {

// Continued fraction of the regularised incomplete beta I_x(a, b) (A&S 26.5.8, modified Lentz).
double beta_fraction(double a, double b, double x) {
  constexpr double tiny = 1e-300, eps = 1e-15;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    for (int pass = 0; pass < 2; ++pass) {
      d = 1.0 + num * d;
      if (std::abs(d) < tiny) d = tiny;
      c = 1.0 + num / c;
      if (std::abs(c) < tiny) c = tiny;
      d = 1.0 / d;
      const double step = d * c;
      h *= step;
      if (pass == 1 && std::abs(step - 1.0) < eps) return h;
      num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    }
  }
  return h;
}

double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front =
      std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
  return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

// Upper regularised incomplete gamma Q(a, x) (A&S 6.5.29 series, 6.5.31 continued fraction).
double upper_gamma(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double front = std::exp(-x + a * std::log(x) - std::lgamma(a));
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000 && std::abs(term) > 1e-16 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return 1.0 - front * sum;
  }
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < 1e-15) break;
  }
  return front * h;
}

}  // namespace

MeanError block_mean(const std::vector<double>& v) {
  MeanError r;
  r.blocks = int(v.size());
  if (v.empty()) return r;
  for (double x : v) r.mean += x;
  r.mean /= double(v.size());
  if (v.size() < 2) {
    r.se = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  double var = 0.0;
  for (double x : v) var += (x - r.mean) * (x - r.mean);
  r.se = std::sqrt(var / double(v.size() - 1) / double(v.size()));
  return r;
}

double block_error_ratio(const std::vector<double>& v) {
  if (v.size() < 4) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> merged;
  for (std::size_t k = 0; k + 1 < v.size(); k += 2) merged.push_back(0.5 * (v[k] + v[k + 1]));
  const double fine = block_mean(v).se;
  return fine > 0.0 ? block_mean(merged).se / fine : std::numeric_limits<double>::quiet_NaN();
}

double student_t_two_sided(double t, double nu) {
  if (!std::isfinite(t)) return 0.0;
  return incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t));
}

double welch_dof(double s1, int nu1, double s2, int nu2) {
  const double v1 = s1 * s1, v2 = s2 * s2;
  const double den = (nu1 > 0 ? v1 * v1 / nu1 : 0.0) + (nu2 > 0 ? v2 * v2 / nu2 : 0.0);
  if (den <= 0.0) return double(std::max(1, std::min(nu1, nu2)));
  return (v1 + v2) * (v1 + v2) / den;
}

double normal_upper_quantile(double p) {
  // Bisection on erfc: P(Z > x) = erfc(x / sqrt 2) / 2, monotone; 200 halvings reach round-off.
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double chi_square_upper(double x, double k) {
  return upper_gamma(0.5 * k, 0.5 * x);
}

}  // namespace fldsim::oracle
