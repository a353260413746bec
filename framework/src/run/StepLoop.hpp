// One frame of a run as run_experiment takes it, the whole step in one screen:
//   the due observers decide whether the stress pieces are computed (stresslets, virial, the
//   extra deterministic solve, the Brownian estimate: only on the attempt that ends the frame);
//   StepControl hands out pieces of the frame (the fixed step, or adaptive steps), each an
//   attempt of the integrator that is accepted or rejected:
//     - stability guard, in every mode: a non-finite velocity or position, a failed solve, or a
//       node overlap deeper than run.max_overlap (and by more than max_overlap / 10 deeper than
//       at the start of the attempt: StepGuard);
//     - adaptive mode: the embedded error estimate above run.reject_at x run.tolerance (the
//       controller keeps it near the tolerance; StepControl.hpp says why it rejects so rarely);
//   a rejected attempt is undone and retried on a shorter piece of the same Brownian path
//   (BrownianBridge.hpp); then the due observers sample at the frame's end.
// A run that cannot go on (a retry would be shorter than run.dt_min) is put back to the start
// of the frame and StepFailure is thrown, so the caller can write a checkpoint there.
// Simulation and the step benchmarks both use it, so the benchmarks time the step users run.
#pragma once

#include <iosfwd>
#include <memory>
#include <vector>

#include "dynamics/StepControl.hpp"
#include "dynamics/StepStatistics.hpp"
#include "dynamics/StressSampler.hpp"
#include "dynamics/TimeIntegrator.hpp"
#include "dynamics/VelocityEvaluator.hpp"
#include "fldsim/error.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/results.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim {

// The run cannot continue; the system is at the start of the frame that failed.
class StepFailure : public Error {
 public:
  using Error::Error;
};

struct StepGuard {
  double max_overlap = 0.1;  // a: reject a step that leaves a node overlap deeper than this
  // ... and deeper than at its start by more than max_overlap / 10. A step is rejected for what
  // it jumped, not for where the path goes: refining a rejected step follows the same Brownian
  // path (the bridge), and where the exact path itself goes beyond max_overlap (a pair left
  // near it by earlier long steps) a rule without this margin rejected every retry down to
  // run.dt_min and stopped the run (free-draining spheres, phi 0.3, N 1000, dt 4e-4 to 1.6e-3).
  double deepening() const { return 0.1 * max_overlap; }
};

class StepLoop {
 public:
  // brownian: the run has thermal noise; midpoint: the integrator has the midpoint drift stage
  // (needed for the Brownian stress). The loop installs the stress hook on the integrator.
  // control.frame must equal info.dt. log (may be null) gets overlap warnings.
  StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
           const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
           const RunInfo& info, bool brownian, bool midpoint, const StepControlSettings& control,
           const StepGuard& guard = {}, std::ostream* log = nullptr);
  // The fixed step info.dt with the default guard (benchmarks, tests).
  StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
           const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
           const RunInfo& info, bool brownian, bool midpoint);
  StepLoop(const StepLoop&) = delete;
  StepLoop& operator=(const StepLoop&) = delete;

  // The Brownian stress from this probe instead of the midpoint difference (not owned).
  void use_brownian_stress_probe(BrownianStressProbe* probe) { stress_.use_probe(probe); }

  // Advance one frame of info.dt; due observers sample into sink.
  void step(ResultSink& sink);
  // The last accepted step's own solve (on stress steps of a Brownian run, not the extra solve).
  const SolveStats& last_solve() const { return last_solve_; }
  // Seconds spent in the observers' sample calls since construction.
  double observer_seconds() const { return observer_seconds_; }
  const StepStatistics& statistics() const { return stats_; }
  const StepControl& control() const { return control_; }
  std::int64_t overlap_frames() const { return overlap_frames_; }

  // Adaptive state (the proposal) and statistics, for checkpoints. A frame's end leaves no
  // bridged noise pending: every frame is its own base interval of the Brownian path.
  std::vector<double> save_state() const;
  void restore_state(const std::vector<double>& state);
  // The stress sampler's CG start (StressSampler::deterministic), for checkpoints.
  const std::vector<double>& stress_start() const { return stress_.deterministic(); }
  void restore_stress_start(const std::vector<double>& dU) { stress_.restore_deterministic(dU); }

 private:
  void warn_overlap(double gap, const NodePair* pair);
  double gap_measure(double dt);

  System& sys_;
  TimeIntegrator& integrator_;
  VelocityEvaluator& evaluator_;
  const geometry::CellNeighbourList& list_;
  std::vector<std::shared_ptr<Observer>>& observers_;
  const RunInfo& info_;
  bool brownian_;
  StressSampler stress_;
  StepControl control_;
  StepGuard guard_;
  std::ostream* log_;
  StepStatistics stats_;
  SolveStats last_solve_;
  double observer_seconds_ = 0.0;
  double gap_ = 0.0;  // smallest gap of the current configuration
  bool gap_known_ = false;
  double deepest_warned_ = 0.0;
  std::int64_t overlap_frames_ = 0;
  // Start of the frame, restored when the run cannot go on.
  BodySnapshot frame_start_;
  std::vector<Vec3> displacement_, nonaffine_;
  std::vector<double> warm_start_;
};

}  // namespace fldsim
