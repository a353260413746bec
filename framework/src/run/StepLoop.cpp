#include "run/StepLoop.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "fldsim/error.hpp"

namespace fldsim {

StepLoop::StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
                   const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
                   const RunInfo& info, bool brownian, bool midpoint)
    : sys_(sys),
      integrator_(integrator),
      evaluator_(evaluator),
      list_(list),
      observers_(observers),
      info_(info),
      brownian_(brownian),
      stress_(sys.size(), brownian, midpoint) {
  integrator_.set_stress_stage(
      [this](StressStage stage, const System& s, VelocityEvaluator& ev) { stress_.sample(stage, s, ev); });
}

void StepLoop::step(ResultSink& sink) {
  // Which observers sample after this step; only then is their extra work done.
  const std::int64_t next = sys_.step() + 1;
  const double next_time = sys_.time() + info_.dt;
  bool any_due = false, stress_due = false;
  for (const auto& o : observers_) {
    const bool due = o->needs().every_step || o->due(next, next_time);
    any_due = any_due || due;
    stress_due = stress_due || (due && o->needs().stress);
  }
  integrator_.step(sys_, evaluator_, info_.dt, stress_due);
  // On stress steps of a Brownian run the sampler solved once more; report the step's own solve.
  last_solve_ = stress_due && brownian_ ? stress_.step_solve() : evaluator_.stats();
  const double* U = integrator_.step_velocity();
  for (std::size_t k = 0; k < 6 * sys_.size(); ++k)
    if (!std::isfinite(U[k]))
      throw Error("step " + std::to_string(sys_.step()) + ": velocity of body " + std::to_string(k / 6) +
                  " is not finite (overlap or time step too large? min gap " + std::to_string(list_.min_gap(sys_)) +
                  " a)");
  if (!any_due) return;
  const auto t0 = std::chrono::steady_clock::now();
  const StepView view{sys_,         evaluator_.pairs(), info_,      U, evaluator_.force(),
                      stress_due ? &stress_.pieces() : nullptr, last_solve_, list_.min_gap(sys_)};
  for (auto& o : observers_)
    if (o->needs().every_step || o->due(sys_.step(), sys_.time())) o->sample(view, sink);
  observer_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace fldsim
