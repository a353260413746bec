// Moving rigid bodies by a velocity over a time h, from a saved base configuration, so that
// multi-stage schemes (midpoint, Runge–Kutta) can evaluate stages and then take the full step
// from the same start. Positions move by h U; orientations by the rotation exp(h Omega)
// (exact for constant Omega; quaternions are renormalised); the box strain by h gammadot.
#pragma once

#include <vector>

#include "fldsim/system.hpp"

namespace fldsim {

struct BodySnapshot {
  std::vector<Vec3> positions;
  std::vector<Quat> orientations;
  double strain = 0.0;
  double time = 0.0;

  void save(const System& s);
  void restore(System& s) const;
};

// Set s to base + h * U (U: 6 per body, total velocity), then refresh node positions. The
// positions are not wrapped (call wrap_into_box after the final stage of a step).
void move_from(System& s, const BodySnapshot& base, const double* U, double h);
// Add h * U and h * dU (the velocity relative to the imposed flow) to the displacement records.
void record_displacement(System& s, const double* U, const double* dU, double h);
// Map every centre into the box (Lees–Edwards shift on y crossings).
void wrap_into_box(System& s);

}  // namespace fldsim
