// A screened electrostatic (Yukawa) repulsion between the surfaces of sphere nodes of different
// bodies, the force law of LAMMPS's `pair_style yukawa/colloid` (its documentation; Russel,
// Saville & Schowalter, Colloidal Dispersions, 1989):
//   F = A exp(-kappa h) d,   U = (A/kappa) exp(-kappa h),   h = r - a_i - a_j,   r < cutoff
// with d the unit vector from one node to the other. Unlike the paper's repulsion it has no
// singularity and no cap: it keeps growing into overlaps. Its use here is to run LAMMPS's own
// documented FLD settings side by side (bench/lammps, issue 15). A = A* 6 pi mu a^2 rate, the
// rate chosen by `unit` as for `repulsion`. U is not shifted to zero at the cutoff (as LAMMPS
// without pair_modify shift): the force is what moves bodies; the energy is what the Monte Carlo
// oracle samples, and the jump at the cutoff, A/kappa exp(-kappa (cutoff - 2a)), is negligible
// for the documented kappa = 100/a.
#pragma once

#include <string>

#include "fldsim/force.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

class ScreenedRepulsion : public ForceLaw, public PairEnergy {
 public:
  static void describe(ParamSchema& s);
  explicit ScreenedRepulsion(const Params& p);

  double range(const System& system) const override;
  void add(const System& system, const NodePairList& pairs, double* wrench,
           Eigen::Matrix3d* virial) const override;
  double pair_energy(const System& system, const NodePair& pair) const override;

  // A in internal units for the system's rate convention.
  double amplitude(const System& system) const;

 private:
  double strength_star_;
  double kappa_;
  double cutoff_;
  std::string unit_;
};

}  // namespace fldsim
