// Free Brownian bodies (free-draining hydrodynamics, no interactions): translational MSD and
// director autocorrelation against the exact results for a rigid body with constant
// resistance: <|dr|^2> = 6 D t and <n(t).n(0)> = exp(-2 D_r t) (e.g. Kim & Karrila 1991; see
// physics-reference-values.md section 5).
#include <gtest/gtest.h>

#include <cmath>

#include "Scene.hpp"

namespace fldsim::testing {
namespace {

// N free bodies 4 a apart on a grid (free-draining hydrodynamics ignores pairs anyway), kT = 1.
std::unique_ptr<Scene> free_bodies(const std::string& shape_name, const std::string& shape_yaml,
                                   std::size_t n) {
  Physics ph;
  ph.kT = 1.0;
  const int side = int(std::ceil(std::cbrt(double(n))));
  auto scene = std::make_unique<Scene>(make<Shape>("shape", shape_name, shape_yaml), n, 4.0 * side, ph);
  auto& s = *scene->system;
  for (std::size_t i = 0; i < n; ++i)
    s.positions()[i] = 4.0 * Vec3(double(i % side), double((i / side) % side), double(i / (side * side))) +
                       Vec3(2.0, 2.0, 2.0);
  scene->finish(make<HydroModel>("hydro", "free_draining"), {}, HydroRequest{true, false, false});
  return scene;
}

// Leimkuhler-Matthews, or Euler-Maruyama with `drift`.
std::unique_ptr<TimeIntegrator> free_integrator(bool leimkuhler_matthews, std::uint64_t seed,
                                                DriftScheme drift, std::size_t n) {
  if (leimkuhler_matthews) return std::make_unique<LeimkuhlerMatthews>(seed, n);
  return std::make_unique<EulerMaruyama>(seed, true, drift, n);
}

// Runs `steps` steps of N free bodies (Euler-Maruyama with the midpoint drift unless
// leimkuhler_matthews); returns squared displacements and director overlaps n(t).n(0).
void run_free(const std::string& shape_name, const std::string& shape_yaml, std::size_t n, double dt,
              int steps, std::vector<double>& sq, std::vector<double>& overlap,
              bool leimkuhler_matthews = false) {
  auto scene = free_bodies(shape_name, shape_yaml, n);
  auto& s = *scene->system;
  std::vector<Vec3> n0(n);
  for (std::size_t i = 0; i < n; ++i) n0[i] = s.director(i);
  auto integrator = free_integrator(leimkuhler_matthews, 7, DriftScheme::Midpoint, n);
  for (int k = 0; k < steps; ++k) integrator->step(s, *scene->evaluator, dt, false);
  sq.clear();
  overlap.clear();
  for (std::size_t i = 0; i < n; ++i) {
    sq.push_back(s.displacement()[i].squaredNorm());
    overlap.push_back(s.director(i).dot(n0[i]));
  }
}

TEST(FreeDiffusion, SphereMeanSquaredDisplacementIsSixDt) {
  // Internal units: D0 = kT/(6 pi mu a) = 1. Each body's |dr|^2 has variance 24 (D t)^2, so the
  // mean over N bodies has SE sqrt(24/N) D t; we use the sample SE and allow 3 SE.
  std::vector<double> sq, ov;
  const double dt = 0.01;
  const int steps = 50;
  run_free("sphere", "{}", 2000, dt, steps, sq, ov);
  const auto m = mean_with_error(sq);
  const double expected = 6.0 * 1.0 * dt * steps;
  EXPECT_NEAR(m.mean, expected, 3.0 * m.se) << "MSD " << m.mean << " +- " << m.se;
}

TEST(FreeDiffusion, DicolloidDirectorDecorrelatesAtTwiceRotationalDiffusivity) {
  // Free-draining dicolloid of two unit nodes at +-c/2: perpendicular rotational resistance
  // 2 (8 pi mu a^3) + 2 (6 pi mu a)(c/2)^2 = 8/3 + c^2/2 in internal units (6 pi mu a = 1).
  const double c = 1.0;
  const double Dr = 1.0 / (8.0 / 3.0 + c * c / 2.0);
  std::vector<double> sq, ov;
  const double dt = 0.005;
  const int steps = 60;  // t = 0.3, exp(-2 Dr t) ~ 0.82
  run_free("dicolloid", "{a: 1, b: 1, c: 1}", 2000, dt, steps, sq, ov);
  const auto m = mean_with_error(ov);
  const double expected = std::exp(-2.0 * Dr * dt * steps);
  EXPECT_NEAR(m.mean, expected, 3.0 * m.se) << "<n.n0> " << m.mean << " +- " << m.se;
  // Translation of the symmetric dicolloid: resistance 2 x 6 pi mu a, so D = 1/2.
  const auto t = mean_with_error(sq);
  EXPECT_NEAR(t.mean, 6.0 * 0.5 * dt * steps, 3.0 * t.se);
}

// A free-draining dicolloid's mobility turns with the body; without translation-rotation coupling
// (two equal nodes about the centre) the averaged noise adds no drift (TimeIntegrator.hpp), so
// Leimkuhler-Matthews keeps the exact director decorrelation exp(-2 D_r t) and D = 1/2, as above.
// The MSD after n steps is 6 D dt (n - 1/2), the director's exponent the same up to O(dt) per step.
// Broken variant, run once: the two draws scaled as independent (1/sqrt 2 instead of 1/2) doubles the
// diffusivity and fails this test (<n.n0> 0.680 +- 0.006) and the sphere test below.
TEST(FreeDiffusion, LeimkuhlerMatthewsDicolloidKeepsRotationalAndTranslationalDiffusion) {
  const double c = 1.0;
  const double Dr = 1.0 / (8.0 / 3.0 + c * c / 2.0);
  std::vector<double> sq, ov;
  const double dt = 0.005;
  const int steps = 60;
  run_free("dicolloid", "{a: 1, b: 1, c: 1}", 2000, dt, steps, sq, ov, true);
  const auto m = mean_with_error(ov);
  EXPECT_NEAR(m.mean, std::exp(-2.0 * Dr * dt * (steps - 0.5)), 3.0 * m.se)
      << "<n.n0> " << m.mean << " +- " << m.se;
  const auto t = mean_with_error(sq);
  EXPECT_NEAR(t.mean, 6.0 * 0.5 * dt * (steps - 0.5), 3.0 * t.se);
}

// Leimkuhler-Matthews (TimeIntegrator.hpp): a free sphere's increment is sqrt(2 D dt) (xi_n +
// xi_{n+1}) / 2 per axis, so E|d_n|^2 = 3 D dt (half of Euler-Maruyama's 6 D dt), consecutive
// increments are correlated, E[d_n . d_{n+1}] = 1.5 D dt (Euler-Maruyama: 0), and the noises
// telescope: E|x_n - x_0|^2 = 6 D dt (n - 1/2), the right diffusivity. Per body and axis
// d_1 d_2 = s^2 (a + b)(b + c) with s^2 = D dt / 2 has mean s^2 and variance 5 s^4, so with
// 4000 spheres the mean of d_1 . d_2 (3 s^2) has SE sqrt(15 / 4000) s^2 = 2 % of it. Euler-Maruyama,
// run through the same function, is the broken variant: its correlation is 0, 49 SE away.
struct Increments {
  MeanWithError first_square, product, msd;
};

Increments free_sphere_increments(bool leimkuhler_matthews, double dt, int steps) {
  const std::size_t n = 4000;
  auto scene = free_bodies("sphere", "{}", n);
  auto& s = *scene->system;
  auto integrator = free_integrator(leimkuhler_matthews, 11, DriftScheme::None, n);
  std::vector<Vec3> d1(n);
  std::vector<double> first_square, product, msd;
  for (int k = 0; k < steps; ++k) {
    integrator->step(s, *scene->evaluator, dt, false);
    if (k == 0)
      for (std::size_t i = 0; i < n; ++i) d1[i] = s.displacement()[i];
    if (k == 1)
      for (std::size_t i = 0; i < n; ++i) {
        first_square.push_back(d1[i].squaredNorm());
        product.push_back(d1[i].dot(s.displacement()[i] - d1[i]));
      }
  }
  for (std::size_t i = 0; i < n; ++i) msd.push_back(s.displacement()[i].squaredNorm());
  return {mean_with_error(first_square), mean_with_error(product), mean_with_error(msd)};
}

TEST(FreeDiffusion, LeimkuhlerMatthewsIncrementsAreCorrelatedAndKeepTheDiffusivity) {
  const double dt = 0.01;
  const int steps = 20;
  const Increments lm = free_sphere_increments(true, dt, steps);
  EXPECT_NEAR(lm.first_square.mean, 3.0 * dt, 3.0 * lm.first_square.se) << "E|d_1|^2";
  EXPECT_NEAR(lm.product.mean, 1.5 * dt, 3.0 * lm.product.se) << "E[d_1 . d_2]";
  EXPECT_NEAR(lm.msd.mean, 6.0 * dt * (steps - 0.5), 3.0 * lm.msd.se) << "MSD after " << steps << " steps";
  const Increments em = free_sphere_increments(false, dt, steps);
  EXPECT_NEAR(em.product.mean, 0.0, 3.0 * em.product.se) << "Euler-Maruyama's increments are independent";
  EXPECT_GT(std::fabs(em.product.mean - 1.5 * dt), 10.0 * em.product.se)
      << "the correlation test cannot tell Euler-Maruyama from Leimkuhler-Matthews";
}

}  // namespace
}  // namespace fldsim::testing
