// Screened electrostatic (Yukawa / DLVO) repulsion between sphere nodes of different bodies.
// Linearised Poisson–Boltzmann theory gives for two charged spheres the pair energy
//   U(r) = epsilon (sigma / r) exp(-kappa (r - sigma)),   sigma = a_i + a_j,
// (Verwey & Overbeek, "Theory of the Stability of Lyophobic Colloids", 1948; Russel, Saville &
// Schowalter, "Colloidal Dispersions", 1989, ch. 4), with the size factors exp(kappa a)/(1 + kappa a)
// absorbed into epsilon = U(sigma), the energy at contact; the force on node j, along
// d = r / |r| from node i to node j, is
//   F(r) = -dU/dr = U(r) (kappa + 1/r).
// The force is cut at a surface gap of `cutoff` Debye lengths 1/kappa (truncated, not shifted).
// Its potential (fldsim::PairEnergy, for `fldsim oracle`) is therefore U shifted to zero at the
// cut, U(r) - U(r_c) for r < r_c: the same force, and no energy jump at r_c.
#pragma once

#include <fldsim/force.hpp>
#include <fldsim/params.hpp>

namespace yukawa {

class YukawaForce : public fldsim::ForceLaw, public fldsim::PairEnergy {
 public:
  static void describe(fldsim::ParamSchema& schema);
  explicit YukawaForce(const fldsim::Params& params);

  double range(const fldsim::System& system) const override;
  void add(const fldsim::System& system, const fldsim::NodePairList& pairs, double* wrench,
           Eigen::Matrix3d* virial) const override;
  double pair_energy(const fldsim::System& system, const fldsim::NodePair& pair) const override;

  // |F| between two nodes whose radii sum to `sigma`, at centre distance r (> 0), without the
  // cutoff.
  double magnitude(double r, double sigma) const;
  // U(r) without the cutoff shift.
  double energy(double r, double sigma) const;

 private:
  double strength_;  // epsilon, energy at contact [kT]
  double kappa_;     // inverse Debye length [1/a]
  double cutoff_;    // largest surface gap with a force [a]
};

}  // namespace yukawa
