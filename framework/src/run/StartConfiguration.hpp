// Where the bodies of a new run start (system.init): hard-body Monte Carlo, positions listed in
// the experiment, or the last trajectory frame of an earlier result file.
#pragma once

#include <iosfwd>

#include "fldsim/system.hpp"
#include "run/Experiment.hpp"

namespace fldsim {

// Places every body of `sys` (and updates its nodes); one line on `log` says how.
// Throws fldsim::Error if the listed or read configuration does not fit the system.
void place_start_configuration(System& sys, const Experiment& ex, std::ostream& log);

}  // namespace fldsim
