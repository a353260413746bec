#include "dynamics/TimeIntegrator.hpp"

#include <algorithm>
#include <cmath>

#include "fldsim/hydro.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim {
namespace {
// Orientations move as q = exp(Theta) q0 (move_from). Runge-Kutta on the rotation vector Theta
// (Munthe-Kaas, BIT 38, 92 (1998)) needs the stage angular velocity omega as
// Theta' = dexp^-1_Theta(omega) = omega - (1/2) Theta x omega + O(Theta^2); dropping the
// commutator leaves the orientation second-order whenever the rotation axis changes (an
// out-of-plane Jeffery orbit, tests/dynamics/IntegratorOrderTest.cpp). Third order needs only
// the first commutator. Theta = h * rate (angular parts), k is corrected in place.
void correct_for_rotation(std::vector<double>& k, const std::vector<double>& rate, double h) {
  for (std::size_t i = 0; 6 * i < k.size(); ++i) {
    Eigen::Map<Vec3> w(k.data() + 6 * i + 3);
    const Vec3 theta = h * Eigen::Map<const Vec3>(rate.data() + 6 * i + 3);
    w -= 0.5 * theta.cross(w);
  }
}
}  // namespace

TimeIntegrator::TimeIntegrator(std::size_t bodies) : U_(6 * bodies, 0.0), dU_(6 * bodies, 0.0) {}

bool TimeIntegrator::all_finite(const double* v, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(v[k])) return false;
  return true;
}

void TimeIntegrator::begin_attempt(const System& s, VelocityEvaluator& ev, double dt) {
  base_.save(s);
  warm_ = ev.warm_start();  // same size every time: no allocation after the first
  dt_ = dt;
}

bool TimeIntegrator::take_velocity(const VelocityEvaluator& ev) {
  std::copy_n(ev.velocity(), U_.size(), U_.begin());
  std::copy_n(ev.relative_velocity(), dU_.size(), dU_.begin());
  return all_finite(U_.data(), U_.size());
}

void TimeIntegrator::finish_attempt(System& s, VelocityEvaluator& ev, StepAttempt& a) const {
  a.finite = all_finite(U_.data(), U_.size()) && std::isfinite(a.error);
  for (const Vec3& x : s.positions()) a.finite = a.finite && x.allFinite();
  if (a.finite) a.min_gap = ev.min_gap(s);
}

double TimeIntegrator::largest_error(const System& s, const double* a, const double* b, double h) const {
  const double radius = s.shape().bounding_radius();
  double worst = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    Vec6 d = Eigen::Map<const Vec6>(a + 6 * i);
    if (b) d -= Eigen::Map<const Vec6>(b + 6 * i);
    const Vec3 dv = d.head<3>(), dw = d.tail<3>();
    worst = std::max(worst, dv.squaredNorm() + radius * radius * dw.squaredNorm());
  }
  return h * std::sqrt(worst);
}

double TimeIntegrator::mean_square_node_step(const System& s) const {
  const auto& nodes = s.shape().nodes();
  double sum = 0.0, flow = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 dv(dU_[6 * i], dU_[6 * i + 1], dU_[6 * i + 2]);
    const Vec3 dw(dU_[6 * i + 3], dU_[6 * i + 4], dU_[6 * i + 5]);
    for (const Node& n : nodes) sum += (dv + dw.cross(s.orientations()[i] * n.position)).squaredNorm();
  }
  for (const Node& n : nodes) flow += n.radius * n.radius;
  const double gammadot = s.physics().shear_rate;
  const std::size_t count = s.size() * nodes.size();
  if (count == 0) return 0.0;
  return dt_ * dt_ * (sum / double(count) + (2.0 / 3.0) * gammadot * gammadot * flow / double(nodes.size()));
}

void TimeIntegrator::accept(System& s) {
  record_displacement(s, U_.data(), dU_.data(), dt_);
  wrap_into_box(s);
}

void TimeIntegrator::reject(System& s, VelocityEvaluator& ev) {
  base_.restore(s);
  std::copy(warm_.begin(), warm_.end(), ev.warm_start().begin());
}

void TimeIntegrator::step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) {
  attempt(s, ev, NoiseInterval{std::uint64_t(s.step()), dt, 0, 0, 0}, want_virial);
  accept(s);
  s.set_step(s.step() + 1);
}

EulerMaruyama::EulerMaruyama(std::uint64_t seed, bool brownian, DriftScheme drift, std::size_t bodies,
                             RejectedNoise rejected)
    : TimeIntegrator(bodies),
      seed_(seed),
      brownian_(brownian),
      drift_(drift),
      bridge_(rejected),
      U0_(6 * bodies) {}

std::string EulerMaruyama::describe() const {
  if (!brownian_) return "Euler (no Brownian forces)";
  return drift_ == DriftScheme::Midpoint ? "Euler-Maruyama with midpoint thermal drift"
                                         : "Euler-Maruyama without thermal drift (drift: none)";
}

StepAttempt EulerMaruyama::attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                                   bool want_virial) {
  const double dt = interval.duration();
  begin_attempt(s, ev, dt);
  StepAttempt a;
  ev.prepare(s, want_virial);
  if (brownian_) ev.draw_brownian(s, seed_, bridge_, interval);
  ev.solve(s, brownian_);
  const bool midpoint = brownian_ && drift_ == DriftScheme::Midpoint;
  if (midpoint) {
    std::copy_n(ev.velocity(), U0_.size(), U0_.begin());
    if (!all_finite(U0_.data(), U0_.size())) return StepAttempt{0.0, a.min_gap, false};
    at_stress_stage(StressStage::Start, s, ev, want_virial);
    move_from(s, base_, U0_.data(), 0.5 * dt);
    ev.prepare(s, false);
    ev.solve(s, true);  // same F_B: the noise is frozen over the step
  }
  if (!take_velocity(ev)) return StepAttempt{0.0, a.min_gap, false};
  at_stress_stage(midpoint ? StressStage::Final : StressStage::Start, s, ev, want_virial);
  move_from(s, base_, U_.data(), dt);
  if (midpoint) a.error = largest_error(s, U_.data(), U0_.data(), dt);
  finish_attempt(s, ev, a);
  return a;
}

bool averaged_noise_unbiased(const HydroModel& hydro, const System& s) {
  if (hydro.pair_range(s) != 0.0) return false;
  // A body's coupling R_tr = sum_n 6 pi mu a_n [p_n]x (isolated-node drags) vanishes when the
  // radius-weighted node centre is the body centre.
  Vec3 moment = Vec3::Zero();
  double scale = 0.0;
  for (const Node& n : s.shape().nodes()) {
    moment += n.radius * n.position;
    scale += n.radius * (n.radius + n.position.norm());
  }
  return moment.norm() <= 1e-12 * scale;
}

std::string leimkuhler_matthews_refusal(const HydroModel& hydro, const System& s) {
  if (averaged_noise_unbiased(hydro, s)) return "";
  return "leimkuhler_matthews needs a hydro model without pair terms (such as free_draining) and bodies "
         "without translation-rotation coupling (spheres, homonuclear dicolloids); hydro '" +
         hydro.plugin_name() + "' with " + s.shape().plugin_name() +
         " bodies is not: use euler_maruyama (the default)";
}

LeimkuhlerMatthews::LeimkuhlerMatthews(std::uint64_t seed, std::size_t bodies)
    : TimeIntegrator(bodies), seed_(seed) {}

std::string LeimkuhlerMatthews::describe() const {
  return "Leimkuhler-Matthews (Euler-Maruyama with the mean of consecutive steps' noise)";
}

StepAttempt LeimkuhlerMatthews::attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                                        bool want_virial) {
  const double dt = interval.duration();
  begin_attempt(s, ev, dt);
  StepAttempt a;
  ev.prepare(s, want_virial);
  if (interval.depth == 0 && interval.attempt == 0)
    ev.draw_brownian_with_next(s, seed_, interval);
  else
    ev.draw_brownian(s, seed_, bridge_, interval);  // a piece of a split step: plain Euler-Maruyama
  ev.solve(s, true);
  if (!take_velocity(ev)) return StepAttempt{0.0, a.min_gap, false};
  at_stress_stage(StressStage::Start, s, ev, want_virial);
  move_from(s, base_, U_.data(), dt);
  finish_attempt(s, ev, a);
  return a;
}

RungeKutta3::RungeKutta3(std::size_t bodies) : RungeKutta3(bodies, false, 0, RejectedNoise::Bridge) {}

RungeKutta3::RungeKutta3(std::uint64_t seed, std::size_t bodies, RejectedNoise rejected)
    : RungeKutta3(bodies, true, seed, rejected) {}

RungeKutta3::RungeKutta3(std::size_t bodies, bool brownian, std::uint64_t seed, RejectedNoise rejected)
    : TimeIntegrator(bodies),
      seed_(seed),
      brownian_(brownian),
      bridge_(rejected),
      k1_(6 * bodies),
      k2_(6 * bodies),
      k3_(6 * bodies),
      r1_(6 * bodies),
      r2_(6 * bodies),
      r3_(6 * bodies),
      e_(6 * bodies) {}

std::string RungeKutta3::describe() const {
  return brownian_ ? "explicit third-order Runge-Kutta (Kutta) with the Brownian force frozen over its stages"
                   : "explicit third-order Runge-Kutta (Kutta), deterministic";
}

StepAttempt RungeKutta3::attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                                 bool want_virial) {
  const double dt = interval.duration();
  const std::size_t n6 = U_.size();
  begin_attempt(s, ev, dt);
  StepAttempt a;
  auto stage = [&](std::vector<double>& k, std::vector<double>& r, bool at_start) {
    ev.prepare(s, want_virial);
    if (brownian_ && at_start) ev.draw_brownian(s, seed_, bridge_, interval);  // at x, kept for all stages
    ev.solve(s, brownian_);
    std::copy_n(ev.velocity(), n6, k.begin());
    std::copy_n(ev.relative_velocity(), n6, r.begin());
    return all_finite(k.data(), n6);
  };
  if (!stage(k1_, r1_, true)) return StepAttempt{0.0, a.min_gap, false};
  at_stress_stage(StressStage::Start, s, ev, want_virial);
  move_from(s, base_, k1_.data(), 0.5 * dt);
  if (!stage(k2_, r2_, false)) return StepAttempt{0.0, a.min_gap, false};
  correct_for_rotation(k2_, k1_, 0.5 * dt);
  for (std::size_t k = 0; k < n6; ++k) U_[k] = 2.0 * k2_[k] - k1_[k];
  move_from(s, base_, U_.data(), dt);
  if (!stage(k3_, r3_, false)) return StepAttempt{0.0, a.min_gap, false};
  correct_for_rotation(k3_, U_, dt);
  for (std::size_t k = 0; k < n6; ++k) {
    U_[k] = (k1_[k] + 4.0 * k2_[k] + k3_[k]) / 6.0;
    dU_[k] = (r1_[k] + 4.0 * r2_[k] + r3_[k]) / 6.0;
    e_[k] = (k1_[k] - 2.0 * k2_[k] + k3_[k]) / 6.0;  // third-order result minus the midpoint rule's
  }
  move_from(s, base_, U_.data(), dt);
  if (!brownian_) a.error = largest_error(s, e_.data(), nullptr, dt);
  finish_attempt(s, ev, a);
  return a;
}

}  // namespace fldsim
