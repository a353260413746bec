// The paper's short-range repulsion between sphere nodes of different bodies
// (Kumar & Higdon, section 2.3; Kumar & Higdon J. Rheol. 2010):
//   F = C_p (delta_min/delta) (eta - eta^2/2)^3 d,  eta = 1 - delta/delta_min,  delta < delta_min
// with d the unit vector from one node to the other and gaps 0 <= delta < delta_num evaluated at
// delta_num (the paper's clamp). The paper says nothing about overlaps (delta < 0): by default
// (`overlap: plateau`) they feel the same constant F(delta_num); `overlap: wall` makes the force grow,
// F = F(delta_num) min(1 + |delta| / wall_length, wall_factor) (by default by F(delta_num) per
// 1e-4 a up to 10 F(delta_num)). docs/time_steps.md, "The repulsion's force cap", has what each
// costs (the wall's stiffness biases the midpoint Brownian stress; free draining at a fixed step). The paper
// quotes C_p* = C_p / (8 pi mu a^2 rate) with rate = D0/a^2 for Pe < 1 and gammadot for Pe >= 1 (DESIGN.md:
// the printed "8 pi mu a^4/D0" is dimensionally a typo).
//
// Its potential (PairEnergy), the integral of the force as coded, U(delta) = int_delta^delta_min F:
// with x = delta/delta_min, eta - eta^2/2 = (1 - x^2)/2, so F = (C_p/8) (1 - x^2)^3 / x and
//   U = (C_p delta_min / 8) [-ln x - 11/12 + 3x^2/2 - 3x^4/4 + x^6/6]     delta_num <= delta < delta_min
//   U = U(delta_num) + F(delta_num) (delta_num - delta)                   0 <= delta < delta_num
//   U = U(0) + F(delta_num) (d + d^2 / (2 wall_length))        overlap d = -delta <= d_c
//   U = U(d_c) + wall_factor F(delta_num) (d - d_c)             d > d_c = (wall_factor - 1) wall_length
// (linear below delta_num, quadratic in the overlap up to the wall's cap, linear beyond; the
// plateau is wall_factor = 1), U = 0 beyond delta_min.
#pragma once

#include "fldsim/force.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

class ShortRangeRepulsion : public ForceLaw, public PairEnergy {
 public:
  static void describe(ParamSchema& s);
  explicit ShortRangeRepulsion(const Params& p);

  double range(const System& system) const override;
  void add(const System& system, const NodePairList& pairs, double* wrench,
           Eigen::Matrix3d* virial) const override;
  double pair_energy(const System& system, const NodePair& pair) const override;

  // The continuation into overlaps: F(delta_num) min(1 + overlap / length, factor); factor 1 is the
  // plateau.
  struct Wall {
    double length = 1e-4, factor = 10.0;
  };
  // Magnitude of the force at surface gap `gap` (repulsive, >= 0), for prefactor C_p.
  static double magnitude(double gap, double prefactor, double delta_min, double delta_num, const Wall& wall);
  // Its potential at surface gap `gap` (any sign): the integral of magnitude() from gap to delta_min.
  static double energy(double gap, double prefactor, double delta_min, double delta_num, const Wall& wall);
  // C_p in internal units for the system's rate convention.
  double prefactor(const System& system) const;

 private:
  double prefactor_star_;
  double delta_min_;
  double delta_num_;
  double wall_length_, wall_factor_;  // factor 1: the plateau
  std::string unit_;
};

}  // namespace fldsim
