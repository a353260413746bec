// A force law between nodes of different bodies (e.g. the paper's short-range repulsion), and
// the optional pair energy of a law that derives from a potential.
#pragma once

#include <Eigen/Core>

#include "fldsim/neighbours.hpp"
#include "fldsim/plugin_base.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

class FLDSIM_VISIBLE ForceLaw : public Component {
 public:
  // Largest node centre distance at which the law acts (the core's pair list covers it).
  virtual double range(const System& system) const = 0;
  // Add body forces and torques (6 per body: F then T) of all pairs in `pairs` to `wrench`.
  // If `virial` is not null, also add the molecular virial of the pairs (API 3):
  //   sum over node pairs of R (x) f_j,  R = X_j - X_i = r - d_jb + d_ia,
  // the separation of the two bodies' centres in the pair's image (r = x_j - x_i of the nodes,
  // d the node offsets, system.node_offsets()) and f_j the force on node j. The interparticle
  // stress of rigid bodies is -virial / V, and at equilibrium the osmotic pressure is
  // Pi = n kT + tr(virial) / (3 V) (docs/equilibrium-oracle.md). The node-node sum r (x) f_j
  // (API 2) differs by the intra-body constraint virial and is not the pressure of rigid bodies.
  virtual void add(const System& system, const NodePairList& pairs, double* wrench,
                   Eigen::Matrix3d* virial) const = 0;
};

// The potential a force law derives from (API 2.1; 3.0 keeps it). A law with an energy derives from both
// ForceLaw and PairEnergy; a law without one (a dissipative or non-conservative law) does not,
// and pair_energy_of() returns null for it. The equilibrium
// Monte Carlo oracle (`fldsim oracle`, docs/equilibrium-oracle.md) samples exp(-U/kT) with
//   U = sum over node pairs (a of body i, b of body j != i) of pair_energy(system, pair),
// so the energy must be the one whose gradient add() applies: f_j = -dU/dx_j for every node
// pair, including any clamp, plateau or overlap (negative gap) region the force has, and zero
// at and beyond range(). A law cut at a finite range with a force jump there has no such
// potential; shift it so that U(range) = 0 (the force is unchanged). tests/plugins checks
// -dU/dr = F by finite differences for every built-in law that declares an energy.
class FLDSIM_VISIBLE PairEnergy {
 public:
  virtual ~PairEnergy() = default;
  // Energy of one node pair of different bodies, in the system's energy unit (kT for a
  // Brownian system). `pair` is filled as in add(): node indices within their bodies, r the
  // minimum-image x_j - x_i and distance = |r|; the Monte Carlo calls it with body_i < body_j
  // for pairs at any distance (return 0 beyond range()). Called for the pairs of one moved
  // body at a time: no allocation, and nothing that depends on other pairs.
  virtual double pair_energy(const System& system, const NodePair& pair) const = 0;
};

// The energy of `law`, or null if it declares none.
inline const PairEnergy* pair_energy_of(const ForceLaw& law) {
  return dynamic_cast<const PairEnergy*>(&law);
}

}  // namespace fldsim
