// Lubrication pair modes against an independent Jeffrey–Onishi (1984) two-sphere resistance
// matrix built from the scalar functions X^A, Y^A, Y^B, X^C, Y^C (physics-reference-values
// §2a/§2b), and against the tabulated asymptotic values of §2c.
#include <gtest/gtest.h>

#include <cmath>

#include "HydroTestSupport.hpp"
#include "fldsim-sdk/lubrication/LubricationPair.hpp"

using namespace fldsim;
using namespace fldsim::hydro;
using test::kPi;

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
constexpr double kZeta3 = 1.2020569031595942;

// Resistance scalars of two equal spheres, JO normalisation (A: 6 pi mu a, B: 4 pi mu a^2,
// C: 8 pi mu a^3), without the isolated-sphere parts.
struct JOScalars {
  double XA11 = 0, XA12 = 0, YA11 = 0, YA12 = 0, YB11 = 0, YB12 = 0, XC11 = 0, XC12 = 0, YC11 = 0, YC12 = 0;
};

Eigen::Matrix3d eps_dot(const Vec3& d) {  // (eps . d)_ij = eps_ijk d_k
  Eigen::Matrix3d m;
  m << 0, d.z(), -d.y(), -d.z(), 0, d.x(), d.y(), -d.x(), 0;
  return m;
}

// (F1, L1, F2, L2) = -R (U1, W1, U2, W2), d from sphere 1 to sphere 2 (Kim & Karrila 1991 ch. 11):
//   A^ab = X^A_ab dd + Y^A_ab (I - dd),  B^ab = Y^B_ab eps.d,  C^ab = X^C_ab dd + Y^C_ab (I - dd),
//   F_a = A^ab U_b + (B^ba)^T W_b,  L_a = B^ab U_b + C^ab W_b,
// with, for equal spheres, A^22 = A^11, A^21 = A^12, C likewise, Y^B_22 = -Y^B_11, Y^B_21 = -Y^B_12.
Mat12 jo_matrix(const JOScalars& s, const Vec3& d, double mu, double a) {
  const Eigen::Matrix3d dd = d * d.transpose(), P = Eigen::Matrix3d::Identity() - dd, e = eps_dot(d);
  const double sA = 6 * kPi * mu * a, sB = 4 * kPi * mu * a * a, sC = 8 * kPi * mu * a * a * a;
  Eigen::Matrix3d A[2][2], B[2][2], C[2][2];
  A[0][0] = A[1][1] = sA * (s.XA11 * dd + s.YA11 * P);
  A[0][1] = A[1][0] = sA * (s.XA12 * dd + s.YA12 * P);
  C[0][0] = C[1][1] = sC * (s.XC11 * dd + s.YC11 * P);
  C[0][1] = C[1][0] = sC * (s.XC12 * dd + s.YC12 * P);
  B[0][0] = sB * s.YB11 * e;
  B[1][1] = -sB * s.YB11 * e;
  B[0][1] = sB * s.YB12 * e;
  B[1][0] = -sB * s.YB12 * e;
  Mat12 R;
  for (int al = 0; al < 2; ++al)
    for (int be = 0; be < 2; ++be) {
      R.block<3, 3>(6 * al, 6 * be) = A[al][be];
      R.block<3, 3>(6 * al, 6 * be + 3) = B[be][al].transpose();
      R.block<3, 3>(6 * al + 3, 6 * be) = B[al][be];
      R.block<3, 3>(6 * al + 3, 6 * be + 3) = C[al][be];
    }
  return R;
}

// Singular JO terms at gap xi (reference §2b), with the xi ln(1/xi) terms of Y^B and Y^C.
JOScalars jo_singular(double xi) {
  const double L = std::log(1.0 / xi);
  JOScalars s;
  s.XA11 = 1.0 / (4 * xi) + 9.0 / 40 * L;
  s.XA12 = -s.XA11;
  s.YA11 = L / 6;
  s.YA12 = -L / 6;
  s.YB11 = -L / 4 - xi * L / 8;
  s.YB12 = L / 4 + xi * L / 8;
  s.YC11 = L / 5 + 47.0 / 250 * xi * L;
  s.YC12 = L / 20 + 31.0 / 500 * xi * L;
  // Contact values of X^C less the isolated sphere: X^C_11 -> 7 zeta(3)/8, X^C_12 -> -zeta(3)/8.
  s.XC11 = 7 * kZeta3 / 8 - 1;
  s.XC12 = -kZeta3 / 8;
  return s;
}

Vec12 pair_wrench(const PairRows& S, const Vec12& v) {
  return -(S.transpose() * (S * v));
}

struct Case {
  double xi;
  Vec3 d, t;  // line of centres and a unit tangent
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const Vec3 d = Vec3(0.3, -0.5, 0.81).normalized();
  const Vec3 t = d.cross(Vec3(1, 0, 0)).normalized();
  for (double xi : {0.001, 0.01, 0.05}) out.push_back({xi, d, t});
  return out;
}

constexpr double kMu = 1.0 / (6.0 * kPi);
constexpr double kRoundOff = 1e-12;

}  // namespace

TEST(LubricationPair, ModesMatchJeffreyOnishiSingularTerms) {
  LubricationOptions opt;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.xi);
    const double a = 1.0, r = 2.0 + c.xi;
    PairRows S;
    LubricationPair::rows(a, a, r * c.d, kMu, opt, S);
    const Mat12 R = jo_matrix(jo_singular(c.xi), c.d, kMu, a);
    const double L = std::log(1.0 / c.xi);
    const double sC = 8 * kPi * kMu;
    auto check = [&](const Vec12& v, const Vec12& expected_difference, const char* mode) {
      SCOPED_TRACE(mode);
      const Vec12 mine = pair_wrench(S, v), jo = -R * v;
      EXPECT_LT((mine - jo - expected_difference).norm(), kRoundOff * jo.norm()) << mine.transpose() << "\n"
                                                                                 << jo.transpose();
    };
    Vec12 v;
    // Squeeze: equal and opposite normal velocities (X^A).
    v << c.d, Vec3::Zero(), -c.d, Vec3::Zero();
    check(v, Vec12::Zero(), "squeeze");
    // Sliding: sphere 1 translates tangentially (Y^A, Y^B including its xi ln(1/xi) term, which the
    // gap-point lever arm l = r/2 = a (1 + xi/2) reproduces exactly).
    v << c.t, Vec3::Zero(), Vec3::Zero(), Vec3::Zero();
    check(v, Vec12::Zero(), "sliding");
    // Co-rotation about t: forces from Y^B exact; torques (Y^C_11 + Y^C_12) = (1/4)(1 + xi) ln(1/xi)
    // in JO, (1/4)(1 + xi/2)^2 ln(1/xi) here: the model differs by 8 pi mu a^3 (xi^2/16) ln(1/xi).
    v << Vec3::Zero(), c.t, Vec3::Zero(), c.t;
    Vec12 diff = Vec12::Zero();
    diff.segment<3>(3) = diff.segment<3>(9) = -sC * c.xi * c.xi / 16 * L * c.t;
    check(v, diff, "co-rotation");
    // Counter-rotation about t: the pump gives the leading 3/20 ln(1/xi) of Y^C_11 - Y^C_12 but not
    // JO's (47/250 - 31/500) xi ln(1/xi) = (63/500) xi ln(1/xi).
    v << Vec3::Zero(), c.t, Vec3::Zero(), -c.t;
    diff.setZero();
    diff.segment<3>(3) = sC * 63.0 / 500 * c.xi * L * c.t;
    diff.segment<3>(9) = -diff.segment<3>(3);
    check(v, diff, "counter-rotation");
    // Twist: counter-rotation about d, JO contact value zeta(3) - 1 (beyond the isolated sphere).
    v << Vec3::Zero(), c.d, Vec3::Zero(), -c.d;
    check(v, Vec12::Zero(), "twist");
  }
}

TEST(LubricationPair, CoefficientsReproduceTabulatedAsymptotics) {
  // Reference §2c "asymptotic values for unit tests" (JO units, 5 decimals) at xi = 0.001, 0.01,
  // 0.05; the model carries only the singular terms, so add the O(1) constants of §2b (and the
  // xi ln(1/xi) term of X^A). Tolerance 1e-5: the table's last digit.
  const double XA11[] = {252.54985, 27.03282, 6.67347};
  const double YA11[] = {2.14961, 1.76585, 1.49761};
  const double YB11[] = {-1.48888, -0.91813, -0.52874};
  const double xis[] = {0.001, 0.01, 0.05};
  for (int k = 0; k < 3; ++k) {
    const double xi = xis[k], L = std::log(1.0 / xi);
    const auto c = LubricationPair::coefficients(1.0, 1.0, 2.0 + xi, kMu, LubricationOptions{});
    EXPECT_NEAR(c.squeeze / (6 * kPi * kMu) + 0.995419 + 3.0 / 112 * xi * L, XA11[k], 1e-5);
    EXPECT_NEAR(c.shear / (6 * kPi * kMu) + 0.998317, YA11[k], 1e-5);
    // Torque on sphere 1 per unit sliding velocity: c_sh l; JO L_1 = -4 pi mu a^2 Y^B_11 (U x d).
    EXPECT_NEAR(-c.shear * c.lever_i / (4 * kPi * kMu) + 0.238920, YB11[k], 1e-5);
  }
}

TEST(LubricationPair, LammpsPumpIsAQuarterOfJeffreyOnishi) {
  LubricationOptions jo, lmp;
  lmp.pump = PumpForm::Lammps;
  const auto a = LubricationPair::coefficients(1.0, 1.0, 2.01, kMu, jo);
  const auto b = LubricationPair::coefficients(1.0, 1.0, 2.01, kMu, lmp);
  // 8 pi mu a^3 (3/40) ln(1/xi) vs LAMMPS 8 pi mu a^3 (3/160) ln(1/xi) (reference §2d).
  EXPECT_NEAR(b.pump / a.pump, 0.25, 1e-14);
  EXPECT_NEAR(a.pump, 8 * kPi * kMu * 3.0 / 40 * std::log(100.0), 1e-13);
  // The ablation: no pump mode, every other coefficient as with Jeffrey-Onishi's.
  LubricationOptions none;
  none.pump = PumpForm::None;
  const auto c = LubricationPair::coefficients(1.0, 1.0, 2.01, kMu, none);
  EXPECT_EQ(c.pump, 0.0);
  EXPECT_EQ(c.squeeze, a.squeeze);
  EXPECT_EQ(c.shear, a.shear);
  EXPECT_EQ(c.twist, a.twist);
}

TEST(LubricationPair, WithoutLogTermsOnlyTheSqueezeSingularityIsLeft) {
  // log_terms false (LAMMPS flaglog 0): X^A's 1/(4 xi) alone, at any gap; no shear or pump mode;
  // the twist (a contact constant, not a log term) as `twist` says. Both pump forms.
  for (PumpForm pump : {PumpForm::JeffreyOnishi, PumpForm::Lammps}) {
    LubricationOptions opt;
    opt.log_terms = false;
    opt.pump = pump;
    LubricationOptions with_logs = opt;
    with_logs.log_terms = true;
    for (double xi : {1e-4, 0.01, 0.3}) {
      const auto c = LubricationPair::coefficients(1.0, 1.0, 2.0 + xi, kMu, opt);
      const auto l = LubricationPair::coefficients(1.0, 1.0, 2.0 + xi, kMu, with_logs);
      EXPECT_NEAR(c.squeeze, 6 * kPi * kMu / (4 * xi), 1e-12 / xi);
      EXPECT_NEAR(l.squeeze - c.squeeze, 6 * kPi * kMu * 9.0 / 40 * std::log(1.0 / xi), 1e-12 / xi);
      EXPECT_EQ(c.shear, 0.0);
      EXPECT_EQ(c.pump, 0.0);
      EXPECT_EQ(c.twist, l.twist);
      EXPECT_GT(l.shear, 0.0);
    }
  }
}

TEST(LubricationPair, GapFloorAndLogCutoff) {
  LubricationOptions opt;
  opt.delta_num = 1.0 / 64;  // exactly representable, as is 2 + 1/64
  // Overlapping or closer than delta_num: evaluated at delta_num.
  const auto o = LubricationPair::coefficients(1.0, 1.0, 1.99, kMu, opt);
  const auto f = LubricationPair::coefficients(1.0, 1.0, 2.0 + 1.0 / 64, kMu, opt);
  EXPECT_EQ(o.xi, 1.0 / 64);
  EXPECT_EQ(o.squeeze, f.squeeze);
  EXPECT_EQ(o.shear, f.shear);
  // xi >= 1: log terms vanish, squeeze keeps 6 pi mu a /(4 xi).
  const auto far = LubricationPair::coefficients(1.0, 1.0, 3.2, kMu, opt);
  EXPECT_EQ(far.shear, 0.0);
  EXPECT_EQ(far.pump, 0.0);
  EXPECT_NEAR(far.squeeze, 6 * kPi * kMu / (4 * 1.2), 1e-15);
}

TEST(LubricationPair, RigidMotionsAreAnnihilatedAndRadiiSymmetric) {
  LubricationOptions opt;
  for (double aj : {1.0, 0.5, 2.0}) {
    const double ai = 1.0;
    const Vec3 r = Vec3(0.4, 1.2, -0.7).normalized() * (ai + aj + 0.03);
    PairRows S;
    LubricationPair::rows(ai, aj, r, kMu, opt, S);
    // Rigid motion of the pair: u = V + Omega x x, w = Omega with x_i = 0, x_j = r: no mode is
    // excited (force- and torque-free pair interaction; momentum conservation).
    const Vec3 V(0.3, -1.1, 0.2), W(-0.7, 0.4, 0.9);
    Vec12 v;
    v << V, W, V + W.cross(r), W;
    EXPECT_LT((S * v).norm(), 1e-13 * S.norm() * v.norm());
    // Swapping the spheres (i <-> j, r -> -r) gives the same coefficients.
    const auto c1 = LubricationPair::coefficients(ai, aj, r.norm(), kMu, opt);
    const auto c2 = LubricationPair::coefficients(aj, ai, r.norm(), kMu, opt);
    EXPECT_NEAR(c1.squeeze, c2.squeeze, 1e-12 * c1.squeeze);
    EXPECT_NEAR(c1.shear, c2.shear, 1e-12 * c1.shear);
    EXPECT_NEAR(c1.pump, c2.pump, 1e-12 * c1.pump);
    EXPECT_GT(c1.pump, 0.0);
    EXPECT_NEAR(c1.lever_i + c1.lever_j, r.norm(), 1e-14);
  }
}

TEST(LubricationPair, TaperTakesEveryCoefficientSmoothlyToZeroAtTheCutoff) {
  LubricationOptions opt;
  opt.cutoff = 2.5;
  opt.taper_width = 0.3;
  const auto at = [&](double r) { return LubricationPair::coefficients(1.0, 1.0, r, kMu, opt); };
  LubricationOptions abrupt = opt;
  abrupt.taper_width = 0.0;
  // Below the window: untouched. At the cutoff: every mode vanishes.
  const auto inside = at(2.19), plain = LubricationPair::coefficients(1.0, 1.0, 2.19, kMu, abrupt);
  EXPECT_EQ(inside.squeeze, plain.squeeze);
  EXPECT_EQ(inside.pump, plain.pump);
  const auto edge = at(2.5);
  EXPECT_EQ(edge.squeeze, 0.0);
  EXPECT_EQ(edge.shear, 0.0);
  EXPECT_EQ(edge.pump, 0.0);
  EXPECT_EQ(edge.twist, 0.0);
  // C2 at both ends of the window: one-sided first and second differences of T(r) vanish like h
  // and 1 (smoothstep 1 - s^3 (10 - 15 s + 6 s^2): T' = -30 s^2 (1-s)^2 / w, T'' ~ s and (1-s)).
  const double h = 1e-4;
  for (double r0 : {2.2, 2.5}) {
    SCOPED_TRACE(r0);
    const double t0 = taper_factor(r0, opt);
    const double d1 = (taper_factor(r0 + h, opt) - taper_factor(r0 - h, opt)) / (2 * h);
    const double d2 = (taper_factor(r0 + h, opt) - 2 * t0 + taper_factor(r0 - h, opt)) / (h * h);
    EXPECT_LT(std::abs(d1), 30 * h * h / (0.3 * 0.3 * 0.3) * 2);
    EXPECT_LT(std::abs(d2), 60 * h / (0.3 * 0.3 * 0.3) * 2);
  }
  // Never negative, also in rounding just below the cutoff (the rows take sqrt(c T)); a run of
  // 512 spheres hit a NaN from 1 - s^3 (10 - 15 s + 6 s^2) < 0 there.
  for (int k = 0; k <= 100000; ++k) {
    const double r = 2.5 - 1e-3 * k / 100000.0;
    ASSERT_GE(taper_factor(r, opt), 0.0) << r;
    ASSERT_FALSE(std::isnan(std::sqrt(at(r).squeeze))) << r;
  }
  // Mid-window: T = 1/2 and the slope is the smoothstep's -15/(8 w); the central difference is off
  // by at most h^2 max|T'''|/6 = h^2 (60/w^3)/6.
  EXPECT_NEAR(taper_factor(2.35, opt), 0.5, 1e-14);
  const double slope = (taper_factor(2.35 + h, opt) - taper_factor(2.35 - h, opt)) / (2 * h);
  EXPECT_NEAR(slope, -15.0 / (8 * 0.3), h * h * 10 / (0.3 * 0.3 * 0.3));
}

TEST(LubricationPair, ContactLeverIsTheRadiusAndOnlyTheCentreLeverKeepsRigidRotationFree) {
  LubricationOptions centre, contact;
  contact.lever = Lever::Contact;
  const double r = 2.3;
  const auto c = LubricationPair::coefficients(1.0, 1.0, r, kMu, contact);
  EXPECT_EQ(c.lever_i, 1.0);
  EXPECT_EQ(c.lever_j, 1.0);
  // A pair rotating rigidly (u_j - u_i = W x r, w_i = w_j = W, W perpendicular to r) excites the
  // shear mode with the contact lever by c_sh (r - 2a) W x d: a force on a rigid rotation.
  const Vec3 d(0, 1, 0), W(0, 0, 1.0);
  Vec12 v;
  v << Vec3::Zero(), W, W.cross(r * d), W;
  PairRows S;
  LubricationPair::rows(1.0, 1.0, r * d, kMu, centre, S);
  EXPECT_LT((S * v).norm(), 1e-14);
  LubricationPair::rows(1.0, 1.0, r * d, kMu, contact, S);
  const Vec12 f = pair_wrench(S, v);
  EXPECT_NEAR(f.segment<3>(6).norm(), c.shear * (r - 2.0), 1e-12 * c.shear);
}

namespace {
// A centred pair as BodyResistance's sphere path sees it, for the closed-form tests below.
struct CentredCase {
  Vec3 r;                     // separation x_j - x_i
  PairRows S;                 // rows() at r
  LubricationCoefficients c;  // the coefficients rows() used
  double w;                   // visibility weight
};

// Every option set (pump, twist, lever, taper), equal and unequal radii, gaps from below the
// floor to the taper, random directions, weights 1 and 0.37: 640 cases, each passed to check.
template <class Check>
int for_centred_cases(std::mt19937_64& rng, Check check) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), gap(0.0, 0.49);
  int checked = 0;
  for (const PumpForm pump : {PumpForm::JeffreyOnishi, PumpForm::Lammps})
    for (const bool twist : {true, false})
      for (const Lever lever : {Lever::Centre, Lever::Contact})
        for (const double taper : {0.0, 0.3})
          for (const double a_j : {1.0, 0.7})
            for (int trial = 0; trial < 20; ++trial) {
              LubricationOptions o;
              o.pump = pump;
              o.twist = twist;
              o.lever = lever;
              o.taper_width = taper;
              o.delta_num = 1e-3;
              const double a_i = 1.0, abar = 0.5 * (a_i + a_j);
              Vec3 d(u(rng), u(rng), u(rng));
              d.normalize();
              const double h = trial == 0 ? 1e-4 : gap(rng);  // below the floor once
              CentredCase k;
              k.r = (a_i + a_j + h * abar) * d;
              LubricationPair::rows(a_i, a_j, k.r, 0.3, o, k.S, k.c);
              k.w = trial % 3 == 0 ? 0.37 : 1.0;
              check(k);
              ++checked;
            }
  return checked;
}
}  // namespace

// The closed-form Gram blocks of a centred pair (BodyResistance's path for spheres) against the
// products of the rows they replace; agreement to rounding (1e-14 of the pair's largest entry),
// exact symmetry of the diagonal blocks.
TEST(LubricationPair, CentredGramEqualsTheRowProducts) {
  std::mt19937_64 rng(21);
  const int checked = for_centred_cases(rng, [](const CentredCase& k) {
    Mat6 ii, jj, ij;
    LubricationPair::centred_gram(k.r / k.r.norm(), k.c, k.w, ii, jj, ij);
    const Mat12 G = k.w * k.S.transpose() * k.S;
    const double scale = G.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LE((ii - G.topLeftCorner<6, 6>()).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_LE((jj - G.bottomRightCorner<6, 6>()).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_LE((ij - G.topRightCorner<6, 6>()).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_EQ(ii, ii.transpose());
    EXPECT_EQ(jj, jj.transpose());
  });
  EXPECT_EQ(checked, 640);
}

// add_centred_gram (how BodyResistance::add_to puts a sphere pair into R) gives bit for bit what
// adding centred_gram's blocks gave (or assigning the ij block), starting from random blocks. A
// version that summed a corner's terms in another order, e.g. (sh li li + pu) P + tw dd as
// sh li li P + (pu P + tw dd), differs in the last bits here.
TEST(LubricationPair, AddCentredGramIsAddingTheCentredGramBlocks) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int checked = for_centred_cases(rng, [&](const CentredCase& k) {
    const Vec3 d = k.r / k.r.norm();
    Mat6 ii, jj, ij;
    LubricationPair::centred_gram(d, k.c, k.w, ii, jj, ij);
    const Mat6 Rii = Mat6::NullaryExpr([&]() { return u(rng); });
    const Mat6 Rjj = Mat6::NullaryExpr([&]() { return u(rng); });
    const Mat6 Rij = Mat6::NullaryExpr([&]() { return u(rng); });
    for (const bool assign : {false, true}) {
      Mat6 Aii = Rii, Ajj = Rjj, Aij = Rij;
      LubricationPair::add_centred_gram(d, k.c, k.w, Aii, Ajj, Aij, assign);
      const Mat6 ii_sum = Rii + ii, jj_sum = Rjj + jj, ij_sum = Rij + ij;
      EXPECT_EQ(Aii, ii_sum);
      EXPECT_EQ(Ajj, jj_sum);
      if (assign) {
        EXPECT_EQ(Aij, ij);
      } else {
        EXPECT_EQ(Aij, ij_sum);
      }
    }
  });
  EXPECT_EQ(checked, 640);
}

// The closed-form pair wrench -w S^T S v and Brownian wrench sqrt(w) S^T beta of a centred pair
// (BodyResistance's path for spheres: strain forces, stresslets, Brownian forces) against the
// products of the rows they replace, random velocities and normals; agreement to rounding (1e-14
// of the largest term of the product).
TEST(LubricationPair, CentredWrenchAndNoiseEqualTheRowProducts) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> normal;
  const int checked = for_centred_cases(rng, [&](const CentredCase& k) {
    using Modes = Eigen::Matrix<double, LubricationPair::kRows, 1>;
    const PairRows Sw = std::sqrt(k.w) * k.S;
    const Vec12 v = Vec12::NullaryExpr([&]() { return u(rng); });
    const Modes beta = Modes::NullaryExpr([&]() { return normal(rng); });
    const Vec3 d = k.r / k.r.norm();
    const Vec12 wrench = LubricationPair::centred_wrench(d, k.c, k.w, v);
    const double scale_w = (Sw.transpose() * Sw).cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff();
    ASSERT_GT(scale_w, 0.0);
    EXPECT_LE((wrench + Sw.transpose() * (Sw * v)).cwiseAbs().maxCoeff(), 1e-14 * scale_w);
    // The strain force's special case drops only terms of the zero velocities: the same numbers.
    Vec12 strain = Vec12::Zero();
    strain.segment<3>(6) = v.segment<3>(6);
    const Vec12 by_strain = LubricationPair::centred_strain_wrench(d, k.c, k.w, v.segment<3>(6));
    const Vec12 by_wrench = LubricationPair::centred_wrench(d, k.c, k.w, strain);
    for (int e = 0; e < 12; ++e) EXPECT_EQ(by_strain[e], by_wrench[e]) << "entry " << e;
    const Vec12 noise = LubricationPair::centred_noise(d, k.c, k.w, beta);
    const double scale_n = Sw.cwiseAbs().maxCoeff() * beta.cwiseAbs().maxCoeff();
    EXPECT_LE((noise - Sw.transpose() * beta).cwiseAbs().maxCoeff(), 1e-14 * scale_n);
  });
  EXPECT_EQ(checked, 640);
}
