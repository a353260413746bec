// A benchmark scene: N bodies of one shape at volume fraction phi, made with the real plugins
// (PluginRegistry over the build's plugin directory), started from a quick hard-body
// configuration, with FLD (or another hydro plugin, wrapped in TimedHydro), the paper's repulsion,
// Euler-Maruyama with the midpoint drift, and optional observers: the parts of the same
// Simulation that `fldsim run` steps, so the benchmarks time the step users run.
//
// Quick start (a full hard-body MC is too slow for N = 27000 at phi = 0.5): spheres whose N is a
// cube start on a simple cubic lattice at the target density when its spacing leaves a gap, any
// other scene from initialise_monte_carlo with a fixed number of sweeps at the target; then a few
// MC sweeps. Configurations are cached in a directory (bench/results/configs) so that every
// benchmark of a scene starts from the same bodies.
#pragma once

#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "TimedHydro.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/results.hpp"
#include "plugins/PluginRegistry.hpp"
#include "run/Simulation.hpp"

namespace fldsim::bench {

struct SceneSpec {
  std::string shape = "sphere";  // sphere | dicolloid (a = b = 1, centre distance c)
  double c = 0.2;
  std::size_t count = 1000;
  double phi = 0.3;
  double peclet = 10.0;  // gammadot in units of D0/a^2 (internal: shear rate = Pe)
  bool brownian = true;  // kT = 1, else kT = 0 at the same shear rate and dt
  std::string hydro = "fld";
  std::string hydro_yaml = "{}";
  double repulsion = 10.0;  // C_p*, paper unit
  double dt_paper = 1e-3;   // in 1/gammadot for Pe >= 1, a^2/D0 otherwise (the paper's convention)
  double dt = 0.0;          // internal time step (a^2/D0); 0 = from dt_paper
  double skin = 0.3;
  bool skin_auto = false;  // run.skin: auto
  int mc_sweeps = 10;      // MC sweeps at the target density after the quick start
  bool lattice = true;     // spheres: lattice start when possible, else always MC compression
  std::string cache_dir;   // where configurations are cached ("" = no cache)
  std::uint64_t seed = 42;
  // Order of the bodies' indices (positions and orientations permuted): "" as built, "shuffle"
  // random (the layout a long run drifts to as bodies mix), "cells" along a Z-order curve of cells of
  // about 2 radii (neighbours close in memory).
  std::string order;
};

// One observer plugin with its schedule, as in an experiment's `observers:` list.
struct ObserverSpec {
  std::string plugin;
  std::int64_t every = 1;
  std::string yaml = "{}";
};

// A ResultSink that keeps nothing: benchmarks time the observers' work, not file output.
class DiscardingSink : public ResultSink {
 public:
  void write_scalar(const std::string&, double, double, const std::string&, const std::string&) override {}
  void write_array(const std::string&, const std::vector<std::size_t>&, const double*, const std::string&,
                   const std::string&) override {}
  void append_sample(const std::string&, std::int64_t, double, const std::vector<std::size_t>&, const double*,
                     const std::string&) override {}
  void write_attribute(const std::string&, const std::string&, const std::string&) override {}
};

const PluginRegistry& registry();
// Parameters of plugin (kind, name) from a YAML map, checked against its schema.
Params plugin_params(const std::string& kind, const std::string& name, const std::string& yaml);

class BenchScene {
 public:
  BenchScene(const SceneSpec& spec, const std::vector<ObserverSpec>& observers);

  // One time step exactly as `fldsim run` takes it (Simulation::step).
  void step() { simulation_->step(); }

  Simulation& simulation() { return *simulation_; }
  System& system() { return simulation_->system(); }
  geometry::CellNeighbourList& neighbours() { return simulation_->neighbours(); }
  VelocityEvaluator& evaluator() { return simulation_->evaluator(); }
  TimedHydro& hydro() { return *timed_; }
  std::shared_ptr<HydroModel> hydro_plugin() { return hydro_; }
  const std::vector<std::shared_ptr<ForceLaw>>& forces() const { return simulation_->forces(); }
  std::vector<std::shared_ptr<Observer>>& observers() { return simulation_->observers(); }
  const RunInfo& run_info() const { return simulation_->run_info(); }
  double dt() const { return simulation_->settings().dt; }
  const std::vector<std::string>& skipped() const { return simulation_->skipped(); }
  // The run log's `note:` lines so far (RunNotes: a preconditioner that fell back, and when it works
  // again); the rest of the log (set-up lines) is not part of a benchmark's output.
  std::vector<std::string> notes() const {
    std::vector<std::string> out;
    std::istringstream in(log_.str());
    for (std::string line; std::getline(in, line);)
      if (line.rfind("note: ", 0) == 0) out.push_back(line);
    return out;
  }
  const std::string& start_note() const { return start_note_; }
  // Time spent in the observers' sample calls, seconds, since construction (the stress pieces
  // are computed inside the step: stresslets and the extra solve count as hydro time).
  double observer_seconds() const { return simulation_->step_loop().observer_seconds(); }

 private:
  void start_configuration(const SceneSpec& spec, System& sys);

  std::shared_ptr<HydroModel> hydro_;
  std::shared_ptr<TimedHydro> timed_;
  DiscardingSink sink_;
  std::ostringstream log_;  // set-up lines (not printed) and notes
  std::unique_ptr<Simulation> simulation_;
  std::string start_note_;
};

}  // namespace fldsim::bench
