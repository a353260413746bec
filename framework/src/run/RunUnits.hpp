// From the experiment's physical parameters to the core's internal units (node radius a = 1,
// 6 pi mu a = 1, kT = 1 when Brownian, so internal time is a^2/D0 and Pe = gammadot), and the
// user's time unit: run.time_unit, with `paper` = a^2/D0 for Pe < 1 and 1/gammadot for Pe >= 1
// (Kumar & Higdon's convention).
#pragma once

#include <string>

#include "fldsim/system.hpp"
#include "run/Experiment.hpp"

namespace fldsim {

// kT and gammadot of the run in internal units (volume_fraction is set with the box).
Physics physics_of(const Experiment& ex);

struct UserTimeUnit {
  std::string name;    // "a^2/D0" or "1/gammadot"
  double scale = 1.0;  // internal time per user time unit
};

// Throws ConfigError if the unit cannot apply (diffusive time without Brownian motion, strain
// time without shear).
UserTimeUnit user_time_unit(const Experiment& ex, const Physics& ph);

}  // namespace fldsim
