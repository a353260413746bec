// The paper's short-range repulsion between sphere nodes of different bodies
// (Kumar & Higdon, section 2.3; Kumar & Higdon J. Rheol. 2010):
//   F = C_p (delta_min/delta) (eta - eta^2/2)^3 d,  eta = 1 - delta/delta_min,  delta < delta_min
// with d the unit vector from one node to the other and gaps below delta_num evaluated at
// delta_num. The paper quotes C_p* = C_p / (8 pi mu a^2 rate) with rate = D0/a^2 for Pe < 1 and
// gammadot for Pe >= 1 (DESIGN.md: the printed "8 pi mu a^4/D0" is dimensionally a typo).
#pragma once

#include "fldsim/force.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

class ShortRangeRepulsion : public ForceLaw {
 public:
  static void describe(ParamSchema& s);
  explicit ShortRangeRepulsion(const Params& p);

  double range(const System& system) const override;
  void add(const System& system, const NodePairList& pairs, double* wrench,
           Eigen::Matrix3d* virial) const override;

  // Magnitude of the force at surface gap `gap` (repulsive, >= 0), for prefactor C_p.
  static double magnitude(double gap, double prefactor, double delta_min, double delta_num);
  // C_p in internal units for the system's rate convention.
  double prefactor(const System& system) const;

 private:
  double prefactor_star_;
  double delta_min_;
  double delta_num_;
  std::string unit_;
};

}  // namespace fldsim
