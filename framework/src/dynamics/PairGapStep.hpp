// How far a step moves near pairs of nodes towards or away from each other: the change of the
// surface gap of every node pair of different bodies whose gap at the start or the end of the
// step is below a range, and how far the imposed flow alone would have moved them. What the
// pair-gap bound controls (StepControl, run.gap_step): a near-contact pair whose gap jumps by far
// more than the repulsion's range in one step samples the repulsion wrongly. At rest and at low
// Pe that jump is set by the lubrication between the two nodes, the same at any volume fraction
// for a given step, where the rms node step is not (docs/time_steps.md, "The pair-gap bound").
// Under strong shear lubrication keeps the actual gap changes small even when the flow carries
// pairs into contact from outside the range faster than a step resolves (N = 125, phi 0.5, Pe 1000:
// 3e-2 strain steps, overlaps to 0.07 a, where 8e-3 strain stays within 4e-4 a), so the
// flow's own normal displacement of each near pair, gammadot dt r_x r_y / |r|, counts too, as the
// node bound counts what the flow moves a touching neighbour.
#pragma once

#include <cstddef>

#include "fldsim/neighbours.hpp"
#include "fldsim/shape.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

struct PairGapSteps {
  double sum_square = 0.0;   // sum over the near pairs of (gap change)^2, a^2
  double flow_square = 0.0;  // sum over them of (gammadot dt r_x r_y / |r|)^2, a^2
  std::size_t pairs = 0;     // how many
  // What the bound holds below l^2: the mean of the two, a^2 (0 without near pairs).
  double mean_square() const { return pairs ? (sum_square + flow_square) / double(pairs) : 0.0; }
};

// pairs: the list at the end of the step (x(j,b) - x(i,a) and |r|), s.node_offsets() of that
// state (System::update_nodes, as every move leaves them); relative_velocity: U - U_inf
// (6 per body) used for the step, dt its length. The relative displacement of the two nodes is
// dt [gammadot (c_j - c_i)_y x + Omega_inf x (o_jb - o_ia) + (dv_j + dw_j x o_jb) - (dv_i + dw_i x o_ia)]
// (o: a node's offset from its body's centre, c_j - c_i = r - o_jb + o_ia, so images need no
// care), and the gap change |r| - |r - that| (not linearised in the pair's direction: sliding
// past a neighbour changes the gap too).
PairGapSteps near_pair_gap_steps(const System& s, const NodePairList& pairs, const double* relative_velocity,
                                 double dt, double range);

// The neighbour-list range the bound needs: every node pair of gap below `range` listed, so the
// largest node contact distance plus range (a). Used by the run and by `fldsim check`.
double pair_gap_list_range(const Shape& shape, double range);

}  // namespace fldsim
