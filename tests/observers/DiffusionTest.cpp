// Diffusion: synthetic Brownian walks and rotational random walks with known diffusivities;
// shear advection must not enter the shear-corrected MSD.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "DiffusionObserver.hpp"
#include "DiffusionStatistics.hpp"
#include "FakeSink.hpp"

using namespace fldsim;
using namespace fldsim::observers;

namespace {

struct Walkers {
  std::vector<Vec3> nonaffine, total, directors;
};

// n bodies, Gaussian steps of variance 2 D_a dt per axis; the total displacement adds the
// affine advection gammadot * y * dt along x (y = current unwrapped gradient coordinate, all
// bodies starting at y = 0); directors turn by Gaussian rotation vectors of variance 2 D_r dt
// per component (isotropic rotational diffusion).
class WalkGenerator {
 public:
  WalkGenerator(std::size_t n, Vec3 d, double d_rot, double shear_rate, double dt, std::uint64_t seed)
      : d_(d), d_rot_(d_rot), gd_(shear_rate), dt_(dt), rng_(seed), y_(n, 0.0) {
    w_.nonaffine.assign(n, Vec3::Zero());
    w_.total.assign(n, Vec3::Zero());
    std::normal_distribution<double> g(0.0, 1.0);
    w_.directors.resize(n);
    for (auto& v : w_.directors) v = Vec3(g(rng_), g(rng_), g(rng_)).normalized();
  }
  const Walkers& step() {
    std::normal_distribution<double> g(0.0, 1.0);
    for (std::size_t i = 0; i < y_.size(); ++i) {
      Vec3 dx;
      for (int a = 0; a < 3; ++a) dx[a] = std::sqrt(2.0 * d_[a] * dt_) * g(rng_);
      w_.nonaffine[i] += dx;
      w_.total[i] += dx + Vec3(gd_ * y_[i] * dt_, 0.0, 0.0);
      y_[i] += dx.y();
      const Vec3 omega = std::sqrt(2.0 * d_rot_ * dt_) * Vec3(g(rng_), g(rng_), g(rng_));
      w_.directors[i] = Eigen::AngleAxisd(omega.norm(), omega.normalized()) * w_.directors[i];
    }
    return w_;
  }

 private:
  Vec3 d_;
  double d_rot_, gd_, dt_;
  std::mt19937_64 rng_;
  std::vector<double> y_;
  Walkers w_;
};

}  // namespace

TEST(DiffusionStatistics, LogSpacedLagsAreIncreasingMultiplesOfTheUnit) {
  const auto lags = DiffusionStatistics::log_spaced_lags(100, 10, 5);
  EXPECT_EQ(lags.front(), 5);
  EXPECT_EQ(lags.back(), 500);
  for (std::size_t j = 1; j < lags.size(); ++j) {
    EXPECT_GT(lags[j], lags[j - 1]);
    EXPECT_EQ(lags[j] % 5, 0);
  }
}

TEST(DiffusionStatistics, BrownianWalksReproduceDiffusivities) {
  const Vec3 d(1.0, 0.5, 2.0);
  const double d_rot = 0.5, dt = 0.01;
  WalkGenerator gen(100, d, d_rot, 0.0, dt, 4242);
  DiffusionStatistics st(DiffusionStatistics::log_spaced_lags(100, 10, 1), 5, dt, 100);
  for (std::int64_t s = 1; s <= 4000; ++s) {
    const Walkers& w = gen.step();
    st.add_sample(s, w.nonaffine, w.total, w.directors);
  }
  ASSERT_GT(st.completed_origins(), 700u);
  // MSD_a = 2 D_a t at every lag (Einstein); D from the first lag and from the long-lag slope
  // must agree with D_a within 3 standard errors (blocking over the correlated origins).
  for (int a = 0; a < 3; ++a) {
    const BlockAverage ds = st.d_short(a), dl = st.d_long(a);
    EXPECT_NEAR(ds.mean(), d[a], 3.0 * ds.stderr_mean()) << "axis " << a;
    EXPECT_NEAR(dl.mean(), d[a], 3.0 * dl.stderr_mean()) << "axis " << a;
    const auto& m = st.msd_nonaffine(st.lags() - 1, a);
    EXPECT_NEAR(m.mean(), 2.0 * d[a] * st.lag_time(st.lags() - 1), 3.0 * m.stderr_mean()) << "axis " << a;
  }
  // <n(t).n(0)> decays per step by the exact factor of a Gaussian rotation vector with variance
  // s2 = 2 D_r dt per component: E[n'.n] = 1/3 + 2/3 (1 - s2) exp(-s2/2) (mean cosine of a 3-D
  // Gaussian angle); the decay rate -ln(factor)/dt = 2 D_r (1 + O(D_r dt)) defines D_r,expected.
  const double s2 = 2.0 * d_rot * dt;
  const double expected = -std::log(1.0 / 3.0 + 2.0 / 3.0 * (1.0 - s2) * std::exp(-0.5 * s2)) / (2.0 * dt);
  const BlockAverage dr = st.d_rot(1);
  EXPECT_NEAR(dr.mean(), expected, 3.0 * dr.stderr_mean());
  EXPECT_LT(std::abs(expected - d_rot), 0.01 * d_rot);  // the discretisation shift is small
}

TEST(DiffusionStatistics, ShearAdvectionIsRemovedFromTheNonaffineMsd) {
  const Vec3 d(1.0, 1.0, 1.0);
  const double dt = 0.01, gd = 5.0;
  WalkGenerator gen(100, d, 0.1, gd, dt, 777);
  DiffusionStatistics st(DiffusionStatistics::log_spaced_lags(100, 10, 1), 5, dt, 100);
  for (std::int64_t s = 1; s <= 3000; ++s) {
    const Walkers& w = gen.step();
    st.add_sample(s, w.nonaffine, w.total, w.directors);
  }
  const std::size_t last = st.lags() - 1;
  for (int a = 0; a < 3; ++a) {
    const BlockAverage ds = st.d_short(a), dl = st.d_long(a);
    EXPECT_NEAR(ds.mean(), d[a], 3.0 * ds.stderr_mean()) << "axis " << a;
    EXPECT_NEAR(dl.mean(), d[a], 3.0 * dl.stderr_mean()) << "axis " << a;
  }
  // The flow is along x only: y and z total displacements equal the non-affine ones.
  for (int a = 1; a < 3; ++a)
    EXPECT_DOUBLE_EQ(st.msd_total(last, a).mean(), st.msd_nonaffine(last, a).mean());
  // Along x the total MSD carries the advection: at least the Taylor term (2/3) gd^2 D t^3
  // (Elrick 1962; it adds to gd^2 <y0^2> t^2 >= 0), far above the Brownian 2 D t.
  const double t = st.lag_time(last);
  const auto& mt = st.msd_total(last, 0);
  EXPECT_GT(mt.mean() - 3.0 * mt.stderr_mean(),
            2.0 * d.x() * t + (2.0 / 3.0) * gd * gd * d.y() * t * t * t - 0.5);
}

namespace {
class SphereShape : public Shape {
 public:
  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override { return 4.0 / 3.0 * std::numbers::pi; }

 private:
  std::vector<Node> nodes_{{Vec3::Zero(), 1.0}};
};
}  // namespace

TEST(DiffusionObserver, SampledRunGivesTheBrownianDiffusivity) {
  // The observer sees System::nonaffine_displacement() every 2 steps of dt = 0.01 with
  // max_lag = 1 (user time = internal time here): lags are multiples of 2 steps up to 100 steps.
  const std::size_t n = 50;
  const double dt = 0.01, D = 1.0;
  System sys(std::make_shared<SphereShape>(), n, 20.0, Physics{});
  RunInfo run;
  run.dt = dt;
  run.total_steps = 4000;
  DiffusionObserver obs({1.0, 8, 10});
  obs.set_schedule(2, 0.0);
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  NodePairList pairs;
  std::mt19937_64 rng(31);
  std::normal_distribution<double> g(0.0, std::sqrt(2.0 * D * dt));
  for (std::int64_t step = 0; step <= run.total_steps; ++step) {
    sys.set_step(step);
    sys.set_time(step * dt);
    if (obs.due(step, sys.time())) {
      StepView view{sys, pairs, run, nullptr, nullptr, nullptr, {}, 0.0};
      obs.sample(view, sink);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 dx(g(rng), g(rng), g(rng));
      sys.nonaffine_displacement()[i] += dx;
      sys.displacement()[i] += dx;
    }
  }
  obs.finish(run, sink);
  const auto& lag = sink.arrays.at("results/diffusion/lag_time").data;
  EXPECT_NEAR(lag.front(), 2 * dt, 1e-12);
  EXPECT_NEAR(lag.back(), 1.0, 1e-12);
  for (const char* axis : {"x", "y", "z"}) {
    const auto& ds = sink.scalar(std::string("results/diffusion/D_short_") + axis);
    const auto& dl = sink.scalar(std::string("results/diffusion/D_long_") + axis);
    EXPECT_NEAR(ds.value, D, 3.0 * ds.stderr_value) << axis;
    EXPECT_NEAR(dl.value, D, 3.0 * dl.stderr_value) << axis;
  }
  // Spheres have no director: no rotational results.
  EXPECT_EQ(sink.scalars.count("results/diffusion/D_r"), 0u);
}

TEST(DiffusionObserver, LagTimesAreInTheRunsTimeUnit) {
  // A strain-unit run at gammadot = 4: one user time unit is 0.25 internal (a^2/D0). With
  // max_lag = 2 strain units and dt = 0.01 a^2/D0 the largest lag is 50 steps = 0.5 a^2/D0
  // = 2 strain units; lag times are written as given (strain) and labelled with the run's unit.
  const std::size_t n = 4;
  const double dt = 0.01;
  System sys(std::make_shared<SphereShape>(), n, 20.0, Physics{});
  RunInfo run;
  run.dt = dt;
  run.total_steps = 200;
  run.time_unit = "1/gammadot";
  run.time_scale = 0.25;
  DiffusionObserver obs({2.0, 5, 4});
  obs.set_schedule(1, 0.0);
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  NodePairList pairs;
  for (std::int64_t step = 0; step <= run.total_steps; ++step) {
    sys.set_step(step);
    sys.set_time(step * dt);
    StepView view{sys, pairs, run, nullptr, nullptr, nullptr, {}, 0.0};
    if (obs.due(step, sys.time())) obs.sample(view, sink);
  }
  obs.finish(run, sink);
  const auto& lag = sink.arrays.at("results/diffusion/lag_time");
  EXPECT_EQ(lag.unit, "1/gammadot");
  EXPECT_NEAR(lag.data.back(), 2.0, 1e-12);
  EXPECT_NEAR(lag.data.front(), 1 * dt / 0.25, 1e-12);
}
