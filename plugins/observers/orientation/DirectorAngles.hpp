// Orientation angles of a director in the paper's convention (Kumar & Higdon §3.2; DESIGN.md):
// x velocity, y gradient, z vorticity. theta is the angle from the vorticity axis folded to
// [0, pi/2] (|n_z|, since n and -n are the same body); phi is the angle of the x-y projection
// measured from the gradient axis y, positive towards the flow axis +x, folded to [-pi/2, pi/2].
// So phi = pi/2 is the flow axis, 0 the gradient axis, 0 < phi < pi/2 the extensional quadrant
// (n along (1,1,0)), -pi/2 < phi < 0 the compressional one (n along (-1,1,0)).
#pragma once

#include "fldsim/box.hpp"

namespace fldsim::observers {

struct DirectorAngles {
  double theta;  // [0, pi/2]
  double phi;    // (-pi/2, pi/2]
};

DirectorAngles director_angles(const Vec3& n);

}  // namespace fldsim::observers
