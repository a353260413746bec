// Properties of the assembled body resistance on random dense configurations (brute-force pair
// lists): SPD, exact pairwise square root, momentum conservation of the pair terms, PCG against a
// dense solve, and the covariance of the Brownian forces.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <sstream>
#include <string>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "HydroTestSupport.hpp"
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"

using namespace fldsim;
using namespace fldsim::hydro;
using namespace fldsim::hydro::test;

namespace {

struct Config {
  const char* name;
  double c;  // < 0: sphere
  std::size_t n;
  double box;
};

std::shared_ptr<const Shape> shape_of(const Config& s) {
  return s.c < 0 ? sphere_shape() : dicolloid_shape(s.c);
}

ModelSettings lubrication_settings() {
  ModelSettings s;
  s.lubrication = true;
  s.isotropic = IsotropicForm::Sphere;
  s.tolerance = 1e-10;
  return s;
}

// Dense enough for many lubricated pairs, small enough for dense eigen-solves; box edges above twice
// the largest centre interaction range 2.5 + c, so minimum images are unique.
const Config kSetups[] = {
    {"spheres", -1.0, 14, 6.0}, {"dicolloid c=0.2", 0.2, 12, 6.2}, {"dicolloid c=1", 1.0, 10, 7.2}};

struct Assembled {
  System system;
  NodePairList pairs;
  std::unique_ptr<ResistanceModel> model;
};

Assembled assemble(const Config& setup, unsigned seed) {
  Assembled a{System(shape_of(setup), setup.n, setup.box, physics(1.0, 1.0, 0.3)), {}, nullptr};
  random_configuration(a.system, 0.01, seed);
  a.model = std::make_unique<ResistanceModel>(lubrication_settings());
  a.pairs = brute_force_pairs(a.system, a.model->pair_range(a.system));
  HydroRequest req;
  req.stresslets = true;
  a.model->configure(a.system, req);
  a.model->assemble(a.system, a.pairs);
  return a;
}

// R_0 of the lubrication model: 6 pi mu a I, 8 pi mu a^3 I per body (a = 1).
Eigen::MatrixXd isotropic_part(const System& s) {
  const double mu = s.physics().viscosity;
  Eigen::VectorXd d(6 * s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    d.segment<6>(6 * i) << Vec3::Constant(6 * kPi * mu), Vec3::Constant(8 * kPi * mu);
  return d.asDiagonal();
}

}  // namespace

TEST(BodyResistance, SymmetricPositiveDefiniteWithExactPairSquareRoot) {
  for (const Config& setup : kSetups) {
    SCOPED_TRACE(setup.name);
    Assembled a = assemble(setup, 17);
    const BodyResistance& lub = a.model->lubrication();
    ASSERT_GE(lub.size(), setup.n) << "configuration not dense enough to test anything";
    const Eigen::MatrixXd R = a.model->resistance().dense();
    EXPECT_EQ((R - R.transpose()).norm(), 0.0);
    const Eigen::MatrixXd Rdelta = R - isotropic_part(a.system);
    // R_delta = sum_p B_p B_p^T with B_p the body-level pair rows transposed.
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(R.rows(), 8 * Eigen::Index(lub.size()));
    for (std::size_t k = 0; k < lub.size(); ++k) {
      const auto [i, j] = lub.bodies(k);
      B.block<6, 8>(6 * i, 8 * k) = lub.rows(k).leftCols<6>().transpose();
      B.block<6, 8>(6 * j, 8 * k) = lub.rows(k).rightCols<6>().transpose();
    }
    EXPECT_LT((B * B.transpose() - Rdelta).norm(), 1e-13 * Rdelta.norm());
    // Weyl: lambda_min(R_0 + R_delta) >= lambda_min(R_0) = min(6 pi mu a, 8 pi mu a^3) = 1 since
    // R_delta is PSD; round-off allowance relative to the largest eigenvalue.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(R);
    const double lmax = eig.eigenvalues().maxCoeff();
    EXPECT_GE(eig.eigenvalues().minCoeff(), 1.0 - 1e-12 * lmax);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_delta(Rdelta);
    EXPECT_GE(eig_delta.eigenvalues().minCoeff(), -1e-12 * lmax);
  }
}

// add_to writes every off-diagonal block of its pattern (assembly does not zero them first): a
// matrix whose values are garbage before add_to ends with the same R_delta as a zeroed one, bit for
// bit, also where several node pairs share a block (dicolloids).
TEST(BodyResistance, AddToWritesEveryOffDiagonalBlock) {
  for (const Config& setup : kSetups) {
    SCOPED_TRACE(setup.name);
    Assembled a = assemble(setup, 17);
    BodyResistance lub = a.model->lubrication();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> upper;
    lub.body_pairs(upper);
    BlockSparseMatrix zeroed, dirty;
    zeroed.set_pattern(a.system.size(), upper);
    dirty.set_pattern(a.system.size(), upper);
    lub.bind(zeroed);
    lub.add_to(zeroed);
    for (std::size_t k = 0; k < dirty.col().size(); ++k) dirty.upper(std::int64_t(k)).setConstant(1e300);
    lub.bind(dirty);
    lub.add_to(dirty);
    ASSERT_GT(zeroed.col().size(), 0u);
    if (setup.c >= 0) EXPECT_LT(zeroed.col().size(), lub.size()) << "no block shared by two node pairs";
    EXPECT_EQ(zeroed.dense(), dirty.dense());
  }
}

TEST(BodyResistance, PairForcesConserveMomentum) {
  for (const Config& setup : kSetups) {
    SCOPED_TRACE(setup.name);
    Assembled a = assemble(setup, 29);
    const BodyResistance& lub = a.model->lubrication();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t k = 0; k < lub.size(); ++k) {
      const auto [i, j] = lub.bodies(k);
      const Vec3 R = a.system.box().minimum_image(a.system.positions()[j] - a.system.positions()[i]);
      Eigen::Matrix<double, 12, 1> v = Eigen::Matrix<double, 12, 1>::NullaryExpr([&]() { return u(rng); });
      const Eigen::Matrix<double, 12, 1> w = -lub.rows(k).transpose() * (lub.rows(k) * v);
      const Vec3 Fi = w.segment<3>(0), Ti = w.segment<3>(3), Fj = w.segment<3>(6), Tj = w.segment<3>(9);
      const double scale = w.norm() * (1.0 + R.norm());
      // Newton's third law and zero total torque about body i's centre.
      EXPECT_LT((Fi + Fj).norm(), 1e-13 * scale);
      EXPECT_LT((Ti + Tj + R.cross(Fj)).norm(), 1e-13 * scale);
      // A rigid motion of the two bodies together excites no mode.
      const Vec3 V(u(rng), u(rng), u(rng)), W(u(rng), u(rng), u(rng));
      v << V, W, V + W.cross(R), W;
      EXPECT_LT((lub.rows(k) * v).norm(), 1e-13 * lub.rows(k).norm() * v.norm());
    }
    // The pair strain forces R_FE:E_inf sum to zero over all bodies (R_0 of a sphere has none).
    Vec3 total = Vec3::Zero();
    double scale = 0.0;
    for (std::size_t i = 0; i < a.system.size(); ++i) {
      total += Eigen::Map<const Vec3>(a.model->strain_force().data() + 6 * i);
      scale += Eigen::Map<const Vec3>(a.model->strain_force().data() + 6 * i).norm();
    }
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(total.norm(), 1e-13 * scale);
  }
}

TEST(ResistanceModel, ConjugateGradientsMatchDenseSolve) {
  for (const Config& setup : kSetups) {
    SCOPED_TRACE(setup.name);
    Assembled a = assemble(setup, 41);
    const Eigen::MatrixXd R = a.model->resistance().dense();
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::VectorXd F = Eigen::VectorXd::NullaryExpr(R.rows(), [&]() { return u(rng); });
    const Eigen::VectorXd rhs =
        F + Eigen::Map<const Eigen::VectorXd>(a.model->strain_force().data(), R.rows());
    const Eigen::VectorXd ref = R.ldlt().solve(rhs);
    Eigen::VectorXd dU = Eigen::VectorXd::Zero(R.rows());
    a.model->solve(a.system, F.data(), dU.data());
    const auto stats = a.model->last_solve();
    EXPECT_GT(stats.iterations, 0);
    EXPECT_LE(stats.residual, 1e-10);
    EXPECT_EQ(stats.pairs, std::int64_t(a.model->lubrication().size()));
    // |x - x*|/|x*| <= cond(R) * relative residual.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(R);
    const double cond = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
    EXPECT_LE((dU - ref).norm() / ref.norm(), cond * stats.residual);
  }
}

TEST(ResistanceModel, BrownianForceCovarianceIsTwoKTOverDtTimesResistance) {
  // Small dense system of 6 spheres: sample F_B over M independent
  // draws (different step numbers of the noise stream) and compare the variance of projections
  // w.F_B with 2 kT/dt w^T R w. Standard error of each variance estimate from the sample variance
  // of (w.F)^2 over the M draws; 3 SE.
  const Config setup{"6 spheres", -1.0, 6, 5.2};
  Assembled a = assemble(setup, 3);
  ASSERT_GE(a.model->lubrication().size(), 3u);
  const Eigen::MatrixXd R = a.model->resistance().dense();
  const Eigen::Index n = R.rows();
  const double dt = 0.01, kT = a.system.physics().kT;
  const int M = 20000;
  std::vector<Eigen::VectorXd> projections;
  for (Eigen::Index k : {0, 4, 7, 15, 22}) projections.push_back(Eigen::VectorXd::Unit(n, k));
  std::mt19937_64 rng(12);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int q = 0; q < 3; ++q)
    projections.push_back(Eigen::VectorXd::NullaryExpr(n, [&]() { return g(rng); }));
  std::vector<double> sum(projections.size(), 0.0), sum2(projections.size(), 0.0);
  Eigen::VectorXd FB(n);
  for (int s = 0; s < M; ++s) {
    const RandomStream noise(2024, RandomPurpose::BodyNoise, std::uint64_t(s));
    a.model->brownian_force(a.system, a.pairs, noise, dt, FB.data());
    for (std::size_t p = 0; p < projections.size(); ++p) {
      const double x = projections[p].dot(FB);
      sum[p] += x * x;
      sum2[p] += x * x * x * x;
    }
  }
  for (std::size_t p = 0; p < projections.size(); ++p) {
    const double mean = sum[p] / M;
    const double se = std::sqrt((sum2[p] / M - mean * mean) / (M - 1));
    const double expected = 2.0 * kT / dt * projections[p].dot(R * projections[p]);
    EXPECT_NEAR(mean, expected, 3.0 * se) << "projection " << p;
  }
}

#ifdef _OPENMP
TEST(ResistanceModel, AssemblyNoiseAndSolveAreIndependentOfThreadCount) {
  // Pair work runs in parallel into per-pair buffers and is summed in pair order: the result must
  // be bitwise identical for 1 and 2 threads.
  const int threads = omp_get_max_threads();
  auto run = [&](int nthreads) {
    omp_set_num_threads(nthreads);
    Assembled a = assemble(kSetups[2], 53);
    const RandomStream noise(7, RandomPurpose::BodyNoise, 11);
    std::vector<double> FB(6 * a.system.size()), dU(6 * a.system.size(), 0.0);
    a.model->brownian_force(a.system, a.pairs, noise, 1e-3, FB.data());
    a.model->solve(a.system, FB.data(), dU.data());
    FB.insert(FB.end(), dU.begin(), dU.end());
    return FB;
  };
  const auto one = run(1), two = run(std::max(2, threads));
  omp_set_num_threads(threads);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) EXPECT_EQ(one[k], two[k]) << k;
}
#endif

// refactor_threshold: an assembly reuses the last preconditioner, within a step and across steps,
// while the diagonal of R has moved little since it was built. That reuse must (1) really happen
// for a small move, (2) leave the answer a converged solve of the *current* matrix, (3) not happen
// for a large move, and (4) survive a checkpoint: a fresh model given the first one's
// save_state() solves bit-identically to it (as `--resume` needs), while a fresh model without it
// does not; a state that does not fit is refused.
// For both preconditioners that are carried (IC(0)'s factor, D-ILU's pivots).
class FactorReuseWith : public ::testing::TestWithParam<Preconditioner> {};

TEST_P(FactorReuseWith, FactorIsReusedWhileRMovesLittleAndSurvivesACheckpoint) {
  const Config setup = kSetups[0];
  auto configuration = [&](unsigned seed) {
    System s(shape_of(setup), setup.n, setup.box, physics(1.0, 1.0, 0.3));
    random_configuration(s, 0.01, seed);
    return s;
  };
  auto moved = [&](System s, unsigned seed) {  // every body moved by at most 2e-4 a per axis
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-2e-4, 2e-4);
    for (Vec3& x : s.positions()) x += Vec3(u(rng), u(rng), u(rng));
    s.update_nodes();
    return s;
  };
  const System A = configuration(41), A1 = moved(A, 1), B = moved(A1, 2), D = configuration(43);
  auto model = [&](double threshold) {
    ModelSettings s = lubrication_settings();
    s.tolerance = 1e-8;
    s.refactor_threshold = threshold;
    s.preconditioner = GetParam();
    auto m = std::make_unique<ResistanceModel>(s);
    HydroRequest req;
    m->configure(A, req);
    return m;
  };
  const double range = model(0.0)->pair_range(A);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> F(6 * setup.n);
  for (double& f : F) f = u(rng);
  auto assemble_at = [&](ResistanceModel& m, System s, std::int64_t step) {
    s.set_step(step);
    m.assemble(s, brute_force_pairs(s, range));
  };
  auto solve = [&](ResistanceModel& m, System s, std::int64_t step) {  // from a zero start
    s.set_step(step);
    std::vector<double> dU(F.size(), 0.0);
    m.solve(s, F.data(), dU.data());
    return dU;
  };
  auto own_factor = [&](const System& s) {  // a model that factors this very matrix
    auto m = model(0.0);
    assemble_at(*m, s, 1);
    return std::make_pair(solve(*m, s, 1), std::move(m));
  };

  // (4) One assembly at step 0 (A), a checkpoint, then step 1 (A1, close to A): A's factor is
  // carried into step 1, and a model restored from the checkpoint does the same, bit for bit.
  auto carried = model(0.25);
  assemble_at(*carried, A, 0);
  const std::vector<double> state = carried->save_state();
  ASSERT_FALSE(state.empty());
  auto restored = model(0.25);
  restored->restore_state(state);
  EXPECT_EQ(restored->save_state(), state);
  assemble_at(*carried, A1, 1);
  const std::vector<double> x_carried = solve(*carried, A1, 1);
  assemble_at(*restored, A1, 1);
  const std::vector<double> x_restored = solve(*restored, A1, 1);
  for (std::size_t k = 0; k < F.size(); ++k) ASSERT_EQ(x_carried[k], x_restored[k]) << k;
  const std::vector<double> x_fresh = own_factor(A1).first;  // a resume without the state
  EXPECT_LE(carried->last_solve().residual, 1e-8);
  EXPECT_NE(x_carried, x_fresh) << "step 1 did not reuse step 0's factor";
  std::vector<double> truncated(state.begin(), state.end() - 1), other_n = state;
  other_n[0] += 1.0;
  EXPECT_THROW(model(0.25)->restore_state(truncated), Error);
  EXPECT_THROW(model(0.25)->restore_state(other_n), Error);

  // (1), (2) Second assembly of step 1 (B, moved little) reuses the factor still (A's): converged
  // on B's matrix, close to a solve with B's own factor but not bit-identical to it.
  assemble_at(*carried, B, 1);
  const std::vector<double> x_reused = solve(*carried, B, 1);
  const auto [x_own, own] = own_factor(B);
  EXPECT_LE(carried->last_solve().residual, 1e-8);
  const Eigen::MatrixXd R = own->resistance().dense();
  const Eigen::Index n6 = Eigen::Index(F.size());
  const Eigen::Map<const Eigen::VectorXd> xr(x_reused.data(), n6), xo(x_own.data(), n6);
  const Eigen::VectorXd f = Eigen::Map<const Eigen::VectorXd>(F.data(), n6) +
                            Eigen::Map<const Eigen::VectorXd>(own->strain_force().data(), n6);
  EXPECT_LE((R * xr - f).norm(), 1e-8 * f.norm() * (1.0 + 1e-6));  // B's matrix, not A1's
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(R);
  const double cond = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
  EXPECT_LE((xr - xo).norm() / xo.norm(), 2.0 * cond * 1e-8);
  EXPECT_NE((xr - xo).norm(), 0.0) << "the second assembly of the step did not reuse the factor";

  // (3) Third assembly of step 1 (D, another configuration): a new factor, built from D's matrix
  // (the saved states hold the same matrix as a model that factors D). D-ILU then solves D exactly
  // as that model; IC(0) keeps the row order it computed for A (it is renewed every 100
  // factorisations, CuthillMcKee.hpp), so only to the tolerance.
  assemble_at(*carried, D, 1);
  const std::vector<double> x_D = solve(*carried, D, 1);
  EXPECT_LE(carried->last_solve().residual, 1e-8);
  const auto [x_D_own, own_D] = own_factor(D);
  const std::vector<double> state_D = carried->save_state(), state_own = own_D->save_state();
  const std::size_t m_D = std::size_t(state_D.at(2)), matrix_end = 3 + 2 * m_D + 36 * (setup.n + m_D);
  ASSERT_GE(state_own.size(), matrix_end);
  ASSERT_GE(state_D.size(), matrix_end);
  EXPECT_TRUE(std::equal(state_D.begin(), state_D.begin() + std::ptrdiff_t(matrix_end), state_own.begin()))
      << "the third assembly did not factor D";
  if (GetParam() == Preconditioner::EisenstatDilu)
    for (std::size_t k = 0; k < F.size(); ++k) ASSERT_EQ(x_D[k], x_D_own[k]) << k;
  // A checkpoint taken now holds an IC(0) row order that is not D's own: restored, the model
  // solves D bit for bit as the carried one (without the order in the state it would not).
  auto restored_D = model(0.25);
  restored_D->restore_state(state_D);
  assemble_at(*restored_D, D, 1);
  const std::vector<double> x_D_restored = solve(*restored_D, D, 1);
  for (std::size_t k = 0; k < F.size(); ++k) ASSERT_EQ(x_D[k], x_D_restored[k]) << k;
}

// A model that builds a new factor swaps its two matrices instead of copying R (the factor's source
// is the R just assembled; the next assembly writes the other one, giving it the current pattern
// if it holds an older one). Through configurations whose pair sets differ and repeat, every
// assembly's R must be bit for bit that of a fresh model assembled at that configuration alone
// (exact oracle: the same arithmetic), and the solve must satisfy that R to the CG tolerance (not
// bit for bit: IC(0) keeps the row order of the first matrix, CuthillMcKee.hpp). Without the
// pattern hand-over (the matrix written with its older pattern) the fifth assembly fails - shown.
TEST(ResistanceModel, AlternatingMatricesHoldTheCurrentR) {
  for (const Config& setup : kSetups) {
    SCOPED_TRACE(setup.name);
    auto configuration = [&](unsigned seed) {
      System s(shape_of(setup), setup.n, setup.box, physics(1.0, 1.0, 0.3));
      random_configuration(s, 0.01, seed);
      return s;
    };
    const System A = configuration(41), D = configuration(43), E = configuration(47);
    auto model = [&] {
      ModelSettings s = lubrication_settings();
      s.refactor_threshold = 0.0;  // a new factor, so a swap, at every assembly
      s.tolerance = 1e-10;
      auto m = std::make_unique<ResistanceModel>(s);
      m->configure(A, HydroRequest{});
      return m;
    };
    const double range = model()->pair_range(A);
    std::vector<double> F(6 * setup.n);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (double& f : F) f = u(rng);
    auto run = [&](ResistanceModel& m, const System& s) {
      m.assemble(s, brute_force_pairs(s, range));
      std::vector<double> dU(F.size(), 0.0);
      m.solve(s, F.data(), dU.data());
      return dU;
    };
    auto carried = model();
    int step = 0;
    for (const System* s : {&A, &A, &D, &E, &E, &A, &D, &D}) {
      SCOPED_TRACE("assembly " + std::to_string(step++));
      const std::vector<double> x = run(*carried, *s);
      auto fresh = model();
      fresh->assemble(*s, brute_force_pairs(*s, range));  // the oracle's R
      const Eigen::MatrixXd R = fresh->resistance().dense();
      ASSERT_EQ(carried->resistance().dense(), R);
      ASSERT_EQ(carried->resistance().col(), fresh->resistance().col());
      const Eigen::Index n6 = Eigen::Index(F.size());
      const Eigen::VectorXd f = Eigen::Map<const Eigen::VectorXd>(F.data(), n6) +
                                Eigen::Map<const Eigen::VectorXd>(fresh->strain_force().data(), n6);
      EXPECT_LE((R * Eigen::Map<const Eigen::VectorXd>(x.data(), n6) - f).norm(),
                1e-10 * f.norm() * (1.0 + 1e-6));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ResistanceModel, FactorReuseWith,
                         ::testing::Values(Preconditioner::IncompleteCholesky,
                                           Preconditioner::EisenstatDilu));

namespace {
// Node pairs two ways: the closed forms (LubricationPair::centred_*, carried to the bodies where a
// node is off its body's centre; the default) and the general products of the body rows
// (set_closed_forms(false)), from the same pairs: spheres and both dicolloids, with the default
// options, LAMMPS's forms and the smooth visibility rule (weights below 1 for node pairs of
// dicolloids); calls check(closed, general, system) for each of 3 x 3 x 4 configurations and
// returns the number of pairs seen.
template <class Check>
int for_pairs_two_ways(Check check) {
  int pairs = 0;
  for (const Config& setup : kSetups)
    for (const int variant : {0, 1, 2})
      for (const unsigned seed : {3u, 11u, 17u, 29u}) {
        SCOPED_TRACE(std::string(setup.name) + ", options " + std::to_string(variant));
        System system(shape_of(setup), setup.n, setup.box, physics(1.0, 1.0, 0.3));
        random_configuration(system, 0.01, seed);
        LubricationOptions o;
        if (variant == 1) {
          o.pump = PumpForm::Lammps;
          o.twist = false;
          o.lever = Lever::Contact;
        }
        if (variant == 2) o.visibility_width = 0.1;
        const NodePairList list = brute_force_pairs(system, o.cutoff);  // unit radii: the pair range
        BodyResistance closed(o), general(o);
        general.set_closed_forms(false);
        closed.update(system, list);
        general.update(system, list);
        check(closed, general, system);
        pairs += int(closed.size());
      }
  return pairs;
}

// R_delta of the pairs lub has seen (update()), as a dense matrix (binds lub to it).
Eigen::MatrixXd dense_resistance(BodyResistance& lub, const System& system) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> upper;
  lub.body_pairs(upper);
  BlockSparseMatrix M;
  M.set_pattern(system.size(), upper);
  lub.bind(M);
  lub.add_to(M);
  return M.dense();
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}
}  // namespace

// R_delta from the closed-form Gram blocks against the general products: agreement to rounding
// (1e-13 of the largest entry), exact symmetry; spheres and dicolloids.
TEST(BodyResistance, ClosedFormGramBlocksEqualTheGeneralProducts) {
  const int pairs =
      for_pairs_two_ways([](BodyResistance& closed, BodyResistance& general, const System& system) {
        const Eigen::MatrixXd Ra = dense_resistance(closed, system), Rb = dense_resistance(general, system);
        const double scale = Rb.cwiseAbs().maxCoeff();
        ASSERT_GT(scale, 0.0);
        EXPECT_LE((Ra - Rb).cwiseAbs().maxCoeff(), 1e-13 * scale);
        EXPECT_EQ((Ra - Ra.transpose()).norm(), 0.0);
      });
  EXPECT_GT(pairs, 100);  // enough pairs to mean something
}

// Dicolloid node pairs take their body blocks in the threads' pair pass, or on one thread in the
// serial add_to (BodyResistance::update): the same function of the same numbers, so R has the same
// bits either way (a variant computing the blocks differently on one thread fails it).
TEST(BodyResistance, OffsetPairBlocksHaveTheSameBitsOnOneThreadAndTwo) {
  const int threads = omp_get_max_threads();
  int offset_pairs = 0;
  for (const Config& setup : kSetups)
    for (const double width : {0.0, 0.1})  // the sharp and the smooth visibility rule
      for (const unsigned seed : {3u, 11u}) {
        SCOPED_TRACE(std::string(setup.name) + ", width " + std::to_string(width));
        System system(shape_of(setup), setup.n, setup.box, physics(1.0, 1.0, 0.3));
        random_configuration(system, 0.01, seed);
        LubricationOptions o;
        o.visibility_width = width;
        const NodePairList list = brute_force_pairs(system, o.cutoff);
        const auto matrix = [&](int nthreads) {
          omp_set_num_threads(nthreads);
          BodyResistance lub(o);
          lub.update(system, list);
          if (system.nodes_per_body() > 1 && nthreads == 1) offset_pairs += int(lub.size());
          return dense_resistance(lub, system);
        };
        const Eigen::MatrixXd one = matrix(1), two = matrix(2);
        EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);
      }
  omp_set_num_threads(threads);
  EXPECT_GT(offset_pairs, 100);
}

// The strain forces R_FE:E, the pairwise Brownian forces and the stresslet sum from the
// closed-form pair wrenches against the general row products, summed over the same pairs (spheres
// and dicolloids):
// agreement to rounding (1e-13 of the largest entry), and the test's rows(k) equal to the rows the
// general path keeps.
TEST(BodyResistance, ClosedFormPairForcesEqualTheGeneralProducts) {
  const int pairs =
      for_pairs_two_ways([](BodyResistance& closed, BodyResistance& general, const System& system) {
        const std::size_t n6 = 6 * system.size();
        Eigen::Matrix3d E;
        E << 0.1, 0.5, -0.2, 0.5, -0.3, 0.05, -0.2, 0.05, 0.2;  // symmetric, traceless
        std::vector<double> fa(n6, 0.0), fb(n6, 0.0);
        closed.add_strain_force(E, fa.data());
        general.add_strain_force(E, fb.data());
        std::vector<double> diff(n6);
        for (std::size_t k = 0; k < n6; ++k) diff[k] = fa[k] - fb[k];
        ASSERT_GT(max_abs(fb), 0.0);
        EXPECT_LE(max_abs(diff), 1e-13 * max_abs(fb)) << "strain force";

        const RandomStream noise(99, RandomPurpose::PairNoise, 7);
        std::fill(fa.begin(), fa.end(), 0.0);
        std::fill(fb.begin(), fb.end(), 0.0);
        closed.add_brownian(noise, system.nodes_per_body(), 1.7, fa.data());
        general.add_brownian(noise, system.nodes_per_body(), 1.7, fb.data());
        for (std::size_t k = 0; k < n6; ++k) diff[k] = fa[k] - fb[k];
        ASSERT_GT(max_abs(fb), 0.0);
        EXPECT_LE(max_abs(diff), 1e-13 * max_abs(fb)) << "Brownian force";

        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        std::vector<double> dU(n6);
        for (double& x : dU) x = u(rng);
        const Eigen::Matrix3d Sa = closed.stresslet_sum(E, dU.data()),
                              Sb = general.stresslet_sum(E, dU.data());
        ASSERT_GT(Sb.cwiseAbs().maxCoeff(), 0.0);
        EXPECT_LE((Sa - Sb).cwiseAbs().maxCoeff(), 1e-13 * Sb.cwiseAbs().maxCoeff()) << "stresslet";

        for (std::size_t k = 0; k < closed.size(); ++k)
          ASSERT_LE((closed.rows(k) - general.rows(k)).cwiseAbs().maxCoeff(),
                    1e-14 * general.rows(k).cwiseAbs().maxCoeff())
              << "rows of pair " << k;
      });
  EXPECT_GT(pairs, 100);
}

namespace fldsim::hydro::test {

// The run log hears of a preconditioner that broke down (RunNotes, API 5.3): the first breakdown
// in full, then a line with the counts at the 2nd, 4th, 8th, ... breakdown, never one per
// factorisation (real runs switch back and forth hundreds of times: ResistanceModel::factorise).
// No pair geometry found in a search (rings of 4-8 spheres at gaps 1e-5-0.1 a, perturbed cubic
// lattices of up to 1000 spheres, 9000 random dense configurations) breaks IC(0) in a small scene,
// so the breakdown comes in the way a resumed run could meet it: a checkpoint whose saved matrix
// is the 4-cycle of BlockPCG.FallsBackToDiluWhereIncompleteCholeskyBreaksDown, in every numbering
// of its four bodies; between breakdowns the chain's own R (three weakly coupled pairs), which
// IC(0) factorises.
TEST(ResistanceModelNotes, SayWhenThePreconditionerFallsBackThenCountTheBreakdowns) {
  System s = four_sphere_chain();
  std::array<std::uint32_t, 4> label = {0, 1, 2, 3};
  int fallbacks = 0;
  do {
    const std::vector<double> state = four_cycle_checkpoint(label);
    ModelSettings st = lubrication_settings();
    st.ic_shifts.clear();  // no diagonal shifts: IC(0) falls back at once
    ResistanceModel m(st);
    HydroRequest req;
    m.configure(s, req);
    m.restore_state(state);
    const std::vector<std::string> notes = m.take_notes();
    EXPECT_TRUE(m.take_notes().empty()) << "notes are handed out once";
    if (m.active_preconditioner() == Preconditioner::IncompleteCholesky) {
      EXPECT_TRUE(notes.empty()) << notes.front();
      continue;
    }
    ++fallbacks;
    const std::string fallback =
        m.active_preconditioner() == Preconditioner::EisenstatDilu ? "eisenstat_dilu" : "block_jacobi";
    const int jacobi = fallback == "block_jacobi" ? 1 : 0;
    EXPECT_EQ(notes,
              std::vector<std::string>{
                  "incomplete_cholesky preconditioner broke down (a pivot block not positive definite); "
                  "CG uses " +
                  fallback + " while it does (same tolerance, more iterations per solve)"});
    auto recover = [&] {
      m.assemble(s, brute_force_pairs(s, m.pair_range(s)));
      ASSERT_EQ(m.active_preconditioner(), Preconditioner::IncompleteCholesky);
    };
    // Breakdowns 2 to 9 (each after a factorisation that works; the 3rd also falls back twice in
    // a row, which is one breakdown): lines at the 2nd, 4th and 8th only.
    std::vector<std::string> seen;
    for (int breakdown = 2; breakdown <= 9; ++breakdown) {
      recover();
      m.restore_state(state);
      if (breakdown == 3) m.restore_state(state);
      for (std::string& line : m.take_notes()) seen.push_back(std::move(line));
    }
    // Factorisations: 1 + 8 x 2 + 1 (the 3rd breakdown's second) = 18, of which 10 fell back.
    auto counts = [&](int breakdowns, int fell, int of) {
      return "incomplete_cholesky preconditioner has broken down " + std::to_string(breakdowns) +
             " times: " + std::to_string(of) + " factorisations, " + std::to_string(fell) + " fell back (" +
             std::to_string(jacobi * fell) + " to block_jacobi)";
    };
    EXPECT_EQ(seen, (std::vector<std::string>{counts(2, 2, 3), counts(4, 5, 8), counts(8, 9, 16)}));
  } while (std::next_permutation(label.begin(), label.end()));
  EXPECT_GT(fallbacks, 0);
}

// With the default ic_shifts the same checkpoints stay on IC(0): where it breaks down the model
// factorises R + alpha diag(R) with the first alpha that works (BlockPCG), says so once in full, and
// counts the shifted factorisations with the breakdowns. The alpha in the line is the solver's own
// (BlockPCG::shift), and CG converges with the shifted factor to the model's tolerance.
TEST(ResistanceModelNotes, SayWhenIncompleteCholeskyNeededADiagonalShift) {
  System s = four_sphere_chain();
  std::array<std::uint32_t, 4> label = {0, 1, 2, 3};
  int shifted = 0;
  do {
    ModelSettings st = lubrication_settings();
    ResistanceModel m(st);
    HydroRequest req;
    m.configure(s, req);
    m.restore_state(four_cycle_checkpoint(label));
    const std::vector<std::string> notes = m.take_notes();
    ASSERT_EQ(m.active_preconditioner(), Preconditioner::IncompleteCholesky);
    // The checkpoint's matrix, read back from its numbers (four_cycle_checkpoint's layout), into a
    // solver of its own.
    const std::vector<double> state = four_cycle_checkpoint(label);
    const std::size_t pairs = std::size_t(state[2]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> upper;
    for (std::size_t k = 0; k < pairs; ++k)
      upper.emplace_back(std::uint32_t(state[3 + 2 * k]), std::uint32_t(state[4 + 2 * k]));
    BlockSparseMatrix R;
    R.set_pattern(4, upper);
    const double* block = state.data() + 3 + 2 * pairs;
    for (std::size_t i = 0; i < 4; ++i, block += 36) R.diagonal(i) = Eigen::Map<const Mat6>(block);
    for (const auto& [i, j] : upper) {
      R.upper(R.find(i, j)) = Eigen::Map<const Mat6>(block);
      block += 36;
    }
    BlockPCG probe(Preconditioner::IncompleteCholesky);
    probe.prepare(R);
    if (probe.shift() == 0.0) {
      EXPECT_TRUE(notes.empty()) << notes.front();
      continue;
    }
    ++shifted;
    std::ostringstream alpha;
    alpha << probe.shift();
    EXPECT_EQ(notes,
              std::vector<std::string>{"incomplete_cholesky preconditioner broke down (a pivot block not "
                                       "positive definite); factorised R + " +
                                       alpha.str() + " diag(R) instead (a diagonal shift; same tolerance)"});
    // A second breakdown after a factorisation that works: the counts line, shifted ones included.
    m.assemble(s, brute_force_pairs(s, m.pair_range(s)));
    m.restore_state(four_cycle_checkpoint(label));
    EXPECT_EQ(m.take_notes(),
              std::vector<std::string>{"incomplete_cholesky preconditioner has broken down 2 times: "
                                       "3 factorisations, 2 with a diagonal shift, 0 fell back (0 to "
                                       "block_jacobi)"});
  } while (std::next_permutation(label.begin(), label.end()));
  EXPECT_GT(shifted, 0);
}

}  // namespace fldsim::hydro::test
