#include "run/RunExperiment.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <sstream>

#include "config/NumberText.hpp"
#include "config/YamlValidation.hpp"
#include "io/Checkpoint.hpp"
#include "io/Hdf5ResultSink.hpp"
#include "run/Provenance.hpp"
#include "run/RunUnits.hpp"
#include "run/Simulation.hpp"
#include "run/StopRequest.hpp"

namespace fldsim {
namespace {

// Runs of this many steps (frames of dt_max with dt: auto) or more report progress unless told
// not to (run.progress, -q): a silent run of minutes looks hung.
constexpr std::int64_t kProgressSteps = 1000;

// The experiment with a `progress` observer (default parameters) appended when run.progress
// asks for one and the file lists none.
Experiment with_default_progress(const Experiment& ex, const PluginRegistry& registry, bool quiet) {
  const bool listed = std::any_of(ex.observers.begin(), ex.observers.end(),
                                  [](const ObserverBlock& o) { return o.plugin.name == "progress"; });
  const bool long_run = ex.dt > 0 && std::llround(ex.duration / ex.dt) >= kProgressSteps;
  if (listed || quiet || ex.progress == "off" || (ex.progress == "auto" && !long_run)) return ex;
  Experiment out = ex;
  ConfigErrors errors(ex.file);
  PluginBlock block;
  block.kind = "observer";
  block.name = "progress";
  block.path = "run.progress";
  block.params = validate_params(YAML::Node(YAML::NodeType::Map),
                                 registry.find("observer", "progress").schema, block.path, errors);
  errors.throw_if_any();
  out.observers.push_back(ObserverBlock{std::move(block), 1, 0.0});
  return out;
}

std::string format_time(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << seconds << " s";
  return s.str();
}

// After SIGINT/SIGTERM: the observers write what they have, the state goes to the checkpoint,
// the result file is closed and renamed (readable, marked as interrupted). Exit 128 + signal.
int stop_early(Simulation& sim, Hdf5ResultSink& sink, const std::string& checkpoint_path,
               const Experiment& ex, int signal) {
  const std::int64_t step = sim.system().step(), total = sim.settings().total_steps;
  const Checkpoint state = sim.capture();  // before the observers summarise
  std::string incomplete;
  try {
    sim.finish();
  } catch (const Error& e) {
    incomplete = e.what();  // e.g. too few samples for a block average: the time series stay
  }
  std::ostringstream status;
  status << "interrupted by " << StopRequest::signal_name(signal) << " at step " << step << " of " << total;
  sink.write_attribute("/parameters", "run_status", status.str());
  write_checkpoint(checkpoint_path, state);
  sink.commit();
  // std::clog, not std::cerr: -q mutes std::cerr while the run lasts (main.cpp), and the
  // interruption, like an error, must still be said.
  std::clog << "fldsim: " << status.str() << "; results so far in " << sink.path() << ", state in "
            << checkpoint_path << "; continue with: fldsim run " << ex.file << " --resume " << checkpoint_path
            << " -o NEW.h5\n";
  if (!incomplete.empty()) std::clog << "fldsim: results so far lack some summaries: " << incomplete << "\n";
  std::clog.flush();
  return 128 + signal;
}

}  // namespace

int run_experiment(const Experiment& ex, const PluginRegistry& registry, const RunOptions& opt,
                   std::ostream& log) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::string output = !opt.output.empty() ? opt.output : ex.output;
  if (output.empty()) throw ConfigError(ex.file + ": output: no result file named (set `output:` or use -o)");
  // Opened first: it refuses an existing file before any Monte Carlo work is spent.
  Hdf5ResultSink sink(output, opt.overwrite);
  const UserTimeUnit unit = user_time_unit(ex, physics_of(ex));  // before begin() writes a frame
  sink.set_time_unit(unit.name, unit.scale);
  Experiment run = with_default_progress(ex, registry, opt.quiet);
  run.output = output;
  // From here on SIGINT/SIGTERM end the run after the current step, with everything kept.
  StopRequest::install();
  Checkpoint resume;
  if (!opt.resume.empty()) resume = read_checkpoint(opt.resume);
  std::unique_ptr<Simulation> sim;
  try {
    sim = Simulation::from_experiment(run, registry, sink, log, opt.resume.empty() ? nullptr : &resume,
                                      opt.resume);
  } catch (const Error& e) {
    // A signal during the set-up (a long Monte Carlo start ends at its next sweep): nothing was
    // run, so nothing to keep; exit as an interrupted run does (a sweep then starts the point anew).
    const int stop = StopRequest::signal();
    if (stop == 0) throw;
    std::clog << "fldsim: " << e.what() << "\n";
    std::clog.flush();
    return 128 + stop;
  }
  write_provenance(sink, ex, registry, *sim);

  const std::string checkpoint_path = output + ".checkpoint";
  const std::int64_t checkpoint_steps =
      ex.checkpoint_every > 0 ? std::max<std::int64_t>(1, std::llround(ex.checkpoint_every / ex.dt)) : 0;
  const auto loop0 = std::chrono::steady_clock::now();
  while (!sim->finished() && StopRequest::signal() == 0) {
    try {
      sim->step();
    } catch (const StepFailure& e) {
      // The step loop put the system back to the start of the failing frame: resumable there.
      write_checkpoint(checkpoint_path, sim->capture());
      log << "steps: " << sim->step_report() << "\n";
      throw Error(std::string(e.what()) + "; checkpoint at that time: " + checkpoint_path);
    }
    if (checkpoint_steps > 0 && sim->system().step() % checkpoint_steps == 0)
      write_checkpoint(checkpoint_path, sim->capture());
  }
  const int stop = StopRequest::signal();
  if (stop != 0) return stop_early(*sim, sink, checkpoint_path, ex, stop);
  sim->finish();
  write_checkpoint(checkpoint_path, sim->capture());
  sink.commit();

  const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const std::int64_t done = sim->steps_taken();
  const std::int64_t rebuilds = sim->rebuilds_taken();
  log << "done: " << done << " steps in " << format_time(loop_s) << " ("
      << (done > 0 ? std::to_string(1000.0 * loop_s / double(done)) : std::string("-")) << " ms/step, "
      << (done > 0 ? double(sim->cg_iterations_taken()) / double(done) : 0.0)
      << " CG iterations/step (all solves), " << rebuilds << " neighbour rebuilds"
      << (ex.skin_auto ? ", skin auto: now " + log_number(sim->neighbour_skin()) + " a" : std::string())
      << "); total " << format_time(wall_s) << "\n"
      << "steps: " << sim->step_report() << "\n"
      << "results: " << output << "   (fldsim summary " << output << "; /usr/bin/python3 tools/plot_run.py "
      << output << ")\ncheckpoint: " << checkpoint_path << "\n";
  // Frequent rebuilds mean the nodes' Brownian steps are comparable to the skin (the affine shear
  // is already allowed for): a larger skin trades more listed pairs for fewer rebuilds.
  if (!ex.skin_auto && done >= 100 && 2 * rebuilds > done)
    log << "hint: the neighbour list was rebuilt " << rebuilds << " times in " << done
        << " steps; the Brownian steps are large against run.skin = " << ex.skin
        << " a, and a larger skin (say " << 2.0 * ex.skin << ") may be faster\n";
  return 0;
}

}  // namespace fldsim
