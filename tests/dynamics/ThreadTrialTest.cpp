// ThreadTrial (run/ThreadTrial.hpp): the schedule of thread counts over the trial steps, the
// decision by medians, and — what makes the trial harmless — that switching the thread count
// between steps leaves the trajectory bitwise unchanged.
#include <gtest/gtest.h>
#include <omp.h>

#include "Scene.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "run/ThreadTrial.hpp"

namespace fldsim::testing {
namespace {

// Feeds the trial step times: t_one for 1-thread steps, t_many otherwise; slot `outlier` (a
// timed slot, 1-based) takes 10x longer, as an observer step might.
ThreadTrial run_trial(double t_one, double t_many, int outlier = -1) {
  ThreadTrial trial(2, true);
  int slot = 0;
  while (trial.running()) {
    double t = trial.threads_for_next_step() == 1 ? t_one : t_many;
    if (slot == outlier) t *= 10.0;
    trial.record(t);
    ++slot;
  }
  return trial;
}

TEST(ThreadTrial, ScheduleIsWarmUpThenAbbaRounds) {
  ThreadTrial trial(2, true);
  std::vector<int> seen;
  while (trial.running()) {
    seen.push_back(trial.threads_for_next_step());
    trial.record(1e-3);
  }
  const std::vector<int> expected{2, 2, 1, 1, 2, 2, 1, 1, 2, 2, 1, 1, 2};
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(int(seen.size()), ThreadTrial::kSteps);
}

TEST(ThreadTrial, KeepsTheThreadsOnlyWhenAtLeastFivePerCentFaster) {
  EXPECT_EQ(run_trial(10e-3, 7e-3).chosen(), 2);
  EXPECT_EQ(run_trial(10e-3, 9.6e-3).chosen(), 1);  // 4 % faster: not worth a second core
  EXPECT_EQ(run_trial(10e-3, 12e-3).chosen(), 1);
  // One slow (observer) step among the 1-thread steps does not move the median.
  EXPECT_EQ(run_trial(10e-3, 9.6e-3, 2).chosen(), 1);
  const ThreadTrial t = run_trial(60e-3, 75e-3);
  EXPECT_EQ(t.report(), "measured 60.0 ms/step on 1 thread, 75.0 on 2 (medians of 6 steps each): 1 thread");
}

TEST(ThreadTrial, RunsOnlyForLongAutomaticMultiThreadedRuns) {
  EXPECT_TRUE(ThreadTrial::should_run(2, true, 1000));
  EXPECT_FALSE(ThreadTrial::should_run(1, true, 1000));
  EXPECT_FALSE(ThreadTrial::should_run(2, false, 1000));  // run.threads or OMP_NUM_THREADS
  EXPECT_FALSE(ThreadTrial::should_run(2, true, ThreadTrial::kMinRunSteps - 1));
  ThreadTrial off(2, false);
  EXPECT_FALSE(off.running());
  EXPECT_EQ(off.threads_for_next_step(), 2);
}

// FLD spheres, Brownian, in shear: 13 steps with the trial's thread counts against
// 13 steps on one thread, from the same start and seed.
TEST(ThreadTrial, SwitchingThreadsBetweenStepsLeavesTheTrajectoryBitwiseUnchanged) {
  auto trajectory = [](bool switching) {
    const std::size_t n = 216;
    Physics ph;
    ph.kT = 1.0;
    ph.shear_rate = 10.0;
    ph.volume_fraction = 0.4;
    auto shape = make<Shape>("shape", "sphere");
    Scene scene(shape, n, std::cbrt(double(n) * shape->volume() / 0.4), ph);
    geometry::MonteCarloOptions mc;
    mc.seed = 3;
    geometry::initialise_monte_carlo(*scene.system, mc);
    scene.finish(make<HydroModel>("hydro", "fld"), {make<ForceLaw>("force", "repulsion")},
                 HydroRequest{true, true, false}, 0.1);
    EulerMaruyama em(9, true, DriftScheme::Midpoint, n);
    const int threads = omp_get_max_threads();
    ThreadTrial trial(2, switching);
    for (int k = 0; k < ThreadTrial::kSteps; ++k) {
      omp_set_num_threads(switching ? trial.threads_for_next_step() : 1);
      em.step(*scene.system, *scene.evaluator, 1e-3, false);
      trial.record(1e-3 * double(k % 3));
    }
    omp_set_num_threads(threads);
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& x = scene.system->positions()[i];
      const Quat& q = scene.system->orientations()[i];
      out.insert(out.end(), {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()});
    }
    return out;
  };
  const std::vector<double> one = trajectory(false), switched = trajectory(true);
  ASSERT_EQ(one.size(), switched.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], switched[k]) << "coordinate " << k;
}

}  // namespace
}  // namespace fldsim::testing
