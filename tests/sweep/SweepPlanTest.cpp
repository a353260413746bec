// The sweep file's expansion (sweep/SweepPlan.hpp): products, zipped axes, repeats and
// per-point overrides give exactly the points the file describes, with labels that say their
// values, and every mistake in the sweep file is one line naming its line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "fldsim/error.hpp"
#include "sweep/StepProbe.hpp"
#include "sweep/SweepPlan.hpp"
#include "sweep/SweepPoints.hpp"

namespace fldsim {
namespace {

namespace fs = std::filesystem;

std::string write_sweep(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("fldsim-sweep-plan-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "base.yaml")
      << "# the base experiment the sweeps name (only its existence is checked here)\n";
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

BaseSeeds seeds(const std::string&) {
  return BaseSeeds{42, 7};
}

std::string value_of(const SweepPoint& p, const std::string& key) {
  std::string v;  // the last setting wins, as with --set
  for (const auto& s : p.settings)
    if (s.key == key) v = s.yaml;
  return v;
}

std::string errors_of(const std::string& text) {
  try {
    read_sweep_plan(write_sweep("bad.yaml", text), seeds);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepPlan, ProductZipRepeatsAndOverridesGiveEveryPointOnce) {
  const std::string file = write_sweep("study.yaml", R"(base: base.yaml
output_dir: out
threads: 2
axes:
  - flow.peclet: [0.1, 1, 1000]
  - system.shape.c: [0.2, 1.0]
  - zip:
      system.volume_fraction: [0.3, 0.5]
      run.dt: [1.0e-3, 1.0e-4]
repeats: 2
overrides:
  - when: {flow.peclet: [0.1, 1], system.volume_fraction: 0.5}
    set: {run.dt: 2.0e-5, run.duration: 5}
)");
  const SweepPlan plan = read_sweep_plan(file, seeds);
  // 3 Pe x 2 shapes x 2 zipped (phi, dt) x 2 repeats.
  ASSERT_EQ(plan.points.size(), 24u);
  EXPECT_EQ(plan.axis_keys,
            (std::vector<std::string>{"flow.peclet", "system.shape.c", "system.volume_fraction", "run.dt"}));
  EXPECT_EQ(plan.base, (fs::path(file).parent_path() / "base.yaml").string());
  EXPECT_EQ(plan.output_of(plan.points[0]),
            (fs::path(file).parent_path() / "out" / (plan.points[0].label + ".h5")).string());
  std::set<std::string> labels;
  for (const auto& p : plan.points) labels.insert(p.label);
  EXPECT_EQ(labels.size(), plan.points.size()) << "labels must name points uniquely";
  // The first axis varies slowest, the repeat fastest.
  EXPECT_EQ(plan.points[0].label, "peclet-0.1_c-0.2_volume_fraction-0.3_dt-1.0e-3_rep0");
  EXPECT_EQ(plan.points[1].label, "peclet-0.1_c-0.2_volume_fraction-0.3_dt-1.0e-3_rep1");
  EXPECT_EQ(plan.points[2].label, "peclet-0.1_c-0.2_volume_fraction-0.5_dt-1.0e-4_rep0");
  int overridden = 0;
  for (const auto& p : plan.points) {
    EXPECT_EQ(value_of(p, "run.threads"), "2");
    EXPECT_EQ(value_of(p, "run.seed"), std::to_string(42 + p.repeat));
    EXPECT_EQ(value_of(p, "system.init.seed"), std::to_string(7 + p.repeat));
    const bool slow = value_of(p, "flow.peclet") != "1000" && value_of(p, "system.volume_fraction") == "0.5";
    EXPECT_EQ(value_of(p, "run.dt"),
              slow ? "2.0e-5" : (value_of(p, "system.volume_fraction") == "0.3" ? "1.0e-3" : "1.0e-4"))
        << p.label;
    overridden += slow;
  }
  EXPECT_EQ(overridden, 2 * 2 * 2);  // Pe 0.1 and 1, both shapes, phi 0.5, both repeats
}

TEST(SweepPlan, NoAxesIsTheBaseExperimentOnce) {
  const SweepPlan plan = read_sweep_plan(write_sweep("one.yaml", "base: base.yaml\n"), seeds);
  ASSERT_EQ(plan.points.size(), 1u);
  EXPECT_EQ(plan.points[0].label, "base");
  EXPECT_EQ(plan.output_dir, (fs::path(plan.file).parent_path() / "one").string());
}

TEST(SweepPlan, EveryMistakeIsOneLineNamingLineAndKey) {
  const std::string e = errors_of(R"(base: base.yaml
axis:
  - flow.peclet: [1]
axes:
  - flow.peclet: 10
  - zip:
      system.volume_fraction: [0.3, 0.5]
      run.dt: [1.0e-3]
  - {a: [1], b: [2]}
repeats: 0
overrides:
  - when: {flow.pecelt: 1}
    set: {run.dt: 1.0e-4}
)");
  EXPECT_NE(e.find(":2:1: unknown key 'axis' (did you mean 'axes'?)"), std::string::npos) << e;
  EXPECT_NE(e.find(":5:18: axes[0].flow.peclet: expected a non-empty list of values, got 10"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find(":8:15: axes[1].zip.run.dt: zipped lists must be equally long: 1 values here, 2 for "
                   "system.volume_fraction"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find(":9:5: axes[2]: expected one `KEY: [values]`"), std::string::npos) << e;
  EXPECT_NE(e.find(":10:10: repeats: expected an integer from 1 to 10000"), std::string::npos) << e;
  EXPECT_NE(e.find(":12:12: overrides[0].when: 'flow.pecelt' is not an axis key"), std::string::npos) << e;
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 5) << "one line per mistake:\n" << e;
}

TEST(SweepPlan, MissingBaseIsNamed) {
  const std::string e = errors_of("axes:\n  - flow.peclet: [1]\n");
  EXPECT_NE(e.find("base: expected the base experiment file"), std::string::npos) << e;
  // A base that is not there: one line at the key, not one per point.
  const std::string absent = errors_of("base: nothere.yaml\naxes:\n  - flow.peclet: [1, 2]\n");
  EXPECT_NE(absent.find(":1:7: base: '"), std::string::npos) << absent;
  EXPECT_NE(absent.find("nothere.yaml' is not a readable file"), std::string::npos) << absent;
  EXPECT_EQ(std::count(absent.begin(), absent.end(), '\n'), 0) << absent;
}

// A path in the sweep file is relative to the sweep file, whatever the current directory (the
// rule of experiment files); before, it went to `fldsim run --set` as written and was resolved
// against the current directory.
TEST(SweepPlan, PathValuesAreRelativeToTheSweepFile) {
  const std::string file = write_sweep("paths.yaml", R"(base: base.yaml
axes:
  - system.init.file: [starts/a.h5, /abs/b.h5]
overrides:
  - when: {system.init.file: starts/a.h5}
    set: {plugins.paths: [mine, /opt/theirs]}
)");
  const SweepPlan plan = read_sweep_plan(file, seeds);
  ASSERT_EQ(plan.points.size(), 2u);
  const fs::path dir = fs::path(file).parent_path();
  EXPECT_EQ(value_of(plan.points[0], "system.init.file"), (dir / "starts/a.h5").string());
  EXPECT_EQ(value_of(plan.points[0], "plugins.paths"), "[" + (dir / "mine").string() + ", /opt/theirs]");
  EXPECT_EQ(value_of(plan.points[1], "system.init.file"), "/abs/b.h5");
  EXPECT_EQ(plan.points[0].label, "file-starts_a.h5") << "labels keep the values as written";
}

// The probe reads the run's own loop time: the last line starting "done: " (a "done:" inside
// another line, e.g. a progress message, is not it), its number before "ms/step".
TEST(StepProbe, ReadsTheLoopTimeOfTheLastDoneLine) {
  EXPECT_DOUBLE_EQ(
      logged_ms_per_frame("step 5/5\ndone: 5 steps in 0.1 s (20.500000 ms/step, 3 CG iterations/step "
                          "(all solves), 0 neighbour rebuilds); total 0.2 s\nsteps: ...\n"),
      20.5);
  EXPECT_DOUBLE_EQ(logged_ms_per_frame("done: 1 steps in 1 s (2.000000 ms/step, x)\nwarning: not done: yet\n"
                                       "done: 2 steps in 1 s (3.000000 ms/step, x)\n"),
                   3.0);
  EXPECT_LT(logged_ms_per_frame("error: run.dt: expected a number\n"), 0.0);
  EXPECT_LT(logged_ms_per_frame("done: 0 steps in 0 s (- ms/step, 0 CG iterations/step)\n"), 0.0);
  EXPECT_LT(logged_ms_per_frame("note: done: 3 steps (1.0 ms/step,\n"), 0.0);
}

// A resumed point's estimate counts only the frames after its checkpoint (before, a point at
// 66 % was listed with the whole run's 14 h); dt: auto keeps the whole. The checkpoint's step comes
// from check_run, which reads it anyway (an unreadable one is an error there, before any estimate);
// Sweep.AnInterruptedSweepResumesToTheNumbersOfAnUninterruptedRun checks the listing end to end.
TEST(SweepPoints, AResumedPointIsEstimatedForTheFramesLeft) {
  EXPECT_DOUBLE_EQ(share_left(1000, 300, false), 0.7);
  EXPECT_DOUBLE_EQ(share_left(300, 300, false), 0.0);
  EXPECT_DOUBLE_EQ(share_left(1000, 300, true), 1.0) << "adaptive steps are not frames";
}

}  // namespace
}  // namespace fldsim
