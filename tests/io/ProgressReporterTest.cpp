// ProgressReporter with a scripted wall clock: the speed is measured over a moving window
// (so it follows a change of speed, unlike the whole-run mean), the ETA follows from it, each
// kind of warning is printed once, and the final line gives the mean speed.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "ProgressReporter.hpp"

namespace fldsim {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// Steps 1..3000 at 100 steps/s (wall 0..30 s), then 200 steps/s up to step 20000 (wall 115 s).
double wall_of(std::int64_t step) {
  return step <= 3000 ? static_cast<double>(step) / 100.0 : 30.0 + static_cast<double>(step - 3000) / 200.0;
}

TEST(ProgressReporter, WindowedSpeedEtaWarningsAndFinalLine) {
  std::ostringstream out;
  ProgressOptions options;
  options.interval = 10.0;
  options.live = false;
  ProgressReporter r(options, out);
  const std::int64_t total = 20000;
  r.start(0, total, 0.0, "1/gammadot", 2.0);
  for (std::int64_t step = 1; step <= total; ++step) {
    const double gap = (step == 500 || step == 600) ? 1e-6 : 0.1;  // two near-contacts: one warning
    const int cg = (step == 700 || step == 800) ? 500 : 20;        // two slow solves: one warning
    r.update(step, 0.001 * static_cast<double>(step), gap, cg, wall_of(step));
    if (step == 2000) {
      // Display at wall 20 s; window from wall 0: 2000 steps / 20 s.
      EXPECT_NEAR(r.window_rate(), 100.0, 1e-9);
      EXPECT_NEAR(r.eta(), (total - 2000) / 100.0, 1e-6);
    }
    if (step == 17000) {
      // Display at wall 100 s; the window (kWindow = 5 displays of 10 s) starts at wall 50 s,
      // inside the 200 steps/s phase. The whole-run mean would be 17000/100 = 170 steps/s.
      EXPECT_NEAR(r.window_rate(), 200.0, 1e-9);
      EXPECT_NEAR(r.eta(), (total - 17000) / 200.0, 1e-6);
    }
  }
  r.finish(wall_of(total));
  const std::string text = out.str();
  EXPECT_EQ(count(text, "warning: minimum gap"), 1) << text;
  EXPECT_EQ(count(text, "warning: CG needed 500 iterations"), 1) << text;
  EXPECT_EQ(r.warnings(), 2);
  // A line every 10 s of wall time over 115 s (11 lines) plus the forced one at the last step.
  EXPECT_EQ(count(text, "\nstep ") + (text.rfind("step ", 0) == 0 ? 1 : 0), 12) << text;
  EXPECT_EQ(count(text, "\r"), 0);
  // Simulated time in the user's unit: t = 0.001 * 2000 / time_scale 2 = 1.
  EXPECT_NE(text.find("step 2000/20000 (10.0%)  t = 1 1/gammadot  100 steps/s  ETA 3m00s"), std::string::npos)
      << text;
  // Final line: 20000 steps in 115 s -> mean 173.9 steps/s.
  EXPECT_NE(text.find("progress: 20000 steps in 1m55s wall time (115.000 s), mean 173.9 steps/s"),
            std::string::npos)
      << text;
}

TEST(ProgressReporter, LiveModeRewritesOneLine) {
  std::ostringstream out;
  ProgressOptions options;
  options.live = true;
  options.live_refresh = 1.0;
  ProgressReporter r(options, out);
  r.start(0, 100, 0.0, "a^2/D0", 1.0);
  for (int step = 1; step <= 100; ++step)
    r.update(step, 0.01 * step, 0.5, 3, step / 10.0);  // exact at whole seconds
  const std::string before_finish = out.str();
  EXPECT_EQ(count(before_finish, "\n"), 0);   // one line, rewritten
  EXPECT_EQ(count(before_finish, "\r"), 10);  // every 1 s over 10 s
  r.finish(10.0);
  EXPECT_NE(out.str().find("\nprogress: 100 steps"), std::string::npos);
}

}  // namespace
}  // namespace fldsim
