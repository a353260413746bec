// The rate that makes a force law's dimensionless strength a force (F = strength* x mu a^2 x
// rate x constant), by the `unit` choice the force plugins share: diffusive = D0/a^2, shear =
// gammadot, paper = D0/a^2 for Pe < 1 and gammadot for Pe >= 1 (Kumar & Higdon's convention).
#pragma once

#include <cmath>
#include <string>

#include "fldsim/system.hpp"

namespace fldsim {

inline double force_rate(const Physics& ph, const std::string& unit) {
  const double a = 1.0;
  // D0/a^2 = kT / (6 pi mu a^3); with kT = 0 only the shear rate is meaningful.
  const double diffusive_rate = ph.kT / (6.0 * M_PI * ph.viscosity * a * a * a);
  const double peclet = diffusive_rate > 0.0 ? ph.shear_rate / diffusive_rate : INFINITY;
  if (unit == "diffusive") return diffusive_rate;
  if (unit == "shear") return ph.shear_rate;
  return peclet < 1.0 ? diffusive_rate : ph.shear_rate;
}

}  // namespace fldsim
