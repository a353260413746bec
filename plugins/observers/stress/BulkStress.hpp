// Bulk stress of a suspension from the box sums the core provides (StressPieces):
//   sigma = -p I + 2 mu E_inf + sigma_H + sigma_P + sigma_B
//   sigma_H = (1/V) sum S^H            hydrodynamic stresslets (Batchelor, J. Fluid Mech. 41, 545 (1970))
//   sigma_P = -(1/V) sum R (x) f       interparticle (virial) part (Brady & Bossis, Annu. Rev. Fluid
//                                      Mech. 20, 111 (1988)) with R = X_j - X_i the separation of the
//                                      bodies' centres (the molecular virial: for rigid bodies the
//                                      moments of the node forces about their centres are carried by
//                                      the bodies, and the fluid sees only F and T); StressPieces::
//                                      interparticle already holds -sum R (x) f (force.hpp: "stress is
//                                      -virial / V"), so sigma_P = StressPieces::interparticle / V
//   sigma_B = (1/V) StressPieces::brownian   Brownian (drift) part (Foss & Brady, J. Fluid Mech. 407,
//                                      167 (2000)) when the hydrodynamics provides it
// The solvent pressure p is undetermined in an incompressible Stokes flow and left out; the
// particle pressure is Pi = -tr(sigma_H + sigma_P + sigma_B)/3 (Jeffrey, Morris & Brady 1993).
// The osmotic pressure of an equilibrium (Pe = 0) suspension is the thermodynamic one,
// n kT + Pi_P with Pi_P = -tr(sigma_P)/3 = tr(sum R (x) f)/(3V): the compressibility factor
// Z = 1 + Pi_P/(n kT), for any body shape, as an average over the Boltzmann distribution of the
// potential. A run that does not sample that distribution near contact does not get it from Pi_P:
// FLD at its default lubrication clamp keeps pairs out of the repulsion's overlap ramp, and the
// contact pressure appears in the Brownian stress instead (as for hard spheres with hydrodynamics,
// Brady, J. Chem. Phys. 98, 3335 (1993)); figures in docs/equilibrium-oracle.md.
// Rheology under u = gammadot y x (E_inf,xy = gammadot/2): eta_r = sigma_xy/(mu gammadot),
// N1 = sigma_xx - sigma_yy, N2 = sigma_yy - sigma_zz.
#pragma once

#include <Eigen/Core>

#include "fldsim/observer.hpp"

namespace fldsim::observers {

enum StressPart { kHydrodynamic = 0, kInterparticle = 1, kBrownian = 2, kParticleTotal = 3 };
inline constexpr const char* kStressPartNames[4] = {"hydrodynamic", "interparticle", "brownian", "particle"};

// The four rheological functions of one stress tensor.
struct Rheology {
  double shear;     // sigma_xy
  double n1;        // sigma_xx - sigma_yy
  double n2;        // sigma_yy - sigma_zz
  double pressure;  // -tr(sigma)/3
};

class BulkStress {
 public:
  BulkStress(double volume, double viscosity, double shear_rate)
      : volume_(volume), viscosity_(viscosity), shear_rate_(shear_rate) {}

  // Particle stress of each part and their sum, indexed by StressPart.
  void particle_stress(const StressPieces& pieces, Eigen::Matrix3d (&parts)[4]) const;
  // Full deviatoric stress 2 mu E_inf + particle stress (no solvent pressure).
  Eigen::Matrix3d total(const StressPieces& pieces) const;
  Eigen::Matrix3d strain_rate() const;  // E_inf
  static Rheology rheology(const Eigen::Matrix3d& sigma);
  // sigma_xy / (mu gammadot) of the full stress: 1 + particle contributions.
  double relative_viscosity(const StressPieces& pieces) const;

 private:
  double volume_, viscosity_, shear_rate_;
};

}  // namespace fldsim::observers
