#include "OrientationObserver.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <iostream>
#include <numbers>

#include "fldsim-sdk/statistics/ObserverOutput.hpp"

namespace fldsim::observers {

OrientationObserver::OrientationObserver(OrientationConfig config)
    : config_(config), stats_(config.theta_bins, config.phi_bins) {}

void OrientationObserver::begin(const System& system, const RunInfo& run, ResultSink& out) {
  skipped_ = !system.shape().anisotropic();
  if (skipped_) {
    std::clog << "orientation: skipped, the shape is isotropic (a single sphere has no director)\n";
    out.write_attribute("results/orientation", "skipped", "isotropic shape: no director to measure");
    return;
  }
  directors_.resize(system.size());
  const std::int64_t every = std::max<std::int64_t>(1, this->every());
  stats_.reserve(static_cast<std::size_t>(run.total_steps / every + 1));
}

void OrientationObserver::sample(const StepView& view, ResultSink& out) {
  if (skipped_) return;
  const System& s = view.system;
  directors_.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) directors_[i] = s.director(i);
  stats_.add_sample(directors_);
  const double t = s.time();
  const double theta_m = stats_.last_theta_m(), phi_m = stats_.last_phi_m();
  out.append_sample("timeseries/orientation/theta_m", s.step(), t, {}, &theta_m, "rad");
  out.append_sample("timeseries/orientation/phi_m", s.step(), t, {}, &phi_m, "rad");
  // Eigen is column-major; Q is symmetric so the row-major layout is the same.
  out.append_sample("timeseries/orientation/order_tensor", s.step(), t, {3, 3}, stats_.last_q().data(), "1");
}

void OrientationObserver::finish(const RunInfo& run, ResultSink& out) {
  if (skipped_ || stats_.samples() == 0) {
    if (!skipped_) out.write_attribute("results/orientation", "skipped", "no samples after start");
    return;
  }
  const std::string r = "results/orientation/";
  const double pi = std::numbers::pi;
  write_blocked(out, r + "theta_m", stats_.theta_m(), "rad", "mean angle from the vorticity axis z");
  write_blocked(out, r + "phi_m", stats_.phi_m(), "rad", "mean |phi|, phi from the gradient axis y");
  write_blocked(out, r + "delta_theta_m", stats_.theta_m(), "rad", "theta_m - 1 (isotropic theta_m = 1 rad)",
                1.0, -1.0);
  write_blocked(out, r + "delta_phi_m", stats_.phi_m(), "rad", "phi_m - pi/4 (isotropic phi_m = pi/4)", 1.0,
                -0.25 * pi);
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i)
    write_blocked(out, r + "S_" + axes[i] + axes[i], stats_.q(i, i), "1",
                  std::string("order parameter <3/2 n_") + axes[i] + "^2 - 1/2>");
  write_decorrelation_time(run, out);

  std::vector<double> edges(stats_.theta_bins() + 1);
  for (int b = 0; b <= stats_.theta_bins(); ++b) edges[b] = stats_.theta_edge(b);
  write_vector(out, r + "theta_edges", edges, "rad", "bin edges of P(theta)");
  write_vector(out, r + "P_theta", stats_.p_theta(), "1", "P(theta), isotropic = 1");
  write_vector(out, r + "P_theta_stderr", stats_.p_theta_stderr(), "1", "SE of P(theta) by blocking");
  edges.resize(stats_.phi_bins() + 1);
  for (int b = 0; b <= stats_.phi_bins(); ++b) edges[b] = stats_.phi_edge(b);
  write_vector(out, r + "phi_edges", edges, "rad", "bin edges of P(phi)");
  write_vector(out, r + "P_phi", stats_.p_phi(), "1", "P(phi), isotropic = 1");
  write_vector(out, r + "P_phi_stderr", stats_.p_phi_stderr(), "1", "SE of P(phi) by blocking");
  const auto map = stats_.p_theta_phi();
  out.write_array(
      r + "P_theta_phi",
      {static_cast<std::size_t>(stats_.theta_bins()), static_cast<std::size_t>(stats_.phi_bins())},
      map.data(), "1", "P(theta, phi), rows theta bins, columns phi bins, isotropic = 1");

  const Eigen::Matrix3d q = stats_.q_mean();
  out.write_array(r + "order_tensor", {3, 3}, q.data(), "1", "Q = <3/2 n n - 1/2 I> (symmetric)");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(q);
  const Eigen::Vector3d values = eig.eigenvalues();
  // Row k = eigenvector k (ascending eigenvalues); the sign of an eigenvector is arbitrary.
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> vectors = eig.eigenvectors().transpose();
  out.write_array(r + "order_eigenvalues", {3}, values.data(), "1", "eigenvalues of Q, ascending");
  out.write_array(r + "order_eigenvectors", {3, 3}, vectors.data(), "1",
                  "row k: unit eigenvector of Q for eigenvalue k (x, y, z)");
}

void OrientationObserver::write_decorrelation_time(const RunInfo& run, ResultSink& out) const {
  // The slowest of the averages above sets how long a run must be: the spacing of effectively
  // independent samples, s x (sample interval), s the blocking's statistical inefficiency. At
  // phi = 0.3, Pe = 1000 theta_m of fused dumbbells decorrelates over ~20 strains (issue 12), so
  // the paper's window (strains 150-500) holds ~17 independent samples.
  double s = 0.0;
  bool lower_bound = false;
  for (const BlockAverage* b :
       {&stats_.theta_m(), &stats_.phi_m(), &stats_.q(0, 0), &stats_.q(1, 1), &stats_.q(2, 2)}) {
    const double sb = b->correlation_samples();
    if (!std::isfinite(sb)) continue;
    s = std::max(s, sb);
    lower_bound = lower_bound || !b->converged();
  }
  const double spacing = double(std::max<std::int64_t>(1, every())) * run.dt / run.time_scale;
  const double window = double(stats_.samples()) * spacing;
  out.write_scalar("results/orientation/decorrelation_time", s * spacing, std::nan(""), run.time_unit,
                   "time between effectively independent samples of the slowest orientation average "
                   "(theta_m, phi_m, S_ii): statistical inefficiency n SE^2/var of its blocking times "
                   "the sample interval; the averaging window is " +
                       std::to_string(window) + " " + run.time_unit +
                       (lower_bound ? " (no plateau reached: a lower bound)" : ""));
}

std::vector<double> OrientationObserver::save_state() const {
  StateWriter w;
  stats_.save(w);
  return w.take();
}

void OrientationObserver::restore_state(const std::vector<double>& state) {
  StateReader r(state, "orientation");
  stats_.restore(r);
  r.finish();
}

}  // namespace fldsim::observers
