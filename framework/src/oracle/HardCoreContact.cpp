#include "oracle/HardCoreContact.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "fldsim/error.hpp"

namespace fldsim::oracle {

HardCoreContact::HardCoreContact(const System& s, double bin_width, double span)
    : contact_(2.0 * s.shape().nodes().front().radius),
      bin_(bin_width),
      span_(span),
      bodies_(double(s.size())),
      sum_(std::size_t(std::llround(span / bin_width)), 0.0) {
  for (const auto& n : s.shape().nodes())
    if (n.radius != s.shape().nodes().front().radius)
      throw Error("Monte Carlo oracle: the hard core's contact term needs nodes of one radius");
  if (sum_.size() < 3) throw Error("Monte Carlo oracle: the contact fit needs at least 3 bins");
  list_.configure(contact_ + span_, 0.0);
}

void HardCoreContact::add_sample(const System& s) {
  list_.update(s);
  const std::size_t m = s.nodes_per_body();
  const auto& off = s.node_offsets();
  for (const NodePair& p : list_.pairs().pairs()) {
    const double h = p.distance - contact_;
    if (h < 0.0 || h >= span_) continue;
    const Vec3 R = p.r - off[p.body_j * m + p.node_b] + off[p.body_i * m + p.node_a];
    const std::size_t k = std::min(sum_.size() - 1, std::size_t(h / bin_));
    sum_[k] += R.dot(p.r) / p.distance;
  }
  ++samples_;
}

void HardCoreContact::end_block() {
  // f(h) per bin = sum / (samples * bin); quadratic through the bin centres, evaluated at 0.
  const Eigen::Index n = Eigen::Index(sum_.size());
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double x = (double(k) + 0.5) * bin_;
    A.row(k) << 1.0, x, x * x;
    y[k] = samples_ > 0 ? sum_[std::size_t(k)] / (double(samples_) * bin_) : 0.0;
  }
  const double f0 = A.colPivHouseholderQr().solve(y)[0];
  blocks_.push_back(f0 / (3.0 * bodies_));
  std::fill(sum_.begin(), sum_.end(), 0.0);
  samples_ = 0;
}

}  // namespace fldsim::oracle
