#include "dynamics/StressSampler.hpp"

#include <algorithm>
#include <cmath>

namespace fldsim {

StressSampler::StressSampler(std::size_t bodies, bool brownian, bool midpoint)
    : brownian_(brownian),
      midpoint_(brownian && midpoint),
      dU_step_(6 * bodies, 0.0),
      deterministic_(6 * bodies, 0.0) {}

void StressSampler::restore_deterministic(const std::vector<double>& dU) {
  // Only a start: one of another size or with a non-finite value (a corrupt checkpoint) is dropped
  // and the solve starts from zero, instead of feeding NaN to CG.
  if (dU.size() != deterministic_.size()) return;
  if (!std::all_of(dU.begin(), dU.end(), [](double v) { return std::isfinite(v); })) return;
  std::copy(dU.begin(), dU.end(), deterministic_.begin());
}

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
  // The deterministic solve starts from the last sample's deterministic solution, not from dU:
  // dU's Brownian part, M F_B ~ (kT/dt)^1/2, is the larger error, and dU_det moves little between
  // samples (N 1000 spheres, phi 0.45, Pe 10, dt 1e-4, a sample every step: CG iterations per
  // sample 9.5 from dU, 6.8 from zero, 5.2 from the last sample; bench/README.md).
  std::copy(deterministic_.begin(), deterministic_.end(), ev.warm_start().begin());
  ev.solve(s, false);
  std::copy_n(ev.relative_velocity(), deterministic_.size(), deterministic_.begin());
  pieces_.hydrodynamic = hydro.stresslet_sum(s, ev.pairs(), ev.relative_velocity());
  std::copy(dU_step_.begin(), dU_step_.end(), ev.warm_start().begin());
  if (probe_) pieces_.brownian = probe_->measure(s);
}

}  // namespace fldsim
