// Orientation statistics of the directors of a suspension, accumulated over samples
// (Kumar & Higdon §3.2). Normalisation: the folded angles cover theta in [0, pi/2], phi in
// [-pi/2, pi/2], a solid angle of pi, so an isotropic suspension has the density
// sin(theta) dtheta dphi / pi and P(theta), P(phi), P(theta, phi) are the measured fractions
// divided by the isotropic ones (1 everywhere for isotropy).
//   theta_m = int theta P(theta) sin(theta) dtheta     (isotropic: int theta sin = 1 rad)
//   phi_m   = (1/pi) int |phi| P(phi) dphi             (isotropic: pi/4)
// With the empirical density P(theta) sin(theta) dtheta = (1/N) sum_k delta(theta - theta_k)
// these integrals are the sample means of theta and |phi|, which we compute directly; the
// histograms (piecewise constant P) reproduce them to within one bin width.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fldsim-sdk/statistics/BlockAverage.hpp"
#include "fldsim/box.hpp"

namespace fldsim::observers {

class OrientationStatistics {
 public:
  OrientationStatistics(int theta_bins, int phi_bins);

  // Reserve room for the expected number of samples (no allocation while sampling).
  void reserve(std::size_t samples);
  void add_sample(const std::vector<Vec3>& directors);
  // Checkpoint state (exact restart); restore needs the same bin counts.
  void save(StateWriter& w) const;
  void restore(StateReader& r);

  int theta_bins() const { return n_theta_; }
  int phi_bins() const { return n_phi_; }
  double theta_edge(int b) const;  // lower edge of theta bin b (b = bins gives pi/2)
  double phi_edge(int b) const;
  // Isotropic probability of a bin: cos(theta_b) - cos(theta_b+1), and dphi / pi.
  double theta_bin_weight(int b) const;
  double phi_bin_weight(int b) const;

  std::size_t samples() const { return theta_m_.count(); }
  std::size_t directors_seen() const { return seen_; }
  // Histograms over all samples, and the SE of each bin from blocking the per-sample values.
  std::vector<double> p_theta() const;
  std::vector<double> p_phi() const;
  std::vector<double> p_theta_stderr() const;
  std::vector<double> p_phi_stderr() const;
  // Row-major [theta bin][phi bin].
  std::vector<double> p_theta_phi() const;

  // Per-sample series (their mean and blocking SE are the steady-state results).
  const BlockAverage& theta_m() const { return theta_m_; }
  const BlockAverage& phi_m() const { return phi_m_; }
  // Order tensor component Q_ij = <3/2 n_i n_j - 1/2 delta_ij>; S_ii = Q_ii.
  const BlockAverage& q(int i, int j) const { return q_[i * 3 + j]; }
  Eigen::Matrix3d q_mean() const;
  // Last sample's values (for time series).
  double last_theta_m() const { return last_theta_m_; }
  double last_phi_m() const { return last_phi_m_; }
  const Eigen::Matrix3d& last_q() const { return last_q_; }

 private:
  int n_theta_, n_phi_;
  std::vector<double> count_theta_, count_phi_, count_map_;
  std::vector<int> sample_theta_, sample_phi_;  // per-sample bin counts (buffers)
  std::vector<BlockAverage> p_theta_series_, p_phi_series_;
  BlockAverage theta_m_, phi_m_;
  BlockAverage q_[9];
  std::size_t seen_ = 0;
  double last_theta_m_ = 0.0, last_phi_m_ = 0.0;
  Eigen::Matrix3d last_q_ = Eigen::Matrix3d::Zero();
};

}  // namespace fldsim::observers
