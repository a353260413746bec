// Volume and centroid of a union of spheres. Exact (closed-form lens/cap formulas) when no point
// lies in three spheres; otherwise a numerical line integration (see integrate_union).
#pragma once

#include <vector>

#include "fldsim/box.hpp"

namespace fldsim::shapes {

struct Ball {
  Vec3 centre;
  double radius;
};

struct VolumeAndCentroid {
  double volume = 0.0;
  Vec3 centroid = Vec3::Zero();
  bool exact = true;         // false when computed by integrate_union
  double error_bound = 0.0;  // estimated absolute error of the volume (0 when exact)
};

// Volume of the lens (intersection) of two balls of radii a, b with centre distance d.
// Standard result for |a - b| < d < a + b (e.g. Weisstein, "Sphere-Sphere Intersection",
// MathWorld):  V = pi (a + b - d)^2 (d^2 + 2d(a + b) - 3(a - b)^2) / (12 d).
// Returns 0 when d >= a + b and the smaller ball's volume when one contains the other.
double lens_volume(double a, double b, double d);

// Signed distance, along the axis from centre A towards centre B, of the lens centroid from A.
double lens_centroid_offset(double a, double b, double d);

// Inclusion–exclusion to second order: V = sum V_k - sum_{k<l} V_lens(k,l), and likewise for the
// first moment. Exact when no point lies in three balls; balls inside another ball are dropped.
// Falls back to integrate_union() otherwise.
VolumeAndCentroid union_volume_centroid(const std::vector<Ball>& balls);

// Numerical integration: V = iint L(y,z) dy dz, where L is the exact length of the union of the
// chords of all balls along the x line through (y,z) (intervals merged exactly). The (y,z)
// integral uses the midpoint rule on an n x n grid over the bounding square; the integrand has
// square-root edges, so the error falls as n^-3/2. The error bound is estimated as
// |V(n) - V(n/2)| (the coarser grid's error dominates that of the finer one).
VolumeAndCentroid integrate_union(const std::vector<Ball>& balls, int n = 1200);

// True when some point may belong to three or more balls (conservative: any triple of balls that
// overlap pairwise counts, even if the three lenses do not meet).
bool triples_may_overlap(const std::vector<Ball>& balls);

}  // namespace fldsim::shapes
