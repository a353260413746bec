#include "fldsim-sdk/lubrication/LubricationPair.hpp"

#include <algorithm>
#include <cmath>

#include "BlockCorners.hpp"
#include "CrossMatrix.hpp"

namespace fldsim::hydro {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kZeta3 = 1.2020569031595942;  // Riemann zeta(3)

}  // namespace

double taper_factor(double r_over_abar, const LubricationOptions& options) {
  if (options.taper_width <= 0.0) return 1.0;
  const double s = (r_over_abar - options.cutoff + options.taper_width) / options.taper_width;
  if (s <= 0.0) return 1.0;
  if (s >= 1.0) return 0.0;
  // 1 - s^3 (10 - 15 s + 6 s^2) written as (1-s)^3 (1 + 3 s + 6 s^2): non-negative in floating
  // point too (the rows take its square root).
  const double u = 1.0 - s;
  return u * u * u * (1.0 + 3.0 * s + 6.0 * s * s);
}

LubricationCoefficients LubricationPair::coefficients(double a_i, double a_j, double r, double mu,
                                                      const LubricationOptions& options) {
  LubricationCoefficients c;
  const double abar = 0.5 * (a_i + a_j);
  // Jeffrey & Onishi (1984) gap: xi = s - 2 with s = 2r/(a_i + a_j); floored at delta_num.
  c.xi = std::max((r - a_i - a_j) / abar, options.delta_num);
  // ln(1/xi) only for xi < 1: beyond, the asymptotic log term changes sign (LAMMPS docs). Without
  // log terms (LAMMPS flaglog 0) it is zero, which leaves the squeeze's 1/xi and removes the shear
  // and pump modes.
  const double log_inv = options.log_terms && c.xi < 1.0 ? std::log(1.0 / c.xi) : 0.0;
  const double lam = a_j / a_i;  // JO radius ratio lambda = a_2/a_1
  const double opl = 1.0 + lam;

  // Squeeze, from X^A_11 = g1/xi + g2 ln(1/xi) (Jeffrey & Onishi 1984, J. Fluid Mech. 139, 261;
  // Kim & Karrila 1991, ch. 11):
  //   g1 = 2 lam^2/(1+lam)^3,  g2 = lam (1 + 7 lam + lam^2)/(5 (1+lam)^3),  scale 6 pi mu a_i.
  // At lam = 1: 1/(4 xi) + (9/40) ln(1/xi)  (physics-reference-values §2b).
  const double g1 = 2.0 * lam * lam / (opl * opl * opl);
  const double g2 = lam * (1.0 + 7.0 * lam + lam * lam) / (5.0 * opl * opl * opl);
  c.squeeze = 6.0 * kPi * mu * a_i * (g1 / c.xi + g2 * log_inv);

  // Shear, from the log term of Y^A_11: 4 lam (2 + lam + 2 lam^2)/(15 (1+lam)^3), scale 6 pi mu
  // a_i (Jeffrey & Onishi 1984); 1/6 at lam = 1. Acting on the relative tangential velocity at the
  // gap point it also gives the leading logs of Y^B_11, Y^B_12 and the co-rotation part of Y^C.
  const double shear_log = 4.0 * lam * (2.0 + lam + 2.0 * lam * lam) / (15.0 * opl * opl * opl);
  c.shear = 6.0 * kPi * mu * a_i * shear_log * log_inv;

  // Lever arms from each centre to the common point of the gap, splitting r in the ratio of the
  // radii: l_i + l_j = r keeps the shear mode blind to rigid rotation (angular momentum); with
  // c_sh this also gives Y^B_11 = -ln(1/xi)/4 - xi ln(1/xi)/8 exactly (reference §2b). LAMMPS
  // uses the radii.
  if (options.lever == Lever::Centre) {
    c.lever_i = r * a_i / (a_i + a_j);
    c.lever_j = r * a_j / (a_i + a_j);
  } else {
    c.lever_i = a_i;
    c.lever_j = a_j;
  }

  const double a_h = 2.0 * a_i * a_j / (a_i + a_j);  // = a at lam = 1
  if (options.pump == PumpForm::JeffreyOnishi) {
    // Pump: the rest of the self-rotation log of Y^C_11 = 2 lam/(5 (1+lam)) ln(1/xi) (scale
    // 8 pi mu a_i^3, Jeffrey & Onishi 1984) after the shear mode's c_sh a_i^2; symmetrised over i <-> j.
    // At lam = 1: 8 pi mu a^3 (1/5 - 1/8) = 8 pi mu a^3 (3/40) ln(1/xi) (reference §2d), which also
    // reproduces Y^C_12 = (1/20) ln(1/xi) exactly.
    const double lam_j = 1.0 / lam;
    const double self_i = 8.0 * kPi * mu * a_i * a_i * a_i * 2.0 * lam / (5.0 * opl) * log_inv;
    const double self_j = 8.0 * kPi * mu * a_j * a_j * a_j * 2.0 * lam_j / (5.0 * (1.0 + lam_j)) * log_inv;
    const double shear_i = c.shear * a_i * a_i;
    const double shear_j = c.shear * a_j * a_j;
    c.pump = std::max(0.0, 0.5 * ((self_i - shear_i) + (self_j - shear_j)));
  } else if (options.pump == PumpForm::Lammps) {
    // LAMMPS pair lubricateU (mono): a_pu = 8 pi mu a^3 (3/160) ln(1/xi), a quarter of the JO value.
    c.pump = 8.0 * kPi * mu * a_h * a_h * a_h * (3.0 / 160.0) * log_inv;
  }

  if (options.twist) {
    // Twist: X^C has no singular term at lam = 1; use the JO contact value of counter-rotation
    // about d, X^C_11 - X^C_12 -> 7 zeta(3)/8 + zeta(3)/8 = zeta(3) (reference §2b), minus the
    // isolated-sphere 1 that R_0 already carries. Counter-rotation with w_j = -w_i gives the
    // torque 2 c_tw w_i, hence c_tw = 8 pi mu a^3 (zeta(3) - 1)/2. For lam != 1 the radius is the
    // harmonic mean a_h (a modelling choice; only lam = 1 is validated).
    c.twist = 8.0 * kPi * mu * a_h * a_h * a_h * 0.5 * (kZeta3 - 1.0);
  }

  c.taper = taper_factor(r / abar, options);
  if (c.taper != 1.0) {
    c.squeeze *= c.taper;
    c.shear *= c.taper;
    c.pump *= c.taper;
    c.twist *= c.taper;
  }
  return c;
}

void LubricationPair::rows(double a_i, double a_j, const Vec3& r, double mu,
                           const LubricationOptions& options, PairRows& S) {
  LubricationCoefficients c;
  rows(a_i, a_j, r, mu, options, S, c);
}

namespace {
// The twelve 3 x 3 corners of a centred pair's Gram blocks ii, jj, ij, each handed as it is formed
// to put_ii / put_jj / put_ij(row, column, value): centred_gram assigns them, add_centred_gram adds
// them to R's blocks, so both give the same values element for element.
template <class PutII, class PutJJ, class PutIJ>
void centred_corners(const Vec3& d, const LubricationCoefficients& c, double w, const PutII& put_ii,
                     const PutJJ& put_jj, const PutIJ& put_ij) {
  const double sq = w * c.squeeze, sh = w * c.shear, pu = w * c.pump, tw = w * c.twist;
  const Eigen::Matrix3d dd = d * d.transpose();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - dd;
  const Eigen::Matrix3d D = cross_matrix(d);
  const Eigen::Matrix3d uu = sq * dd + sh * P;
  const double li = c.lever_i, lj = c.lever_j;
  put_ii(0, 0, uu);
  put_ii(0, 3, -(sh * li) * D);
  put_ii(3, 0, (sh * li) * D);
  put_ii(3, 3, (sh * li * li + pu) * P + tw * dd);
  put_jj(0, 0, uu);
  put_jj(0, 3, (sh * lj) * D);
  put_jj(3, 0, -(sh * lj) * D);
  put_jj(3, 3, (sh * lj * lj + pu) * P + tw * dd);
  put_ij(0, 0, -uu);
  put_ij(0, 3, -(sh * lj) * D);
  put_ij(3, 0, -(sh * li) * D);
  put_ij(3, 3, (sh * li * lj - pu) * P - tw * dd);
}

}  // namespace

void LubricationPair::centred_gram(const Vec3& d, const LubricationCoefficients& c, double w, Mat6& ii,
                                   Mat6& jj, Mat6& ij) {
  centred_corners(d, c, w, assigning(ii), assigning(jj), assigning(ij));
}

void LubricationPair::add_centred_gram(const Vec3& d, const LubricationCoefficients& c, double w, Mat6& Rii,
                                       Mat6& Rjj, Mat6& Rij, bool assign_ij) {
  if (assign_ij)
    centred_corners(d, c, w, adding(Rii), adding(Rjj), assigning(Rij));
  else
    centred_corners(d, c, w, adding(Rii), adding(Rjj), adding(Rij));
}

namespace {
// The translational part of centred_wrench: the tangential t = c_sh (P du + l_i d x w_i + l_j d x w_j)
// and the force f = c_sq (d.du) d + t on node j's velocity (both weighted by w).
struct CentredForce {
  Vec3 t, f;
};
CentredForce centred_force_parts(const Vec3& d, const LubricationCoefficients& c, double w,
                                 const Eigen::Matrix<double, 12, 1>& v) {
  const Vec3 du = v.segment<3>(6) - v.segment<3>(0);
  const Vec3 wi = v.segment<3>(3), wj = v.segment<3>(9);
  const double d_du = d.dot(du);
  // Tangential parts: P du = du - (d.du) d; d x w is tangential already.
  const Vec3 t = (w * c.shear) * (du - d_du * d + c.lever_i * d.cross(wi) + c.lever_j * d.cross(wj));
  return {t, (w * c.squeeze * d_du) * d + t};
}
}  // namespace

Eigen::Matrix<double, 12, 1> LubricationPair::centred_wrench(const Vec3& d, const LubricationCoefficients& c,
                                                             double w,
                                                             const Eigen::Matrix<double, 12, 1>& v) {
  const auto [t, f] = centred_force_parts(d, c, w, v);  // (S^T S v) on u_j; minus it on u_i
  const Vec3 dw = v.segment<3>(3) - v.segment<3>(9);
  const double d_dw = d.dot(dw);
  const Vec3 rot = (w * c.pump) * (dw - d_dw * d) + (w * c.twist * d_dw) * d;
  const Vec3 dxt = d.cross(t);
  Eigen::Matrix<double, 12, 1> out;
  out << f, c.lever_i * dxt - rot, -f, c.lever_j * dxt + rot;  // -S^T S v
  return out;
}

Vec3 LubricationPair::centred_force_j(const Vec3& d, const LubricationCoefficients& c, double w,
                                      const Eigen::Matrix<double, 12, 1>& v) {
  return -centred_force_parts(d, c, w, v).f;
}

Eigen::Matrix<double, 12, 1> LubricationPair::centred_strain_wrench(const Vec3& d,
                                                                    const LubricationCoefficients& c,
                                                                    double w, const Vec3& du) {
  const double d_du = d.dot(du);
  const Vec3 t = (w * c.shear) * (du - d_du * d);
  const Vec3 f = (w * c.squeeze * d_du) * d + t;
  const Vec3 dxt = d.cross(t);
  Eigen::Matrix<double, 12, 1> out;
  out << f, c.lever_i * dxt, -f, c.lever_j * dxt;
  return out;
}

Eigen::Matrix<double, 12, 1> LubricationPair::centred_noise(const Vec3& d, const LubricationCoefficients& c,
                                                            double w,
                                                            const Eigen::Matrix<double, kRows, 1>& beta) {
  // Square roots taken as rows() takes them (sqrt(c_m), then sqrt(w)), so that both paths scale alike.
  const double sw = std::sqrt(w);
  const double s_sq = std::sqrt(c.squeeze) * sw, s_sh = std::sqrt(c.shear) * sw;
  const double s_pu = std::sqrt(c.pump) * sw, s_tw = std::sqrt(c.twist) * sw;
  const Vec3 b = beta.segment<3>(1), p = beta.segment<3>(4);
  const Vec3 u = (s_sq * beta[0]) * d + s_sh * (b - d.dot(b) * d);
  const Vec3 rot = s_pu * (p - d.dot(p) * d) + (s_tw * beta[7]) * d;
  const Vec3 dxb = s_sh * d.cross(b);
  Eigen::Matrix<double, 12, 1> out;
  out << -u, rot - c.lever_i * dxb, u, -c.lever_j * dxb - rot;
  return out;
}

void LubricationPair::rows(double a_i, double a_j, const Vec3& r, double mu,
                           const LubricationOptions& options, PairRows& S, LubricationCoefficients& c) {
  const double dist = r.norm();
  c = coefficients(a_i, a_j, dist, mu, options);
  rows(r / dist, c, S);
}

void LubricationPair::rows(const Vec3& d, const LubricationCoefficients& c, PairRows& S) {
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
  const Eigen::Matrix3d D = cross_matrix(d);  // D w = d x w

  S.setZero();
  const double s_sq = std::sqrt(c.squeeze);
  S.block<1, 3>(0, 0) = -s_sq * d.transpose();
  S.block<1, 3>(0, 6) = s_sq * d.transpose();

  // P (u_j - u_i) + l_i d x w_i + l_j d x w_j  (the w-terms are already tangential).
  const double s_sh = std::sqrt(c.shear);
  S.block<3, 3>(1, 0) = -s_sh * P;
  S.block<3, 3>(1, 3) = s_sh * c.lever_i * D;
  S.block<3, 3>(1, 6) = s_sh * P;
  S.block<3, 3>(1, 9) = s_sh * c.lever_j * D;

  const double s_pu = std::sqrt(c.pump);
  S.block<3, 3>(4, 3) = s_pu * P;
  S.block<3, 3>(4, 9) = -s_pu * P;

  const double s_tw = std::sqrt(c.twist);
  S.block<1, 3>(7, 3) = s_tw * d.transpose();
  S.block<1, 3>(7, 9) = -s_tw * d.transpose();
}

}  // namespace fldsim::hydro
