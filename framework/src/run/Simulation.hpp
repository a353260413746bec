// One run of an experiment: builds the system and the plugins, starts from the requested
// initial configuration, steps the integrator, lets due observers sample, and writes the
// result file (atomically: `OUT.part`, renamed at the end) and checkpoints.
#pragma once

#include <iosfwd>
#include <string>

#include "run/Experiment.hpp"

namespace fldsim {

struct RunOptions {
  std::string output;   // overrides the experiment's `output`
  bool overwrite = false;
  std::string resume;   // checkpoint file to resume from
  bool quiet = false;
};

// Returns the process exit code (0 on success); throws fldsim::Error on failure.
int run_experiment(const Experiment& ex, const PluginRegistry& registry, const RunOptions& opt,
                   std::ostream& log);

}  // namespace fldsim
