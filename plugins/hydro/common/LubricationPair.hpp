// Near-field (lubrication) resistance of two sphere nodes i, j with radii a_i, a_j at centre
// separation r = x_j - x_i (unit vector d). The 12x12 pair resistance acting on the node
// velocities v = (u_i, w_i, u_j, w_j) is written as a sum of modes,
//     R_pair = sum_m c_m G_m^T G_m = S^T S,   S = rows sqrt(c_m) G_m  (8 x 12),
// with c_m >= 0, so R_pair is positive semi-definite by construction and B_p = S^T is an exact
// square root (sum_p B_p B_p^T = R_delta). Every mode annihilates rigid motions of the pair, so
// pair forces and torques conserve momentum and angular momentum exactly.
//
// Modes (rows of S):
//   0     squeeze: d.(u_j - u_i)                                   [X^A, 1/xi and log]
//   1..3  shear:   P (u_j - u_i - (l_i w_i + l_j w_j) x d)          [Y^A, log]
//         (relative tangential velocity at the point p = x_i + l_i d = x_j - l_j d of the gap,
//          l_i = r a_i/(a_i + a_j); P = I - d d^T)
//   4..6  pump:    P (w_i - w_j)                                   [Y^C, log]
//   7     twist:   d.(w_i - w_j)                                   [X^C, contact value]
#pragma once

#include <Eigen/Core>

#include "fldsim/box.hpp"

namespace fldsim::hydro {

enum class PumpForm { JeffreyOnishi, Lammps };

struct LubricationOptions {
  double delta_num = 1e-5;  // gaps (in abar) below this are evaluated at delta_num
  PumpForm pump = PumpForm::JeffreyOnishi;
  bool twist = true;
};

// Mode coefficients c_m (force/velocity units, already dimensional).
struct LubricationCoefficients {
  double xi = 0.0;       // gap (r - a_i - a_j)/abar, floored at delta_num
  double squeeze = 0.0;  // c_sq
  double shear = 0.0;    // c_sh
  double pump = 0.0;     // c_pu
  double twist = 0.0;    // c_tw
  double lever_i = 0.0;  // l_i
  double lever_j = 0.0;  // l_j
};

using PairRows = Eigen::Matrix<double, 8, 12>;

class LubricationPair {
 public:
  static constexpr int kRows = 8;

  // Coefficients for radii a_i, a_j at centre distance r, viscosity mu.
  static LubricationCoefficients coefficients(double a_i, double a_j, double r, double mu,
                                              const LubricationOptions& options);
  // The 8 x 12 matrix S (rows sqrt(c_m) G_m) for separation vector r = x_j - x_i.
  static void rows(double a_i, double a_j, const Vec3& r, double mu, const LubricationOptions& options,
                   PairRows& S);
};

}  // namespace fldsim::hydro
