// One time step of a run as run_experiment takes it: the due observers decide whether the stress
// pieces are computed (stresslets, virial, the extra deterministic solve, the Brownian estimate),
// the integrator steps, a non-finite velocity stops the run, and the due observers sample.
// Simulation and the step benchmarks both use it, so the benchmarks time the step users run.
#pragma once

#include <memory>
#include <vector>

#include "dynamics/StressSampler.hpp"
#include "dynamics/TimeIntegrator.hpp"
#include "dynamics/VelocityEvaluator.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/results.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim {

class StepLoop {
 public:
  // brownian: the run has thermal noise; midpoint: the integrator has the midpoint drift stage
  // (needed for the Brownian stress). The loop installs the stress hook on the integrator.
  StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
           const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
           const RunInfo& info, bool brownian, bool midpoint);
  StepLoop(const StepLoop&) = delete;
  StepLoop& operator=(const StepLoop&) = delete;

  // Advance one step of info.dt; due observers sample into sink.
  void step(ResultSink& sink);
  // The last step's own solve (on stress steps of a Brownian run, not the extra stress solve).
  const SolveStats& last_solve() const { return last_solve_; }
  // Seconds spent in the observers' sample calls since construction.
  double observer_seconds() const { return observer_seconds_; }

 private:
  System& sys_;
  TimeIntegrator& integrator_;
  VelocityEvaluator& evaluator_;
  const geometry::CellNeighbourList& list_;
  std::vector<std::shared_ptr<Observer>>& observers_;
  const RunInfo& info_;
  bool brownian_;
  StressSampler stress_;
  SolveStats last_solve_;
  double observer_seconds_ = 0.0;
};

}  // namespace fldsim
