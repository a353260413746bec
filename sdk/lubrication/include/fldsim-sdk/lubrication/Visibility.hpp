// Inter-visibility of two nodes of different bodies (Kumar & Higdon, §2.1.1): a node pair takes
// part in lubrication only if the nodes are within the cutoff and the segment joining their
// centres leaves each node through a part of its surface that is not buried inside another node
// of the same body. Buried pairs look through a neighbouring node of their own body; counting
// them would double the lubrication of a dicolloid approached end-on.
// The sharp test is on/off: a pair's resistance jumps when an exit point crosses a sibling's
// surface, so deterministic runs of multi-node bodies are first order at such events (issue 11:
// a whole-scene error floor of 1.3e-5 a for dicolloids). The smooth form weighs each pair by
// w = W(s_i) W(s_j) in [0, 1], s the exit point's signed depth outside the sibling surfaces, so that
// R, its Brownian forces (sqrt w) and stresslets change continuously (C2) with the configuration.
#pragma once

#include <vector>

#include "fldsim/shape.hpp"

namespace fldsim::hydro {

// offsets_i: world-frame node offsets of body i (from its centre), radii: node radii (same shape
// for both bodies); a, b: node indices in body i and body j; r = x(j,b) - x(i,a) (minimum image);
// cutoff: centre-distance cutoff for unit mean radius, scaled by abar = (a_a + a_b)/2.
bool nodes_visible(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                   std::size_t a, std::size_t b, const Vec3& r, double cutoff);

// The pair's weight: 0 or 1 by the sharp rule when width = 0; else the product over both exit
// points and every sibling node k of W(d_k / width + 1/2), d_k = |exit - x_k| - a_k (negative
// inside), W the C2 step x^3 (10 - 15 x + 6 x^2) on [0, 1]: the sharp rule's switch spread over
// exit depths -width/2 .. +width/2. 0 beyond the cutoff.
double visibility_weight(const Vec3* offsets_i, const Vec3* offsets_j, const double* radii, std::size_t nodes,
                         std::size_t a, std::size_t b, const Vec3& r, double cutoff, double width);

}  // namespace fldsim::hydro
