// The virials of one configuration, from the force laws as coded: ForceLaw::add is called on one
// node pair at a time, so the force on node j of that pair is the wrench it adds to body j (no
// assumption about what add() reports as its own virial):
//   body  W_b = sum over node pairs (X_j - X_i) (x) f_j   X the body centres (the image of the pair)
//   node  W_n = sum over node pairs (x_j - x_i) (x) f_j   x the node centres
// W_b is the molecular virial of rigid bodies: its trace gives the osmotic pressure
//   Pi V = N kT + tr(W_b) / 3    (Allen & Tildesley, Computer Simulation of Liquids, 2nd ed. 2017,
// section 2.4: molecular virial), which holds for any body reference point, as the volume derivative
// at fixed orientations. W_n - W_b = sum over nodes d (x) f (d the node's offset from its body
// centre) is the intra-body constraint virial a node-level (atomic) virial leaves out.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fldsim/force.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim::oracle {

struct Virials {
  Eigen::Matrix3d body = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d node = Eigen::Matrix3d::Zero();
};

class PairVirial {
 public:
  PairVirial(const System& s, std::vector<const ForceLaw*> laws);
  // Node positions of s must be current.
  Virials measure(const System& s);
  double range() const { return range_; }

 private:
  std::vector<const ForceLaw*> laws_;
  double range_ = 0.0;
  geometry::CellNeighbourList list_;
  NodePairList one_;
  std::vector<double> wrench_;
};

}  // namespace fldsim::oracle
