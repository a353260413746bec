// Inter-visibility of two nodes of different bodies (Kumar & Higdon, §2.1.1): a node pair takes
// part in lubrication only if the nodes are within the cutoff and the segment joining their
// centres leaves each node through a part of its surface that is not buried inside another node
// of the same body. Buried pairs look through a neighbouring node of their own body; counting
// them would double the lubrication of a dicolloid approached end-on.
// The test is on/off: a pair's resistance jumps when an exit point crosses a sibling's surface, so
// deterministic runs of multi-node bodies are first order at such events (bench/accuracy/README.md).
#pragma once

#include <vector>

#include "fldsim/shape.hpp"

namespace fldsim::hydro {

// offsets_i: world-frame node offsets of body i (from its centre), radii: node radii (same shape
// for both bodies); a, b: node indices in body i and body j; r = x(j,b) - x(i,a) (minimum image);
// cutoff: centre-distance cutoff for unit mean radius, scaled by abar = (a_a + a_b)/2.
bool nodes_visible(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                   std::size_t a, std::size_t b, const Vec3& r, double cutoff);

}  // namespace fldsim::hydro
