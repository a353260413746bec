// A full disk, simulated with an LD_PRELOAD library (fixtures/write_failure_injector.c) that
// makes writes to chosen files fail with ENOSPC after a byte budget. The run must stop with one
// line naming the file and "No space left on device", exit 1, never crash, keep the last good
// checkpoint readable, and never leave a half-written file under a real name.
#include <gtest/gtest.h>

#include <filesystem>

#include "CorpusRunner.hpp"
#include "io/Checkpoint.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kExperiment =
    "system: {shape: {plugin: dicolloid}, count: 27, volume_fraction: 0.05}\n"
    "flow: {peclet: 1}\n"
    "hydro: {plugin: free_draining}\n"
    "run: {dt: 0.01, duration: 2, threads: 1, checkpoint_every: 0.5}\n"
    "observers: [{plugin: trajectory, every: 1}, {plugin: orientation, every: 1}]\n"
    "output: out.h5\n";

corpus::Case disk_full(const std::string& matching, long long budget) {
  corpus::Case c;
  c.files["in.yaml"] = kExperiment;
  c.args = {"run", "in.yaml", "-q"};
  c.env["LD_PRELOAD"] = WRITE_FAILURE_INJECTOR;
  c.env["ASAN_OPTIONS"] = "verify_asan_link_order=0:detect_leaks=1";
  c.env["FLDSIM_FAIL_WRITES_MATCHING"] = matching;
  c.env["FLDSIM_FAIL_WRITES_AFTER"] = std::to_string(budget);
  c.exit_code = 1;
  return c;
}

fs::path dir_for(const std::string& name) {
  return fs::temp_directory_path() / ("fldsim-diskfull-" + std::to_string(::getpid())) / name;
}

TEST(DiskFull, ResultFileFullStopsWithOneLineAndKeepsTheLastCheckpoint) {
  corpus::Case c = disk_full(".part", 200000);
  c.lines = {"^fldsim: error: out\\.h5\\.part: .*No space left on device"};
  c.may_leave = {"out.h5.part", "out.h5.checkpoint"};
  const fs::path dir = dir_for("result");
  const corpus::Outcome o = corpus::run_case(c, dir);
  const corpus::Verdict v = corpus::judge(c, o);
  EXPECT_TRUE(v.clear && !v.crash) << v.why;
  EXPECT_FALSE(fs::exists(dir / "out.h5")) << "a half result under the real name";
  EXPECT_FALSE(fs::exists(dir / "out.h5.checkpoint.tmp"));
  ASSERT_TRUE(fs::exists(dir / "out.h5.checkpoint")) << o.err;
  const fldsim::Checkpoint last = fldsim::read_checkpoint((dir / "out.h5.checkpoint").string());
  EXPECT_EQ(last.positions.size(), 27u);
  EXPECT_EQ(last.step % 50, 0) << "a checkpoint of a checkpoint_every step";
  EXPECT_GT(last.step, 0);
}

// Another error ends the run while the result file's last data still sit in HDF5's cache and
// the disk is full: the unwinding close met the full disk and crashed (SIGSEGV in H5F__close)
// until the sink flushed first. The plugin's error is the one line; nothing crashes.
TEST(DiskFull, ErrorMidRunWithAFullDiskDoesNotCrash) {
  corpus::Case c = disk_full(".part", 200000);
  c.files["in.yaml"] =
      "system: {shape: {plugin: dicolloid}, count: 27, volume_fraction: 0.05}\n"
      "flow: {peclet: 1}\n"
      "hydro: {plugin: free_draining}\n"
      "run: {dt: 0.01, duration: 2, threads: 1, checkpoint_every: 0.5}\n"
      "observers: [{plugin: trajectory, every: 1}, {plugin: orientation, every: 1},\n"
      "            {plugin: hostile_throw_sample, when: 103}]\n"
      "plugins: {paths: [" HOSTILE_DIR
      "/throw_in_sample]}\n"
      "output: out.h5\n";
  c.lines = {"^fldsim: error: observer plugin 'hostile_throw_sample' .*sample gives up"};
  c.may_leave = {"out.h5.part", "out.h5.checkpoint"};
  const fs::path dir = dir_for("error-mid-run");
  const corpus::Outcome o = corpus::run_case(c, dir);
  const corpus::Verdict v = corpus::judge(c, o);
  EXPECT_TRUE(v.clear && !v.crash) << v.why;
  EXPECT_FALSE(fs::exists(dir / "out.h5")) << "a half result under the real name";
  ASSERT_TRUE(fs::exists(dir / "out.h5.checkpoint")) << o.err;
  EXPECT_EQ(fldsim::read_checkpoint((dir / "out.h5.checkpoint").string()).step, 100)
      << "the last periodic checkpoint before the error";
}

TEST(DiskFull, CheckpointFullKeepsThePreviousCheckpoint) {
  // First a run without failures, to learn what one checkpoint writes.
  corpus::Case measure = disk_full("nothing-matches-this", 0);
  measure.exit_code = 0;
  measure.may_leave = {"out.h5", "out.h5.checkpoint"};
  const fs::path mdir = dir_for("measure");
  const corpus::Outcome m = corpus::run_case(measure, mdir);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const auto one = static_cast<long long>(fs::file_size(mdir / "out.h5.checkpoint"));

  // Room for one and a half checkpoints' worth of bytes: a later one fails part-way.
  corpus::Case c = disk_full("checkpoint", one + one / 2);
  c.lines = {
      "^fldsim: error: out\\.h5\\.checkpoint\\.tmp: cannot write the checkpoint \\(the previous one is "
      "kept\\): .*No space left on device"};
  c.may_leave = {"out.h5.part", "out.h5.checkpoint"};
  const fs::path dir = dir_for("checkpoint");
  const corpus::Outcome o = corpus::run_case(c, dir);
  const corpus::Verdict v = corpus::judge(c, o);
  EXPECT_TRUE(v.clear && !v.crash) << v.why;
  EXPECT_FALSE(fs::exists(dir / "out.h5.checkpoint.tmp")) << "the half-written checkpoint is removed";
  ASSERT_TRUE(fs::exists(dir / "out.h5.checkpoint"));
  const fldsim::Checkpoint last = fldsim::read_checkpoint((dir / "out.h5.checkpoint").string());
  EXPECT_GT(last.step, 0);
  EXPECT_LT(last.step, 200) << "the run did not reach its end";
  EXPECT_EQ(last.step % 50, 0) << "the last good periodic checkpoint, intact";
  fs::remove_all(dir.parent_path());
}

}  // namespace
