// End-to-end through the command line: a small experiment runs and writes its result file; bad
// input gives the documented one-line error and exit code 2; an existing result is never
// overwritten; a run resumed from its checkpoint reproduces the uninterrupted run bit for bit
// (counter-based noise keyed by step, warm start and observer accumulators saved).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/Checkpoint.hpp"

namespace {

namespace fs = std::filesystem;

struct Command {
  int code;
  std::string output;
};

Command run(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("fldsim-test-" + std::to_string(::getpid()) + ".log");
  const std::string cmd =
      std::string(FLDSIM_BINARY_DIR) + "/bin/fldsim " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WEXITSTATUS(status), ss.str()};
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fldsim-e2e-" + std::to_string(::getpid())) / name;
  fs::create_directories(d);
  return d;
}

std::string experiment(const std::string& output, double duration, const std::string& hydro = "fld",
                       const std::string& extra = "") {
  std::ostringstream y;
  y << "system:\n"
       "  shape: {plugin: dicolloid, c: 0.2}\n"
       "  count: 27\n"
       "  volume_fraction: 0.3\n"
       "  init: {method: monte_carlo, seed: 3, sweeps: 50}\n"
       "flow: {peclet: 5}\n"
       "hydro: {plugin: "
    << hydro
    << "}\n"
       "forces:\n"
       "  - {plugin: repulsion}\n"
       "run: {dt: 0.001, duration: "
    << duration
    << ", seed: 9}\n"
       "output: "
    << output << "\n"
    << extra;
  return y.str();
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

TEST(ExperimentRun, SmallRunWritesItsResultFile) {
  const fs::path d = scratch("small");
  write(d / "e.yaml", experiment((d / "out.h5").string(), 0.02));
  const Command c = run("run " + (d / "e.yaml").string());
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_TRUE(fs::exists(d / "out.h5"));
  EXPECT_FALSE(fs::exists(d / "out.h5.part"));
  EXPECT_NE(c.output.find("done: 20 steps"), std::string::npos) << c.output;
}

TEST(ExperimentRun, BadValueIsOneLineWithFileLineKeyAndExitCode2) {
  const fs::path d = scratch("bad");
  std::string y = experiment((d / "out.h5").string(), 0.02);
  y.replace(y.find("dt: 0.001"), 9, "dt: -1");
  write(d / "e.yaml", y);
  const Command c = run("check " + (d / "e.yaml").string());
  EXPECT_EQ(c.code, 2);
  EXPECT_EQ(c.output, (d / "e.yaml").string() + ":10:11: run.dt: expected a number > 0 or auto, got -1\n");
}

TEST(ExperimentRun, OverrideOfAListByNameIsAOneLineError) {
  const fs::path d = scratch("override");
  write(d / "e.yaml", experiment((d / "out.h5").string(), 0.02));
  const Command c = run("check " + (d / "e.yaml").string() + " --set forces.x=1");
  EXPECT_EQ(c.code, 2);
  EXPECT_EQ(c.output, "--set forces.x=1: forces: is a list: expected an index 0..0, got 'x'\n");
  const Command far = run("check " + (d / "e.yaml").string() + " --set forces.3.prefactor=1");
  EXPECT_EQ(far.code, 2);
  EXPECT_EQ(far.output, "--set forces.3.prefactor=1: forces: has 1 entry: index 3 is out of range\n");
}

// The form errors print (forces[0].plugin) addresses the same entry as the dotted one.
TEST(ExperimentRun, OverrideAcceptsTheIndexFormThatErrorsPrint) {
  const fs::path d = scratch("override-index");
  write(d / "e.yaml", experiment((d / "out.h5").string(), 0.02));
  const Command bracket = run("check " + (d / "e.yaml").string() + " --set forces[0].plugin=nosuch");
  const Command dotted = run("check " + (d / "e.yaml").string() + " --set forces.0.plugin=nosuch");
  EXPECT_EQ(bracket.code, 2);
  EXPECT_NE(bracket.output.find("forces[0].plugin: no force plugin named 'nosuch'"), std::string::npos)
      << bracket.output;
  // The same message after the option as typed.
  auto after_option = [](const std::string& s) { return s.substr(s.find(": ")); };
  EXPECT_EQ(after_option(bracket.output), after_option(dotted.output));
  const Command far = run("check " + (d / "e.yaml").string() + " --set forces[3].prefactor=1");
  EXPECT_EQ(far.output, "--set forces[3].prefactor=1: forces: has 1 entry: index 3 is out of range\n");
  EXPECT_EQ(run("check " + (d / "e.yaml").string() + " --set forces[0].prefactor=20").code, 0);
}

// Paths are relative to where they are written: `output:` in the file to the file's directory
// (whatever the current directory), `--set output=...` on the command line to the current one.
TEST(ExperimentRun, RelativePathsFollowWhereTheyAreWritten) {
  const fs::path d = scratch("relative");
  const fs::path elsewhere = scratch("relative-cwd");
  write(d / "e.yaml",
        experiment("results/out.h5", 0.002, "fld", "observers:\n  - {plugin: trajectory, every: 1}\n"));
  const std::string fldsim = std::string(FLDSIM_BINARY_DIR) + "/bin/fldsim";
  ASSERT_EQ(
      std::system(
          ("cd " + elsewhere.string() + " && " + fldsim + " run -q " + (d / "e.yaml").string()).c_str()),
      0);
  EXPECT_TRUE(fs::exists(d / "results" / "out.h5"));
  EXPECT_FALSE(fs::exists(elsewhere / "results" / "out.h5"));
  ASSERT_EQ(std::system(("cd " + elsewhere.string() + " && " + fldsim + " run -q " + (d / "e.yaml").string() +
                         " --set output=cli.h5")
                            .c_str()),
            0);
  EXPECT_TRUE(fs::exists(elsewhere / "cli.h5"));
  // system.init.file likewise: the result above, named relative to a second file beside it.
  std::string from_file = experiment("results/again.h5", 0.002);
  const std::string mc = "init: {method: monte_carlo, seed: 3, sweeps: 50}";
  from_file.replace(from_file.find(mc), mc.size(), "init: {method: file, file: results/out.h5}");
  write(d / "again.yaml", from_file);
  const Command again = run("run " + (d / "again.yaml").string());
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("start: last frame of " + (d / "results" / "out.h5").string()),
            std::string::npos)
      << again.output;
  EXPECT_TRUE(fs::exists(d / "results" / "again.h5"));
}

// Progress is on by default for runs of 1000 steps or more, off with run.progress: off or -q.
TEST(ExperimentRun, LongRunsReportProgressUnlessTurnedOff) {
  const fs::path d = scratch("progress");
  write(d / "long.yaml", experiment((d / "long.h5").string(), 1.0));    // 1000 steps
  write(d / "short.yaml", experiment((d / "short.h5").string(), 0.5));  // 500 steps
  const Command on = run("run " + (d / "long.yaml").string());
  ASSERT_EQ(on.code, 0) << on.output;
  EXPECT_NE(on.output.find("progress: 1000 steps"), std::string::npos) << on.output;
  const Command off = run("run " + (d / "long.yaml").string() + " --overwrite --set run.progress=off");
  ASSERT_EQ(off.code, 0) << off.output;
  EXPECT_EQ(off.output.find("progress:"), std::string::npos) << off.output;
  EXPECT_NE(off.output.find("done: 1000 steps"), std::string::npos) << off.output;
  const Command quiet = run("run -q " + (d / "long.yaml").string() + " --overwrite");
  ASSERT_EQ(quiet.code, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  const Command brief = run("run " + (d / "short.yaml").string());
  ASSERT_EQ(brief.code, 0) << brief.output;
  EXPECT_EQ(brief.output.find("progress:"), std::string::npos) << brief.output;
  const Command asked = run("run " + (d / "short.yaml").string() + " --overwrite --set run.progress=on");
  ASSERT_EQ(asked.code, 0) << asked.output;
  EXPECT_NE(asked.output.find("progress: 500 steps"), std::string::npos) << asked.output;
  // -q also silences a `progress` observer the experiment lists itself; errors still print.
  write(d / "listed.yaml",
        experiment((d / "listed.h5").string(), 0.5, "fld", "observers:\n  - {plugin: progress}\n"));
  const Command listed = run("run " + (d / "listed.yaml").string());
  EXPECT_NE(listed.output.find("progress: 500 steps"), std::string::npos) << listed.output;
  const Command listed_quiet = run("run -q " + (d / "listed.yaml").string() + " --overwrite");
  ASSERT_EQ(listed_quiet.code, 0) << listed_quiet.output;
  EXPECT_EQ(listed_quiet.output, "");
  const Command refused = run("run -q " + (d / "listed.yaml").string());
  // Refused by the pre-run check (exit 2, file:line:col), which -q does not mute.
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.output.find("listed.h5' exists; give --overwrite"), std::string::npos) << refused.output;
}

// A check only the plugin can make (in its constructor) is made by `check` too, not first at `run`.
TEST(ExperimentRun, CheckConstructsPluginsSoTheirOwnChecksFail) {
  const fs::path d = scratch("plugin-check");
  write(d / "e.yaml", experiment((d / "out.h5").string(), 0.02, "fld",
                                 "observers:\n  - {plugin: pair_distribution, projections: \"xy,xy\"}\n"));
  const Command c = run("check " + (d / "e.yaml").string());
  EXPECT_EQ(c.code, 2);
  EXPECT_EQ(c.output.rfind((d / "e.yaml").string() + ":", 0), 0u) << c.output;
  EXPECT_NE(c.output.find("projections: projection 'xy' listed twice\n"), std::string::npos) << c.output;
  EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '\n'), 1) << c.output;
}

TEST(ExperimentRun, ExistingResultIsNotOverwritten) {
  const fs::path d = scratch("exists");
  write(d / "out.h5", "precious");
  write(d / "e.yaml", experiment((d / "out.h5").string(), 0.002));
  const Command c = run("run " + (d / "e.yaml").string());
  // Refused by the checks before the run, as bad input (exit 2), at the `output` key.
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.output.find("out.h5' exists; give --overwrite to replace it, or another -o"), std::string::npos)
      << c.output;
  std::ifstream in(d / "out.h5");
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "precious");
}

TEST(ExperimentRun, ResumedRunIsBitIdenticalToUninterruptedRun) {
  const fs::path d = scratch("resume");
  // The observers' accumulated state must survive the restart too.
  const std::string observers =
      "observers:\n  - {plugin: orientation, every: 5}\n  - {plugin: stress, every: 5}\n"
      "  - {plugin: pair_distribution, every: 10, range: 3}\n  - {plugin: diffusion, every: 2}\n";
  write(d / "full.yaml", experiment((d / "full.h5").string(), 0.04, "fld", observers));
  write(d / "half.yaml", experiment((d / "half.h5").string(), 0.02, "fld", observers));
  write(d / "rest.yaml", experiment((d / "rest.h5").string(), 0.04, "fld", observers));
  ASSERT_EQ(run("run -q " + (d / "full.yaml").string()).code, 0);
  ASSERT_EQ(run("run -q " + (d / "half.yaml").string()).code, 0);
  const Command c =
      run("run -q " + (d / "rest.yaml").string() + " --resume " + (d / "half.h5.checkpoint").string());
  ASSERT_EQ(c.code, 0) << c.output;
  const auto a = fldsim::read_checkpoint((d / "full.h5.checkpoint").string());
  const auto b = fldsim::read_checkpoint((d / "rest.h5.checkpoint").string());
  ASSERT_EQ(a.step, 40);
  ASSERT_EQ(b.step, 40);
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << "body " << i;
    EXPECT_EQ(a.orientations[i].coeffs(), b.orientations[i].coeffs()) << "body " << i;
  }
  // Samples on both sides of the restart (steps 20 of 40): identical accumulators.
  for (const std::string key : {"observers[0].orientation", "observers[1].stress",
                                "observers[2].pair_distribution", "observers[3].diffusion"}) {
    ASSERT_TRUE(a.blobs.count(key) && b.blobs.count(key)) << key;
    EXPECT_FALSE(a.blobs.at(key).empty()) << key;
    EXPECT_EQ(a.blobs.at(key), b.blobs.at(key)) << key;
  }
}

}  // namespace

namespace {

// `dt: auto` keeps the counter-based reproducibility: the adaptive state (the step proposal and
// the statistics) is in the checkpoint, and a frame's end leaves no bridged noise pending, so a
// resumed run is bit-identical; the thread count changes nothing. Free-draining spheres with
// the paper's repulsion: steps shrink at every contact, so there are many step lengths.
std::string adaptive(const std::string& output, double duration, const std::string& threads,
                     const std::string& rule = "tolerance: 0.002") {
  std::ostringstream y;
  y << "system:\n"
       "  shape: {plugin: sphere}\n"
       "  count: 64\n"
       "  volume_fraction: 0.3\n"
       "  init: {method: monte_carlo, seed: 3, sweeps: 50}\n"
       "hydro: {plugin: free_draining}\n"
       "forces:\n"
       "  - {plugin: repulsion}\n"
       "run: {dt: auto, dt_max: 0.001, "
    << rule << ", duration: " << duration << ", seed: 9, threads: " << threads
    << "}\n"
       "observers:\n  - {plugin: pair_distribution, every: 5, range: 3}\n"
       "output: "
    << output << "\n";
  return y.str();
}

void expect_adaptive_resume_bit_identical(const std::string& name, const std::string& rule) {
  const fs::path d = scratch(name);
  write(d / "full.yaml", adaptive((d / "full.h5").string(), 0.03, "1", rule));
  write(d / "two.yaml", adaptive((d / "two.h5").string(), 0.03, "2", rule));
  write(d / "half.yaml", adaptive((d / "half.h5").string(), 0.015, "1", rule));
  write(d / "rest.yaml", adaptive((d / "rest.h5").string(), 0.03, "1", rule));
  const Command full = run("run " + (d / "full.yaml").string());
  ASSERT_EQ(full.code, 0) << full.output;
  EXPECT_NE(full.output.find("steps: "), std::string::npos) << full.output;
  ASSERT_EQ(run("run -q " + (d / "two.yaml").string()).code, 0);
  ASSERT_EQ(run("run -q " + (d / "half.yaml").string()).code, 0);
  const Command c =
      run("run -q " + (d / "rest.yaml").string() + " --resume " + (d / "half.h5.checkpoint").string());
  ASSERT_EQ(c.code, 0) << c.output;
  const auto a = fldsim::read_checkpoint((d / "full.h5.checkpoint").string());
  for (const std::string other : {"two", "rest"}) {
    const auto b = fldsim::read_checkpoint((d / (other + ".h5.checkpoint")).string());
    ASSERT_EQ(b.step, a.step) << other;
    for (std::size_t i = 0; i < a.positions.size(); ++i) EXPECT_EQ(a.positions[i], b.positions[i]) << other;
    for (const std::string key : {"run.steps", "observers[0].pair_distribution"}) {
      ASSERT_TRUE(a.blobs.count(key) && b.blobs.count(key)) << key;
      EXPECT_EQ(a.blobs.at(key), b.blobs.at(key)) << other << " " << key;
    }
  }
  // The run did adapt: more steps than frames, of several lengths.
  const auto& steps = a.blobs.at("run.steps");
  const double accepted = steps.at(3);  // after the proposal, overlap frames, deepest overlap
  EXPECT_GT(accepted, double(a.step)) << "no step was shorter than dt_max";
}

TEST(ExperimentRun, AdaptiveRunResumesBitIdenticallyOnAnyThreadCount) {
  expect_adaptive_resume_bit_identical("adaptive", "tolerance: 0.002");
}

// The displacement bound's state (the bound and its averaged rate) is in the checkpoint too;
// alone (no tolerance) and with the error controller; and the pair-gap bound's (with its
// statistics, saved after the rest).
TEST(ExperimentRun, DisplacementBoundRunResumesBitIdentically) {
  expect_adaptive_resume_bit_identical("bound", "displacement: 0.02");
  expect_adaptive_resume_bit_identical("gap", "gap_step: 0.02");
  expect_adaptive_resume_bit_identical("both", "displacement: 0.03, tolerance: 0.004");
}

// A run that cannot go on stops with one line naming the time and the cause, and a checkpoint
// at the start of the frame that failed. Here a fixed step of 0.05 a^2/D0 with free draining
// makes overlaps far beyond max_overlap = 1e-4 a, and dt_min forbids the retries it would need.
TEST(ExperimentRun, RunThatCannotGoOnStopsWithACheckpointAndOneLine) {
  const fs::path d = scratch("stuck");
  std::string text = adaptive((d / "stuck.h5").string(), 1.0, "1");
  const std::string from = "run: {dt: auto, dt_max: 0.001, tolerance: 0.002, duration: 1";
  text.replace(text.find(from), from.size(),
               "run: {dt: 0.05, dt_min: 0.02, max_overlap: 1.0e-4, duration: 1");
  write(d / "stuck.yaml", text);
  const Command c = run("run -q " + (d / "stuck.yaml").string());
  EXPECT_NE(c.code, 0);
  EXPECT_NE(c.output.find("cannot go on"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("overlap"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("checkpoint at that time"), std::string::npos) << c.output;
  const auto k = fldsim::read_checkpoint((d / "stuck.h5.checkpoint").string());
  EXPECT_LT(k.step, 20);
  EXPECT_NEAR(k.time, 0.05 * double(k.step), 1e-12);
}

}  // namespace
