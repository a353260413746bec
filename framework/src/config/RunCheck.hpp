// Everything `fldsim run` would find wrong with an experiment, found before any work is done
// or any file is created: the plugins constructed and their observers begun on a stand-in
// system, the scene's feasibility (volume fraction against what the Monte Carlo start can
// pack, bodies and pair range against the box), resources (step count, memory against this
// machine), the start configuration (listed positions, an init file), the output files (an
// existing result or checkpoint is never replaced without --overwrite) and, for --resume, the
// checkpoint and its compatibility with the experiment. `fldsim check` runs exactly this, and
// `fldsim run` runs it first. All problems are reported together as one ConfigError, one line
// each, naming file:line:col and key, or the command-line option.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "config/ConfigErrors.hpp"
#include "plugins/PluginRegistry.hpp"
#include "run/Experiment.hpp"

namespace fldsim {

struct RunTargets {
  std::string output;  // -o; empty = the experiment's `output`
  bool overwrite = false;
  std::string resume;  // --resume CHECKPOINT
};

// The highest true volume fraction the hard-body Monte Carlo start is asked to reach: the
// compression slows sharply as phi approaches random close packing (0.64 for spheres) and
// runs out of its sweep budget at 0.55 for the paper's dicolloids (issue 14).
constexpr double kMonteCarloPhiLimit = 0.55;
// A run's step count is bounded so that the count, the times and the observers' sample
// buffers stay far inside their types; 1e9 steps is weeks of computing for one body.
constexpr double kMaxSteps = 1e9;

struct RunCheckReport {
  std::vector<std::string> warnings;  // e.g. a used plugin shadows another; for the log
  std::string summary;                // "64 x dicolloid, phi = 0.3, 20000 steps, ..."
  // The scene's size, for cost estimates (`fldsim sweep --dry-run`).
  std::int64_t steps = 0;        // frames: run.duration / run.dt (dt_max with dt: auto)
  std::int64_t nodes = 0;        // spheres of all bodies
  double volume_fraction = 0.0;  // true phi of the box
  std::int64_t resume_step = 0;  // the step of the checkpoint to resume (RunTargets::resume), else 0
};

// Throws ConfigError listing every problem (exit code 2).
RunCheckReport check_run(const Experiment& ex, const PluginRegistry& registry, const RunTargets& targets);

// Compares the experiment a checkpoint was written by with this one; each difference that
// would change what is simulated or accumulated is reported at the current value's location.
// Only run.duration, run.checkpoint_every, run.threads, output, plugins.paths and system.init
// may change on resume.
void check_resume_compatible(const Experiment& now, const Experiment& then, const std::string& checkpoint,
                             ConfigErrors& errors);

}  // namespace fldsim
