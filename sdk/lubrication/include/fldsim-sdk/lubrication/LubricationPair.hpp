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
// Without log terms (LubricationOptions::log_terms false) only the squeeze mode's 1/xi remains.
// Every coefficient is multiplied by a taper T(r) that takes it smoothly (C2) to zero over a window
// below the cutoff, so R_delta, and the mobility, are continuous when a pair enters or leaves the
// list: a jump there has a thermal drift kT div M that no finite-step scheme represents (the
// equilibrium g(r) then shows a step at the cutoff; docs/lubrication-taper.md).
#pragma once

#include <Eigen/Core>

#include "fldsim/box.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim::hydro {

// None: no counter-rotation mode (an ablation, for measuring what the pump does).
enum class PumpForm { JeffreyOnishi, Lammps, None };
// Lever arms of the shear mode: from each centre to the common point of the gap, splitting r in
// the ratio of the radii (Centre: l_i + l_j = r, a rigidly rotating pair is force-free), or the
// node radii as LAMMPS pair lubricateU does (Contact: l = a).
enum class Lever { Centre, Contact };
// Arm of the ambient strain seen by a pair (BodyResistance): the body-centre separation R_ij,
// the relative motion of the two bodies in the imposed flow (Centre), or that arm shortened by the
// node pair's gap, R_ij - (r - a_i - a_j) d (Contact): for spheres the contact distance
// (a_i + a_j) d, the fluid's relative velocity between the two contact points as LAMMPS pair
// lubricateU uses it.
enum class StrainArm { Centre, Contact };

struct LubricationOptions {
  double delta_num = 1e-5;  // gaps (in abar) below this are evaluated at delta_num
  PumpForm pump = PumpForm::JeffreyOnishi;
  bool twist = true;
  // false: the squeeze mode's 1/xi term alone, no log terms (so no shear or pump mode), as LAMMPS
  // pair lubricateU with flaglog 0; the twist mode (a contact constant) stays as `twist` says.
  bool log_terms = true;
  Lever lever = Lever::Centre;
  StrainArm strain_arm = StrainArm::Contact;  // docs/two-body.md: closer to the exact A, B, C
  double cutoff = 2.5;                        // node centre distance (in abar) where pairs end
  double taper_width = 0.0;       // 0: abrupt cutoff; else coefficients go to zero over [cutoff - w, cutoff]
  double visibility_width = 0.0;  // 0: the sharp visibility rule; else its smooth form (Visibility.hpp)
};

// C2 switch-off: 1 for r <= cutoff - w, 0 for r >= cutoff, (1-s)^3 (1 + 3 s + 6 s^2) between,
// s = (r - cutoff + w)/w (all in abar). Value and first two derivatives vanish at both ends.
double taper_factor(double r_over_abar, const LubricationOptions& options);

// Mode coefficients c_m (force/velocity units, already dimensional).
struct LubricationCoefficients {
  double xi = 0.0;       // gap (r - a_i - a_j)/abar, floored at delta_num
  double squeeze = 0.0;  // c_sq
  double shear = 0.0;    // c_sh
  double pump = 0.0;     // c_pu
  double twist = 0.0;    // c_tw
  double taper = 1.0;    // T(r), already applied to the four coefficients above
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
  // The same, also returning the coefficients it used.
  static void rows(double a_i, double a_j, const Vec3& r, double mu, const LubricationOptions& options,
                   PairRows& S, LubricationCoefficients& c);
  // S from the unit separation d and the coefficients c of coefficients().
  static void rows(const Vec3& d, const LubricationCoefficients& c, PairRows& S);
  // w S^T S for two nodes at their bodies' centres (identity kinematics, e.g. spheres), in closed
  // form from the coefficients c of rows(): the blocks (i,i), (j,j) and (i,j) of the 12 x 12 Gram
  // matrix, each 6 x 6. With P = I - d d^T and D w = d x w (P D = D, D^T D = P):
  //   ii = [c_sq dd + c_sh P,  -c_sh l_i D;  c_sh l_i D,  (c_sh l_i^2 + c_pu) P + c_tw dd]
  //   jj = [c_sq dd + c_sh P,   c_sh l_j D; -c_sh l_j D,  (c_sh l_j^2 + c_pu) P + c_tw dd]
  //   ij = [-c_sq dd - c_sh P, -c_sh l_j D; -c_sh l_i D,  (c_sh l_i l_j - c_pu) P - c_tw dd]
  // About 20 times fewer operations than the Gram products; equal to them to rounding, exactly
  // symmetric (tests/hydro/LubricationPairTest.cpp).
  // Adds centred_gram's ii and jj to Rii and Rjj, and its ij to Rij (or assigns it, if assign_ij), by
  // 3 x 3 corners straight from their terms: the same sums, element for element, as adding the
  // blocks centred_gram returns, without the 6 x 6 temporaries (whose 3-row column halves, stored
  // separately and read back in pairs across the halves, stalled the additions; bench/README.md).
  static void add_centred_gram(const Vec3& d, const LubricationCoefficients& c, double w, Mat6& Rii,
                               Mat6& Rjj, Mat6& Rij, bool assign_ij);
  static void centred_gram(const Vec3& d, const LubricationCoefficients& c, double w, Mat6& ii, Mat6& jj,
                           Mat6& ij);
  // -w S^T S v for centred nodes, the pair's wrench (f_i, t_i, f_j, t_j) for node velocities
  // v = (u_i, w_i, u_j, w_j), from the coefficients alone. With du = u_j - u_i, dw = w_i - w_j and
  // the tangential t = c_sh (P du + l_i d x w_i + l_j d x w_j):
  //   S^T S v = (-(c_sq (d.du) d + t),  -l_i d x t + c_pu P dw + c_tw (d.dw) d,
  //                c_sq (d.du) d + t,   -l_j d x t - c_pu P dw - c_tw (d.dw) d).
  // The pair stresslets use it (node velocities; BodyResistance carries them from the bodies).
  static Eigen::Matrix<double, 12, 1> centred_wrench(const Vec3& d, const LubricationCoefficients& c,
                                                     double w, const Eigen::Matrix<double, 12, 1>& v);
  // The force on node j of centred_wrench alone (its elements 6-8, the same operations and bits),
  // for the pair stresslets, which need no torques.
  static Vec3 centred_force_j(const Vec3& d, const LubricationCoefficients& c, double w,
                              const Eigen::Matrix<double, 12, 1>& v);
  // centred_wrench for v = (0, 0, du, 0), the strain force's only velocity (E L on node j): the
  // terms of the zero velocities dropped, otherwise the same operations (equal to centred_wrench
  // up to the sign of zeros).
  static Eigen::Matrix<double, 12, 1> centred_strain_wrench(const Vec3& d, const LubricationCoefficients& c,
                                                            double w, const Vec3& du);
  // sqrt(w) S^T beta for centred nodes (the pair's Brownian wrench for the mode normals beta):
  // with s_m = sqrt(w c_m), b = beta[1..3], p = beta[4..6],
  //   (-s_sq beta_0 d - s_sh P b,  -s_sh l_i d x b + s_pu P p + s_tw beta_7 d,
  //     s_sq beta_0 d + s_sh P b,  -s_sh l_j d x b - s_pu P p - s_tw beta_7 d).
  static Eigen::Matrix<double, 12, 1> centred_noise(const Vec3& d, const LubricationCoefficients& c, double w,
                                                    const Eigen::Matrix<double, kRows, 1>& beta);
};

}  // namespace fldsim::hydro
