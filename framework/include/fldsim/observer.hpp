// An observer samples the run when due (`every` steps, from time `start` on) and writes its
// results at the end. It declares what it needs so that nothing else is computed.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "fldsim/hydro.hpp"
#include "fldsim/neighbours.hpp"
#include "fldsim/plugin_base.hpp"
#include "fldsim/results.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

struct ObserverNeeds {
  bool stress = false;      // stress pieces in the StepView (hydro stresslets, virials)
  bool every_step = false;  // sample() every step regardless of `every` (e.g. progress)
};

// Run-wide facts an observer may want (set once before the run).
struct RunInfo {
  std::int64_t total_steps = 0;
  double dt = 0.0;                   // internal time units (a^2/D0)
  std::string time_unit = "a^2/D0";  // the unit the user's times were given in
  double time_scale = 1.0;           // internal time per user time unit
  std::string output_path;
  std::uint64_t seed = 0;
};

// Bulk stress pieces (sums over the box; divide by the volume for a stress), available when
// ObserverNeeds::stress was requested.
struct StressPieces {
  Eigen::Matrix3d hydrodynamic = Eigen::Matrix3d::Zero();   // sum of hydrodynamic stresslets
  Eigen::Matrix3d interparticle = Eigen::Matrix3d::Zero();  // -sum R (x) f_j (molecular virial, force.hpp)
  Eigen::Matrix3d brownian = Eigen::Matrix3d::Zero();       // Brownian stress (drift term), if computed
};

struct StepView {
  const System& system;
  const NodePairList& pairs;
  const RunInfo& run;
  const double* velocity;      // 6N: total U and Omega of each body (including U_inf)
  const double* force;         // 6N: interparticle forces and torques F_P
  const StressPieces* stress;  // null unless requested
  SolveStats solve;
  double min_gap;  // smallest node surface gap between different bodies in the list
};

class FLDSIM_VISIBLE Observer : public Component {
 public:
  virtual ObserverNeeds needs() const { return {}; }
  // Called once before the first step (after the initial configuration is known).
  virtual void begin(const System& system, const RunInfo& run, ResultSink& out) {
    (void)system;
    (void)run;
    (void)out;
  }
  virtual void sample(const StepView& view, ResultSink& out) = 0;
  // Called once after the last step: write steady-state averages and errors.
  virtual void finish(const RunInfo& run, ResultSink& out) {
    (void)run;
    (void)out;
  }

  // Exact restart: the accumulated state (running sums, histograms, sample series, reference
  // positions) as doubles, stored in the checkpoint and handed back on --resume after begin().
  // Counts are exact in a double up to 2^53. Observers that keep nothing between samples keep
  // the defaults. restore_state throws fldsim::Error if the state does not fit the observer's
  // parameters (e.g. a different bin count).
  virtual std::vector<double> save_state() const { return {}; }
  virtual void restore_state(const std::vector<double>& state) { (void)state; }

  // Sampling schedule, from the standard `every` and `start` keys the core adds to every
  // observer's parameters.
  std::int64_t every() const { return every_; }
  double start() const { return start_; }  // internal time units
  void set_schedule(std::int64_t every, double start) {
    every_ = every;
    start_ = start;
  }
  bool due(std::int64_t step, double time) const {
    return time + 1e-12 >= start_ && every_ > 0 && step % every_ == 0;
  }

 private:
  std::int64_t every_ = 1;
  double start_ = 0.0;
};

}  // namespace fldsim
