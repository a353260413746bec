#include "run/RunUnits.hpp"

#include "fldsim/error.hpp"

namespace fldsim {

Physics physics_of(const Experiment& ex) {
  Physics ph;
  ph.kT = ex.brownian ? 1.0 : 0.0;
  // A non-Brownian run has no D0: its time unit is 1/gammadot with gammadot = 1.
  ph.shear_rate = ex.brownian ? ex.peclet : 1.0;
  return ph;
}

UserTimeUnit user_time_unit(const Experiment& ex, const Physics& ph) {
  const double diffusive = 1.0;  // a^2/D0 in internal time units
  const double strain_unit = ph.shear_rate > 0 ? 1.0 / ph.shear_rate : 0.0;
  if (ex.time_unit == "diffusive" || (ex.time_unit == "paper" && ex.brownian && ex.peclet < 1.0)) {
    if (!ex.brownian) throw ConfigError(ex.file + ": run.time_unit: diffusive time needs a Brownian run");
    return {"a^2/D0", diffusive};
  }
  if (strain_unit == 0.0)
    throw ConfigError(ex.file + ": run.time_unit: strain units (1/gammadot) need flow.peclet > 0");
  return {"1/gammadot", strain_unit};
}

}  // namespace fldsim
