#include "dynamics/StressSampler.hpp"

#include <algorithm>

namespace fldsim {

StressSampler::StressSampler(std::size_t bodies, bool brownian, bool midpoint)
    : brownian_(brownian), midpoint_(brownian && midpoint), dU_step_(6 * bodies, 0.0) {}

void StressSampler::sample(StressStage stage, const System& s, VelocityEvaluator& ev) {
  HydroModel& hydro = ev.hydro();
  step_solve_ = ev.stats();
  if (stage == StressStage::Final) {
    if (midpoint_ && !probe_)
      pieces_.brownian = hydro.stresslet_sum(s, ev.pairs(), ev.relative_velocity()) - start_total_;
    return;
  }
  pieces_.interparticle = -ev.virial();
  pieces_.brownian.setZero();
  if (!brownian_) {
    pieces_.hydrodynamic = hydro.stresslet_sum(s, ev.pairs(), ev.relative_velocity());
    return;
  }
  // dU at x includes the Brownian velocity; it is also the warm start of the next solve.
  std::copy_n(ev.relative_velocity(), dU_step_.size(), dU_step_.begin());
  start_total_ = hydro.stresslet_sum(s, ev.pairs(), dU_step_.data());
  // The deterministic solve starts from zero, not from dU: dU's Brownian part, M F_B ~ (kT/dt)^1/2,
  // is the larger error (N 1000 spheres, phi 0.45, Pe 10, dt 1e-4: 6.8 CG iterations instead of 9.5).
  std::fill(ev.warm_start().begin(), ev.warm_start().end(), 0.0);
  ev.solve(s, false);
  pieces_.hydrodynamic = hydro.stresslet_sum(s, ev.pairs(), ev.relative_velocity());
  std::copy(dU_step_.begin(), dU_step_.end(), ev.warm_start().begin());
  if (probe_) pieces_.brownian = probe_->measure(s);
}

}  // namespace fldsim
