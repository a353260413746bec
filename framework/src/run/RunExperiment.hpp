// `fldsim run`: an experiment run to its end as one result file. Opens the result file first
// (an existing one is refused before any work), assembles the Simulation, records the
// provenance, steps it with periodic checkpoints, lets the observers write their results, and
// renames `OUT.part` to `OUT` only when everything succeeded.
#pragma once

#include <iosfwd>
#include <string>

#include "run/Experiment.hpp"

namespace fldsim {

struct RunOptions {
  std::string output;  // overrides the experiment's `output`
  bool overwrite = false;
  std::string resume;  // checkpoint file to resume from
  bool quiet = false;
};

// Returns the process exit code (0 on success); throws fldsim::Error on failure.
int run_experiment(const Experiment& ex, const PluginRegistry& registry, const RunOptions& opt,
                   std::ostream& log);

}  // namespace fldsim
