// The contact term of the hard core's pressure (OracleOptions::hard_core: no node of one body may
// overlap a node of another), for rigid bodies of any shape, by the molecular virial's route: the
// pressure is the volume derivative at fixed orientations, and scaling the body centres by
// (1 - eps) closes a node pair's gap h by eps p, p = (X_j - X_i) . r_ab / |r_ab| the projection
// of the centre separation on the node separation. The pairs that such a compression brings into
// overlap give
//   Z_contact = lim_{eps -> 0} <#{pairs: h < eps p}> / (3 N eps) = f(0+) / (3N),
//   f(h) = sum over node pairs at gap h of p, per unit gap,
// (for spheres p = 2a and f(0+) = (N (N - 1) / 2V) 4 pi (2a)^3 g(2a+) with g normalised by the
// N (N - 1) / V of the radial histograms: Z_contact = 4 phi g(2a+) (N - 1)/N, the finite system's
// virial; 4 phi g(2a+) alone is 0.8 % high at N = 125). f is
// measured in bins of the gap over [0, span) and extrapolated to 0+ per block by a quadratic
// least-squares fit, as the contact value of g; a force law acting inside the first bins (the
// repulsion's 1e-3 a) is left to the caller, who multiplies by exp(-U(0)/kT) when the fit lies
// outside its range (docs/equilibrium-oracle.md).
#pragma once

#include <vector>

#include "fldsim/system.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim::oracle {

class HardCoreContact {
 public:
  // Nodes of one radius (one contact distance); bins of `bin_width` over gaps [0, span).
  HardCoreContact(const System& s, double bin_width = 0.01, double span = 0.1);
  // Adds one configuration (node positions current).
  void add_sample(const System& s);
  // Closes a block: its f(0+) / (3N) from the samples since the last end_block.
  void end_block();
  const std::vector<double>& block_values() const { return blocks_; }

 private:
  double contact_, bin_, span_, bodies_;
  std::vector<double> sum_;  // per bin: sum of p over the block's samples
  std::int64_t samples_ = 0;
  std::vector<double> blocks_;
  geometry::CellNeighbourList list_;
};

}  // namespace fldsim::oracle
