// SIGINT and SIGTERM during a run: the run finishes its step, writes its checkpoint and a
// readable result file holding everything observed so far (marked as interrupted), says so,
// and exits 128 + signal; resuming from that checkpoint ends bit for bit where an
// uninterrupted run ends (same final checkpoint: positions, orientations, displacements,
// solver warm start, every observer's accumulated state).
#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "CorpusRunner.hpp"
#include "io/Checkpoint.hpp"
#include "io/H5Helpers.hpp"

namespace {

namespace fs = std::filesystem;

// 6000 steps of a small FLD scene with accumulating observers: long enough (seconds) to be
// interrupted after its first periodic checkpoint (step 50).
const std::string kExperiment =
    "system: {shape: {plugin: dicolloid}, count: 27, volume_fraction: 0.2}\n"
    "flow: {peclet: 1}\n"
    "hydro: {plugin: fld}\n"
    "forces: [{plugin: repulsion}]\n"
    "run: {dt: 0.001, duration: 6, threads: 1, checkpoint_every: 0.05}\n"
    "observers: [{plugin: orientation, every: 10}, {plugin: stress, every: 10},\n"
    "            {plugin: pair_distribution, every: 50, range: 3, bins: 20}, {plugin: trajectory, every: "
    "100}]\n"
    "output: out.h5\n";

struct Exit {
  int code = -1;
  std::string err;
};

// Runs fldsim in `dir`; when `signal` is set, sends it once the first periodic checkpoint exists.
Exit run_fldsim(const fs::path& dir, const std::vector<std::string>& args, int signal = 0) {
  const fs::path err_file = dir / "stderr.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    if (!std::freopen(err_file.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) ::_exit(126);
    std::vector<std::string> all{FLDSIM_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(FLDSIM_EXE, argv.data());
    ::_exit(127);
  }
  if (signal != 0) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir / "out.h5.checkpoint") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(pid, signal);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  Exit e;
  e.code = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  std::ifstream in(err_file);
  e.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return e;
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("fldsim-signal-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "in.yaml") << kExperiment;
  return dir;
}

void expect_same_state(const fldsim::Checkpoint& a, const fldsim::Checkpoint& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.strain, b.strain);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << "body " << i;
    EXPECT_EQ(a.orientations[i].coeffs(), b.orientations[i].coeffs()) << "body " << i;
    EXPECT_EQ(a.displacement[i], b.displacement[i]) << "body " << i;
    EXPECT_EQ(a.nonaffine[i], b.nonaffine[i]) << "body " << i;
  }
  EXPECT_EQ(a.warm_start, b.warm_start);
  ASSERT_EQ(a.blobs.size(), b.blobs.size());
  for (const auto& [key, value] : a.blobs) {
    ASSERT_TRUE(b.blobs.count(key)) << key;
    EXPECT_EQ(value, b.blobs.at(key)) << key;
  }
}

std::string run_status(const fs::path& result) {
  fldsim::io::quiet_hdf5();
  H5::H5File file(result.string(), H5F_ACC_RDONLY);
  return fldsim::io::read_string_attribute(file.openGroup("/parameters"), "run_status");
}

class Interrupted : public ::testing::TestWithParam<int> {};

TEST_P(Interrupted, KeepsEverythingAndResumesBitForBit) {
  const int sig = GetParam();
  const std::string name = sig == SIGINT ? "SIGINT" : "SIGTERM";
  const fs::path whole = fresh(name + "-whole"), cut = fresh(name + "-cut");

  const Exit reference = run_fldsim(whole, {"run", "in.yaml", "-q"});
  ASSERT_EQ(reference.code, 0) << reference.err;

  const Exit stopped = run_fldsim(cut, {"run", "in.yaml", "-q"}, sig);
  ASSERT_EQ(stopped.code, 128 + sig) << stopped.err;
  EXPECT_NE(stopped.err.find("fldsim: interrupted by " + name + " at step "), std::string::npos)
      << stopped.err;
  EXPECT_NE(
      stopped.err.find("results so far in out.h5, state in out.h5.checkpoint; continue with: fldsim run "
                       "in.yaml --resume out.h5.checkpoint"),
      std::string::npos)
      << stopped.err;
  // The result file is there under its real name, readable, and says it was interrupted.
  ASSERT_TRUE(fs::exists(cut / "out.h5"));
  EXPECT_FALSE(fs::exists(cut / "out.h5.part"));
  EXPECT_EQ(run_status(cut / "out.h5").rfind("interrupted by " + name + " at step ", 0), 0u);
  const Exit summary = run_fldsim(cut, {"summary", "out.h5"});
  EXPECT_EQ(summary.code, 0) << summary.err;
  const fldsim::Checkpoint at_stop = fldsim::read_checkpoint((cut / "out.h5.checkpoint").string());
  EXPECT_GT(at_stop.step, 0);
  EXPECT_LT(at_stop.step, 6000) << "the signal came after the end: the run is too short for this machine";

  // Resumed, it ends exactly where the uninterrupted run ends.
  const Exit resumed =
      run_fldsim(cut, {"run", "in.yaml", "-q", "--resume", "out.h5.checkpoint", "-o", "rest.h5"});
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  expect_same_state(fldsim::read_checkpoint((whole / "out.h5.checkpoint").string()),
                    fldsim::read_checkpoint((cut / "rest.h5.checkpoint").string()));
  fs::remove_all(whole);
  fs::remove_all(cut);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupted, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return info.param == SIGINT ? "SIGINT" : "SIGTERM"; });

}  // namespace
