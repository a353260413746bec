#include "dynamics/TimeIntegrator.hpp"

#include <algorithm>

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

EulerMaruyama::EulerMaruyama(std::uint64_t seed, bool brownian, DriftScheme drift, std::size_t bodies)
    : seed_(seed), brownian_(brownian), drift_(drift), U_(6 * bodies), dU_(6 * bodies) {}

std::string EulerMaruyama::describe() const {
  if (!brownian_) return "Euler (no Brownian forces)";
  return drift_ == DriftScheme::Midpoint ? "Euler-Maruyama with midpoint thermal drift"
                                         : "Euler-Maruyama without thermal drift (drift: none)";
}

void EulerMaruyama::step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) {
  base_.save(s);
  ev.prepare(s, want_virial);
  if (brownian_)
    ev.draw_brownian(s, RandomStream(seed_, RandomPurpose::BodyNoise, std::uint64_t(s.step())), dt);
  ev.solve(s, brownian_);
  const bool midpoint = brownian_ && drift_ == DriftScheme::Midpoint;
  if (midpoint) {
    std::copy_n(ev.velocity(), U_.size(), U_.begin());
    at_stress_stage(StressStage::Start, s, ev, want_virial);
    move_from(s, base_, U_.data(), 0.5 * dt);
    ev.prepare(s, false);
    ev.solve(s, true);  // same F_B: the noise is frozen over the step
  }
  std::copy_n(ev.velocity(), U_.size(), U_.begin());
  std::copy_n(ev.relative_velocity(), dU_.size(), dU_.begin());
  at_stress_stage(midpoint ? StressStage::Final : StressStage::Start, s, ev, want_virial);
  move_from(s, base_, U_.data(), dt);
  record_displacement(s, U_.data(), dU_.data(), dt);
  wrap_into_box(s);
  s.set_step(s.step() + 1);
}

RungeKutta3::RungeKutta3(std::size_t bodies)
    : k1_(6 * bodies),
      k2_(6 * bodies),
      k3_(6 * bodies),
      r1_(6 * bodies),
      r2_(6 * bodies),
      r3_(6 * bodies),
      U_(6 * bodies),
      dU_(6 * bodies) {}

void RungeKutta3::step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) {
  const std::size_t n6 = U_.size();
  base_.save(s);
  auto stage = [&](std::vector<double>& k, std::vector<double>& r) {
    ev.prepare(s, want_virial);
    ev.solve(s, false);
    std::copy_n(ev.velocity(), n6, k.begin());
    std::copy_n(ev.relative_velocity(), n6, r.begin());
  };
  stage(k1_, r1_);
  at_stress_stage(StressStage::Start, s, ev, want_virial);
  move_from(s, base_, k1_.data(), 0.5 * dt);
  stage(k2_, r2_);
  correct_for_rotation(k2_, k1_, 0.5 * dt);
  for (std::size_t k = 0; k < n6; ++k) U_[k] = 2.0 * k2_[k] - k1_[k];
  move_from(s, base_, U_.data(), dt);
  stage(k3_, r3_);
  correct_for_rotation(k3_, U_, dt);
  for (std::size_t k = 0; k < n6; ++k) {
    U_[k] = (k1_[k] + 4.0 * k2_[k] + k3_[k]) / 6.0;
    dU_[k] = (r1_[k] + 4.0 * r2_[k] + r3_[k]) / 6.0;
  }
  move_from(s, base_, U_.data(), dt);
  record_displacement(s, U_.data(), dU_.data(), dt);
  wrap_into_box(s);
  s.set_step(s.step() + 1);
}

}  // namespace fldsim
