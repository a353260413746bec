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
  ev.solve(s, false);
  pieces_.hydrodynamic = hydro.stresslet_sum(s, ev.pairs(), ev.relative_velocity());
  std::copy(dU_step_.begin(), dU_step_.end(), ev.warm_start().begin());
  if (probe_) pieces_.brownian = probe_->measure(s);
}

}  // namespace fldsim
