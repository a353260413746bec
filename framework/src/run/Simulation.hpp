// A simulation: one system with its plugins, neighbour list, integrator and result sink,
// assembled once and stepped. Every front end builds this same object: the `fldsim` program
// (run/RunExperiment), the benchmarks (bench/step/BenchScene), the tests and the Python module.
//
//   Experiment --from_experiment--> SimulationParts + SimulationSettings --> Simulation
//
// A front end with its own bodies or wrapped plugins (a benchmark timing the hydro model, a
// cached start) builds the parts itself. The whole run state that a restart needs is captured
// and applied in one place (capture / apply), so new state (an adaptive time step) is added
// there and nowhere else.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/TimeIntegrator.hpp"
#include "dynamics/VelocityEvaluator.hpp"
#include "fldsim/force.hpp"
#include "fldsim/hydro.hpp"
#include "fldsim/observer.hpp"
#include "geometry/CellNeighbourList.hpp"
#include "io/Checkpoint.hpp"
#include "run/Experiment.hpp"
#include "run/StepLoop.hpp"
#include "run/ThreadPlan.hpp"
#include "run/ThreadTrial.hpp"

namespace fldsim {

// What the experiment names, built: the bodies placed, the plugins made.
struct SimulationParts {
  std::unique_ptr<System> system;  // bodies placed, nodes updated
  std::string hydro_name;          // for the log
  std::shared_ptr<HydroModel> hydro;
  // A second instance of the hydro model for the Brownian stress probe (run.brownian_stress:
  // random_difference), with the probe's solve tolerance; null when the run needs none.
  std::shared_ptr<HydroModel> probe_hydro;
  std::vector<std::shared_ptr<ForceLaw>> forces;
  std::vector<std::shared_ptr<Observer>> observers;  // schedules set
  // Key of each observer's state in a checkpoint, "observers[2].stress" (position and plugin).
  std::vector<std::string> observer_keys;
};

// Refuses an observer whose needs the hydro model cannot meet (a `stress` observer with a model
// that provides no stresslets) with a ConfigError "file:line:col: observers[i].plugin: ...".
// observers[i] is the plugin of ex.observers[i]. `fldsim check` makes it, and a run makes it
// before placing its bodies (a Monte Carlo start can take minutes).
void check_observer_needs(const Experiment& ex, const HydroModel& hydro,
                          const std::vector<std::shared_ptr<Observer>>& observers);

// How the parts are stepped.
struct SimulationSettings {
  double dt = 0.0;                  // the frame, internal time units (a^2/D0); dt_max with dt: auto
  std::int64_t total_steps = 0;     // the run ends at this step (resumed runs count from 0 too)
  std::string integrator = "auto";  // auto | euler_maruyama | rk3 | leimkuhler_matthews
  std::string drift = "midpoint";   // midpoint | none
  // integrator auto may take Leimkuhler-Matthews (where the hydro model and shape allow it): fixed
  // steps, no run.refine, and neither run.drift nor a midpoint Brownian stress asked for.
  bool auto_may_average_noise = false;
  double skin = 0.3;                 // neighbour-list skin, a
  bool skin_auto = false;            // run.skin: auto: rescaled at every rebuild (CellNeighbourList)
  double probe_delta = 1e-4;         // run.brownian_stress_delta (a), with parts.probe_hydro
  std::uint64_t seed = 42;           // Brownian noise
  std::string time_unit = "a^2/D0";  // the user's time unit (RunInfo)
  double time_scale = 1.0;           // internal time per user time unit
  double user_dt = 0.0;              // dt in the user's unit, for the log
  std::string output_path;
  std::string experiment_yaml;  // resolved experiment, stored in checkpoints
  // Step control (docs/time_steps.md): fixed or adaptive (dt: auto) steps inside frames of `dt`,
  // and the stability guard. The constructor sets control.frame = dt and control.order.
  StepControlSettings control;
  StepGuard guard;
  ThreadPlan threads;  // already applied (omp_set_num_threads) by the caller
};

class Simulation {
 public:
  // Sets up the neighbour list, configures the hydro model for what the observers need, makes
  // the integrator and calls every observer's begin(). The sink must outlive the simulation.
  // The log gets the set-up lines (integrator, threads, what is skipped) and thread-trial lines.
  Simulation(SimulationParts parts, SimulationSettings settings, ResultSink& sink, std::ostream& log);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // The whole assembly from an experiment: thread plan, system, plugins, start configuration
  // (Monte Carlo, listed or from a file), or, with `resume`, the checkpoint's state, which is
  // then applied (solver warm start and observer state too) before the first step.
  static std::unique_ptr<Simulation> from_experiment(const Experiment& ex, const PluginRegistry& registry,
                                                     ResultSink& sink, std::ostream& log,
                                                     const Checkpoint* resume = nullptr,
                                                     const std::string& resume_name = "the checkpoint");

  // One time step; due observers sample into the sink.
  void step();
  bool finished() const { return system_->step() >= settings_.total_steps; }
  // Steps until finished().
  void run();
  // The step statistics, one line for the log.
  std::string step_report() const;
  // Every observer writes its steady-state results, and the step statistics go to the sink
  // (once; later calls do nothing).
  void finish();

  // Everything a bit-exact restart needs, and its inverse (with the step control's state). apply() may be
  // called at any time after construction (the neighbour list follows the new positions).
  Checkpoint capture() const;
  void apply(const Checkpoint& c, const std::string& source = "the checkpoint");

  System& system() { return *system_; }
  const System& system() const { return *system_; }
  const SimulationSettings& settings() const { return settings_; }
  const RunInfo& run_info() const { return info_; }
  geometry::CellNeighbourList& neighbours() { return list_; }
  VelocityEvaluator& evaluator() { return *evaluator_; }
  const TimeIntegrator& integrator() const { return *integrator_; }
  const std::shared_ptr<HydroModel>& hydro() const { return parts_.hydro; }
  const std::vector<std::shared_ptr<ForceLaw>>& forces() const { return parts_.forces; }
  std::vector<std::shared_ptr<Observer>>& observers() { return parts_.observers; }
  double pair_range() const { return range_; }
  // Work the scene does not need and is skipped (for the log).
  const std::vector<std::string>& skipped() const { return skipped_; }
  const StepLoop& step_loop() const { return *steps_; }

  // Since the first step() call: steps taken, CG iterations (all solves), neighbour rebuilds.
  std::int64_t steps_taken() const;
  std::int64_t cg_iterations_taken() const;
  std::int64_t rebuilds_taken() const;
  // The neighbour list's skin now (a; it changes with run.skin: auto).
  double neighbour_skin() const;

 private:
  void start_stepping();  // thread trial and counters, at the first step()
  void log_notes();       // the components' RunNotes lines since the last step, to the log

  SimulationParts parts_;
  SimulationSettings settings_;
  ResultSink& sink_;
  std::ostream& log_;
  System* system_;  // parts_.system
  geometry::CellNeighbourList list_;
  double range_ = 0.0;
  std::vector<std::string> skipped_;
  bool brownian_ = false;
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<VelocityEvaluator> evaluator_;
  RunInfo info_;
  std::unique_ptr<BrownianStressProbe> probe_;  // before steps_, which points to it
  std::unique_ptr<StepLoop> steps_;
  std::optional<ThreadTrial> trial_;
  std::int64_t first_step_ = 0, first_iterations_ = 0, first_rebuilds_ = 0;
  bool finished_observers_ = false;
  std::vector<std::pair<std::string, RunNotes*>> notes_;  // label for the log, the component's notes
};

}  // namespace fldsim
