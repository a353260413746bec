#include "OrientationStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "DirectorAngles.hpp"

namespace fldsim::observers {

namespace {
constexpr double kPi = std::numbers::pi;
int bin_of(double x, double lo, double width, int n) {
  return std::clamp(static_cast<int>(std::floor((x - lo) / width)), 0, n - 1);
}
}  // namespace

OrientationStatistics::OrientationStatistics(int theta_bins, int phi_bins)
    : n_theta_(theta_bins),
      n_phi_(phi_bins),
      count_theta_(theta_bins, 0.0),
      count_phi_(phi_bins, 0.0),
      count_map_(static_cast<std::size_t>(theta_bins) * phi_bins, 0.0),
      sample_theta_(theta_bins, 0),
      sample_phi_(phi_bins, 0),
      p_theta_series_(theta_bins),
      p_phi_series_(phi_bins) {}

void OrientationStatistics::reserve(std::size_t samples) {
  for (auto& s : p_theta_series_) s.reserve(samples);
  for (auto& s : p_phi_series_) s.reserve(samples);
  theta_m_.reserve(samples);
  phi_m_.reserve(samples);
  for (auto& s : q_) s.reserve(samples);
}

double OrientationStatistics::theta_edge(int b) const {
  return 0.5 * kPi * b / n_theta_;
}
double OrientationStatistics::phi_edge(int b) const {
  return -0.5 * kPi + kPi * b / n_phi_;
}
double OrientationStatistics::theta_bin_weight(int b) const {
  return std::cos(theta_edge(b)) - std::cos(theta_edge(b + 1));
}
double OrientationStatistics::phi_bin_weight(int) const {
  return 1.0 / n_phi_;
}

void OrientationStatistics::add_sample(const std::vector<Vec3>& directors) {
  const std::size_t n = directors.size();
  if (n == 0) return;
  std::fill(sample_theta_.begin(), sample_theta_.end(), 0);
  std::fill(sample_phi_.begin(), sample_phi_.end(), 0);
  double sum_theta = 0.0, sum_abs_phi = 0.0;
  Eigen::Matrix3d nn = Eigen::Matrix3d::Zero();
  const double w_theta = 0.5 * kPi / n_theta_, w_phi = kPi / n_phi_;
  for (const Vec3& raw : directors) {
    const Vec3 d = raw.normalized();
    const DirectorAngles a = director_angles(d);
    sum_theta += a.theta;
    sum_abs_phi += std::abs(a.phi);
    nn.noalias() += d * d.transpose();
    const int bt = bin_of(a.theta, 0.0, w_theta, n_theta_);
    const int bp = bin_of(a.phi, -0.5 * kPi, w_phi, n_phi_);
    ++sample_theta_[bt];
    ++sample_phi_[bp];
    count_map_[static_cast<std::size_t>(bt) * n_phi_ + bp] += 1.0;
  }
  const double inv_n = 1.0 / static_cast<double>(n);
  for (int b = 0; b < n_theta_; ++b) {
    count_theta_[b] += sample_theta_[b];
    p_theta_series_[b].add(sample_theta_[b] * inv_n / theta_bin_weight(b));
  }
  for (int b = 0; b < n_phi_; ++b) {
    count_phi_[b] += sample_phi_[b];
    p_phi_series_[b].add(sample_phi_[b] * inv_n / phi_bin_weight(b));
  }
  seen_ += n;
  last_theta_m_ = sum_theta * inv_n;
  last_phi_m_ = sum_abs_phi * inv_n;
  last_q_ = 1.5 * nn * inv_n - 0.5 * Eigen::Matrix3d::Identity();
  theta_m_.add(last_theta_m_);
  phi_m_.add(last_phi_m_);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) q_[i * 3 + j].add(last_q_(i, j));
}

void OrientationStatistics::save(StateWriter& w) const {
  w.put(count_theta_).put(count_phi_).put(count_map_).put(double(seen_));
  for (const auto& b : p_theta_series_) b.save(w);
  for (const auto& b : p_phi_series_) b.save(w);
  theta_m_.save(w);
  phi_m_.save(w);
  for (const auto& b : q_) b.save(w);
  w.put(last_theta_m_).put(last_phi_m_).put(last_q_);
}

void OrientationStatistics::restore(StateReader& r) {
  r.get_into(count_theta_);
  r.get_into(count_phi_);
  r.get_into(count_map_);
  seen_ = static_cast<decltype(seen_)>(r.get());
  for (auto& b : p_theta_series_) b.restore(r);
  for (auto& b : p_phi_series_) b.restore(r);
  theta_m_.restore(r);
  phi_m_.restore(r);
  for (auto& b : q_) b.restore(r);
  last_theta_m_ = r.get();
  last_phi_m_ = r.get();
  r.get_into(last_q_);
}

std::vector<double> OrientationStatistics::p_theta() const {
  std::vector<double> p(n_theta_);
  for (int b = 0; b < n_theta_; ++b)
    p[b] = count_theta_[b] / (static_cast<double>(seen_) * theta_bin_weight(b));
  return p;
}

std::vector<double> OrientationStatistics::p_phi() const {
  std::vector<double> p(n_phi_);
  for (int b = 0; b < n_phi_; ++b) p[b] = count_phi_[b] / (static_cast<double>(seen_) * phi_bin_weight(b));
  return p;
}

std::vector<double> OrientationStatistics::p_theta_stderr() const {
  std::vector<double> e(n_theta_);
  for (int b = 0; b < n_theta_; ++b) e[b] = p_theta_series_[b].stderr_mean();
  return e;
}

std::vector<double> OrientationStatistics::p_phi_stderr() const {
  std::vector<double> e(n_phi_);
  for (int b = 0; b < n_phi_; ++b) e[b] = p_phi_series_[b].stderr_mean();
  return e;
}

std::vector<double> OrientationStatistics::p_theta_phi() const {
  std::vector<double> p(count_map_.size());
  for (int t = 0; t < n_theta_; ++t)
    for (int f = 0; f < n_phi_; ++f) {
      const std::size_t k = static_cast<std::size_t>(t) * n_phi_ + f;
      p[k] = count_map_[k] / (static_cast<double>(seen_) * theta_bin_weight(t) * phi_bin_weight(f));
    }
  return p;
}

Eigen::Matrix3d OrientationStatistics::q_mean() const {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = q_[i * 3 + j].mean();
  return m;
}

}  // namespace fldsim::observers
