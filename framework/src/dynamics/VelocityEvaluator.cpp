#include "dynamics/VelocityEvaluator.hpp"

#include <algorithm>

namespace fldsim {

VelocityEvaluator::VelocityEvaluator(std::shared_ptr<HydroModel> hydro,
                                     std::vector<std::shared_ptr<ForceLaw>> forces, CellNeighbourList& pairs,
                                     std::size_t bodies)
    : hydro_(std::move(hydro)),
      forces_(std::move(forces)),
      list_(pairs),
      FP_(6 * bodies, 0.0),
      FB_(6 * bodies, 0.0),
      FB_next_(6 * bodies, 0.0),
      F_(6 * bodies, 0.0),
      dU_(6 * bodies, 0.0),
      U_(6 * bodies, 0.0) {}

void VelocityEvaluator::prepare(System& s, bool want_virial) {
  list_.update(s);
  std::fill(FP_.begin(), FP_.end(), 0.0);
  virial_.setZero();
  for (const auto& f : forces_) f->add(s, list_.pairs(), FP_.data(), want_virial ? &virial_ : nullptr);
  hydro_->assemble(s, list_.pairs());
}

void VelocityEvaluator::draw_brownian(const System& s, const RandomStream& noise, double dt) {
  hydro_->brownian_force(s, list_.pairs(), noise, dt, FB_.data());
}

void VelocityEvaluator::draw_brownian(const System& s, std::uint64_t seed, const BrownianBridge& bridge,
                                      const NoiseInterval& interval) {
  const double h = interval.duration();
  const int n = bridge.terms(interval, terms_);
  auto stream = [&](std::uint32_t stage) {
    return RandomStream(seed, RandomPurpose::BodyNoise, interval.base, stage);
  };
  if (n == 1) {  // coefficient sqrt(h): the plain draw
    hydro_->brownian_force(s, list_.pairs(), stream(terms_[0].stage), h, FB_.data());
    return;
  }
  // F_B is linear in the normals, so the model draws the piece's increment W = sum_j c_j xi_j
  // once, as the combination sum_j (c_j / sqrt(h)) xi_j of unit variance that it scales by
  // sqrt(2 kT / h) like any draw: one pass over bodies and pairs at any depth (d + 1 passes,
  // one per stage, before 7 December 2026: 7-15 % of an adaptive step at N = 1000).
  combination_.count = n;
  const double root_h = std::sqrt(h);
  for (int j = 0; j < n; ++j) {
    combination_.stage[std::size_t(j)] = terms_[std::size_t(j)].stage;
    combination_.coefficient[std::size_t(j)] = terms_[std::size_t(j)].coefficient / root_h;
  }
  hydro_->brownian_force(s, list_.pairs(), stream(0).combined(combination_), h, FB_.data());
}

void VelocityEvaluator::draw_brownian_with_next(const System& s, std::uint64_t seed,
                                                const NoiseInterval& interval) {
  const double h = interval.duration();
  const RandomStream now(seed, RandomPurpose::BodyNoise, interval.base, 0);
  const RandomStream next(seed, RandomPurpose::BodyNoise, interval.base + 1, 0);
  hydro_->brownian_force(s, list_.pairs(), now, h, FB_.data());
  hydro_->brownian_force(s, list_.pairs(), next, h, FB_next_.data());
  for (std::size_t k = 0; k < FB_.size(); ++k) FB_[k] = 0.5 * (FB_[k] + FB_next_[k]);
}

double VelocityEvaluator::min_gap(const System& s) {
  list_.update(s);
  return list_.min_gap(s);
}

void VelocityEvaluator::solve(const System& s, bool with_brownian) {
  const std::size_t n6 = F_.size();
  for (std::size_t k = 0; k < n6; ++k) F_[k] = FP_[k] + (with_brownian ? FB_[k] : 0.0);
  hydro_->solve(s, F_.data(), dU_.data());
  total_iterations_ += hydro_->last_solve().iterations;
  const Vec3 w = s.flow_vorticity();
  const auto& x = s.positions();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 u = s.flow_velocity(x[i]);
    for (int k = 0; k < 3; ++k) {
      U_[6 * i + k] = u[k] + dU_[6 * i + k];
      U_[6 * i + 3 + k] = w[k] + dU_[6 * i + 3 + k];
    }
  }
}

}  // namespace fldsim
