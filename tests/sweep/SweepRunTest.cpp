// Whole sweeps through the real `fldsim` program: every point runs once and lands in the study
// table with exactly the numbers of its own result file; a second invocation runs nothing; a
// changed base is refused before anything runs (nothing touched) and re-run only on request
// (old files kept); an interrupted sweep resumes to the same numbers, bit for bit, as an
// uninterrupted `fldsim run` of the point; under mpirun the same study comes out; and a rank
// that dies loses no point.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "io/Checkpoint.hpp"
#include "io/Summary.hpp"

namespace {

namespace fs = std::filesystem;

const char* kBase = R"(system:
  shape: {plugin: sphere}
  count: 27
  volume_fraction: 0.1
  init: {method: monte_carlo, seed: 1}
flow: {peclet: 1}
hydro: {plugin: free_draining}
forces:
  - {plugin: repulsion}
run: {dt: 1.0e-3, duration: 0.4, time_unit: diffusive, threads: 1}
observers:
  - {plugin: stress, every: 5}
output: unused.h5
)";

const char* kSweep = R"(base: base.yaml
output_dir: results
axes:
  - flow.peclet: [0.5, 2]
  - hydro.plugin: [free_draining, fld]
)";

struct Result {
  int code = -1;
  std::string output;
};

// Runs a shell command line, stdout and stderr together.
Result run(const std::string& command) {
  Result r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, p)) r.output.append(buffer, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fldsim-sweep-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "base.yaml") << kBase;
  std::ofstream(d / "study.yaml") << kSweep;
  return d;
}

std::string sweep(const fs::path& dir, const std::string& options = "") {
  return "cd " + dir.string() + " && " FLDSIM_EXE " sweep study.yaml " + options;
}

// study.csv as rows of column -> text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& s) {
    std::vector<std::string> out(1);
    for (char c : s)
      if (c == ',')
        out.emplace_back();
      else
        out.back() += c;
    return out;
  };
  std::getline(in, line);
  header = split(line);
  while (std::getline(in, line)) {
    const auto f = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

double scalar(const fs::path& file, const std::string& name) {
  for (const auto& s : fldsim::read_result_scalars(file.string()))
    if (s.name == name) return s.value;
  ADD_FAILURE() << name << " not in " << file;
  return 0.0;
}

// Processes whose command line contains `text` (the /proc scan `pgrep -f` does).
std::vector<pid_t> processes_with(const std::string& text) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "cmdline");
    std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::replace(cmd.begin(), cmd.end(), '\0', ' ');
    if (cmd.find(text) != std::string::npos) out.push_back(pid_t(std::stol(name)));
  }
  return out;
}

pid_t parent_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream fields(stat.substr(stat.rfind(')') + 2));
  char state;
  pid_t ppid = 0;
  fields >> state >> ppid;
  return ppid;
}

bool log_shows_steps(const fs::path& log) {
  std::ifstream in(log);
  std::stringstream s;
  s << in.rdbuf();
  return s.str().find("step ") != std::string::npos;
}

std::map<std::string, fs::file_time_type> times_of(const fs::path& dir) {
  std::map<std::string, fs::file_time_type> t;
  for (const auto& e : fs::directory_iterator(dir)) t[e.path().filename()] = fs::last_write_time(e.path());
  return t;
}

TEST(Sweep, EveryPointRunsOnceAndTheStudyTableHoldsItsResults) {
  const fs::path d = fresh_dir("local");
  const Result first = run(sweep(d));
  ASSERT_EQ(first.code, 0) << first.output;
  const auto rows = read_csv(d / "results" / "study.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "done");
    const fs::path h5 = d / "results" / (row.at("point") + ".h5");
    ASSERT_TRUE(fs::exists(h5)) << h5;
    // The table's number is the file's number (printed with 10 significant digits).
    const double eta = scalar(h5, "stress/eta_r");
    EXPECT_NEAR(std::stod(row.at("stress/eta_r")), eta, 1e-9 * std::abs(eta)) << row.at("point");
    EXPECT_EQ(row.at("point"), "peclet-" + row.at("flow.peclet") + "_plugin-" + row.at("hydro.plugin"));
  }
  // Each point is the experiment `fldsim run --set` gives: same seed, same numbers.
  const Result single =
      run("cd " + d.string() +
          " && " FLDSIM_EXE
          " run base.yaml -q -o single.h5 --set flow.peclet=2 --set hydro.plugin=fld --set run.threads=1");
  ASSERT_EQ(single.code, 0) << single.output;
  EXPECT_EQ(scalar(d / "single.h5", "stress/eta_r"),
            scalar(d / "results" / "peclet-2_plugin-fld.h5", "stress/eta_r"));

  const auto before = times_of(d / "results");
  const Result again = run(sweep(d));
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("0 to run, 0 to resume, 4 done, 0 changed"), std::string::npos) << again.output;
  for (const auto& [name, t] : times_of(d / "results"))
    if (name.rfind("study.", 0) != 0) {
      EXPECT_EQ(t, before.at(name)) << name << " was touched by a sweep with nothing to do";
    }
}

// `--dry-run --timed K`: every point is timed by a short run of itself, its listed cost is its
// frames x the measured time per frame, and nothing is left behind (no result, log or scratch file).
TEST(Sweep, TimedDryRunMeasuresEveryPointAndLeavesNoFile) {
  const fs::path d = fresh_dir("timed");
  auto probes = [] {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
      if (e.path().filename().string().rfind("fldsim-sweep-probe-", 0) == 0) out.insert(e.path().string());
    return out;
  };
  const auto probes_before = probes();
  const Result r = run(sweep(d, "--dry-run --timed 5"));
  ASSERT_EQ(r.code, 0) << r.output;
  // "timing LABEL (K frames) ... X ms/frame" for each point, then the listing with "(timed)" costs.
  std::istringstream lines(r.output);
  std::map<std::string, double> ms;
  std::map<std::string, std::string> listed;
  for (std::string line; std::getline(lines, line);) {
    char label[128];
    int frames = 0;
    double x = 0;
    if (std::sscanf(line.c_str(), "timing %127s (%d frames) ... %lf ms/frame", label, &frames, &x) == 3) {
      EXPECT_EQ(frames, 5) << line;
      ms[label] = x;
    }
    if (line.find("(timed)") != std::string::npos && line.find("to run") != std::string::npos)
      listed[line.substr(0, line.find(' '))] = line;
  }
  ASSERT_EQ(ms.size(), 4u) << r.output;
  ASSERT_EQ(listed.size(), 4u) << r.output;
  for (const auto& [label, x] : ms) {
    EXPECT_GT(x, 0.0) << label;
    // 400 frames (0.4 / 1e-3) x x ms on 1 thread, as format_duration prints seconds below 10 s.
    const double seconds = 400 * x * 1e-3;
    char expected[32];
    std::snprintf(expected, sizeof expected, seconds < 10 ? "%.1f s (timed)" : "%.0f s (timed)", seconds);
    EXPECT_NE(listed.at(label).find(expected), std::string::npos) << listed.at(label) << " vs " << expected;
  }
  EXPECT_FALSE(fs::exists(d / "results")) << "a dry run wrote into the output directory";
  EXPECT_EQ(probes(), probes_before) << "a probe's scratch directory was left behind";
}

TEST(Sweep, AChangedBaseIsRefusedBeforeAnythingRunsAndReRunOnlyOnRequest) {
  const fs::path d = fresh_dir("changed");
  ASSERT_EQ(run(sweep(d)).code, 0);
  std::string base = kBase;
  base.replace(base.find("duration: 0.4"), 13, "duration: 0.3");
  std::ofstream(d / "base.yaml") << base;
  const auto before = times_of(d / "results");
  const Result refused = run(sweep(d));
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_NE(refused.output.find("stored `run: {dt: 1.0e-3, duration: 0.4"), std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("4 point(s) have files of a different experiment"), std::string::npos);
  EXPECT_EQ(times_of(d / "results"), before) << "a refused sweep must not touch any file";

  const Result rerun = run(sweep(d, "--rerun-changed"));
  ASSERT_EQ(rerun.code, 0) << rerun.output;
  const fs::path old = d / "results" / "peclet-0.5_plugin-fld.h5.superseded";
  ASSERT_TRUE(fs::exists(old)) << "the old result must be kept";
  EXPECT_NE(scalar(old, "steps/accepted"),
            scalar(d / "results" / "peclet-0.5_plugin-fld.h5", "steps/accepted"));
}

TEST(Sweep, AnInterruptedSweepResumesToTheNumbersOfAnUninterruptedRun) {
  const fs::path d = fresh_dir("resume");
  // One longer point, so that the signal arrives while it runs.
  std::ofstream(d / "study.yaml") << "base: base.yaml\noutput_dir: results\naxes:\n  - run.duration: [60]\n"
                                     "  - hydro.plugin: [fld]\n";
  const pid_t pid = fork();
  if (pid == 0) {
    ::chdir(d.c_str());
    ::freopen("sweep.log", "w", stderr);
    execl(FLDSIM_EXE, FLDSIM_EXE, "sweep", "study.yaml", static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path log = d / "results" / "duration-60_plugin-fld.log";
  // Wait until the point has taken steps (its log shows the run's start), then interrupt.
  for (int i = 0; i < 300; ++i) {
    std::ifstream in(log);
    std::stringstream s;
    s << in.rdbuf();
    if (s.str().find("steps") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 130) << "an interrupted sweep says so with 128 + SIGINT";
  ASSERT_TRUE(fs::exists(d / "results" / "duration-60_plugin-fld.h5.checkpoint"));
  const auto partial = read_csv(d / "results" / "study.csv");
  ASSERT_EQ(partial.size(), 1u);
  EXPECT_EQ(partial[0].at("status"), "interrupted") << "partial results must be flagged in the study table";

  // The listing's estimate is for the frames left (SweepPoints.AResumedPointIsEstimatedForTheFramesLeft).
  const Result listing = run(sweep(d, "--dry-run"));
  ASSERT_EQ(listing.code, 0) << listing.output;
  // "estimated CPU 6.1 s to go (8.4 s for the whole sweep": both printed to 0.05 s.
  double to_go = 0.0, whole = 0.0;
  const std::size_t at = listing.output.find("estimated CPU ");
  ASSERT_NE(at, std::string::npos) << listing.output;
  ASSERT_EQ(std::sscanf(listing.output.c_str() + at, "estimated CPU %lf s to go (%lf s for the whole", &to_go,
                        &whole),
            2)
      << listing.output;
  const double frames = 60.0 / 1e-3;
  const double share =
      1.0 -
      double(
          fldsim::read_checkpoint((d / "results" / "duration-60_plugin-fld.h5.checkpoint").string()).step) /
          frames;
  EXPECT_NEAR(to_go / whole, share, 0.05 / to_go + 0.05 / whole) << listing.output;

  const Result resumed = run(sweep(d));
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("1 to resume"), std::string::npos) << resumed.output;
  EXPECT_TRUE(fs::exists(d / "results" / "duration-60_plugin-fld.h5.interrupted"))
      << "the partial result is kept";

  const Result straight = run(
      "cd " + d.string() +
      " && " FLDSIM_EXE
      " run base.yaml -q -o straight.h5 --set run.duration=60 --set hydro.plugin=fld --set run.threads=1");
  ASSERT_EQ(straight.code, 0) << straight.output;
  EXPECT_EQ(scalar(d / "straight.h5", "stress/eta_r"),
            scalar(d / "results" / "duration-60_plugin-fld.h5", "stress/eta_r"));
  EXPECT_EQ(scalar(d / "straight.h5", "stress/Z"),
            scalar(d / "results" / "duration-60_plugin-fld.h5", "stress/Z"));
}

TEST(Sweep, UnderMpirunTheSameStudyComesOut) {
  const std::string mpirun = FLDSIM_MPIRUN;
  if (mpirun.empty()) GTEST_SKIP() << "fldsim built without MPI (Debian: libopenmpi-dev openmpi-bin)";
  const fs::path local = fresh_dir("mpi-local"), mpi = fresh_dir("mpi");
  ASSERT_EQ(run(sweep(local)).code, 0);
  // Under `make sanitize`, LeakSanitizer would report OpenMPI's own allocations kept until exit
  // (not attributable: its components are unloaded by then); the sweep code's leaks are checked
  // by the local-sweep tests, which run the same scheduler code paths without MPI.
  const Result r = run("cd " + mpi.string() + " && ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" " + mpirun +
                       " --allow-run-as-root --oversubscribe -n 3 " FLDSIM_EXE " sweep study.yaml");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("over 3 MPI rank(s)"), std::string::npos) << r.output;
  std::ifstream a(local / "results" / "study.csv"), b(mpi / "results" / "study.csv");
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  EXPECT_EQ(sa.str(), sb.str()) << "the same points with the same seeds must give the same table";
}

// A rank that dies (kill -9, as a lost node) loses no point: its running point stops with a
// checkpoint instead of running on as an orphan that would write the files the next invocation
// resumes (measured before the fix: the orphan ran to its end after mpirun had exited), and the
// next invocation finishes the study with exactly the numbers of an uninterrupted run.
TEST(Sweep, ARankThatDiesLosesNoPointAndTheNextInvocationResumesIt) {
  const std::string mpirun = FLDSIM_MPIRUN;
  if (mpirun.empty()) GTEST_SKIP() << "fldsim built without MPI (Debian: libopenmpi-dev openmpi-bin)";
  const fs::path d = fresh_dir("rank-death");
  const std::string out_dir = "results-rank-death-" + std::to_string(::getpid());
  std::ofstream(d / "study.yaml") << "base: base.yaml\noutput_dir: " << out_dir
                                  << "\naxes:\n  - run.duration: [60]\n  - flow.peclet: [0.5, 2]\n"
                                     "  - hydro.plugin: [fld]\n";
  const pid_t launcher = fork();
  if (launcher == 0) {
    ::chdir(d.c_str());
    ::freopen("mpirun.log", "w", stdout);
    ::freopen("mpirun.log", "a", stderr);
    ::setenv("ASAN_OPTIONS",
             (std::string(getenv("ASAN_OPTIONS") ? getenv("ASAN_OPTIONS") : "") + ":detect_leaks=0").c_str(),
             1);
    execl("/bin/sh", "sh", "-c",
          (mpirun + " --allow-run-as-root --oversubscribe -n 2 " FLDSIM_EXE " sweep study.yaml").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path results = d / out_dir;
  const std::string first = "duration-60_peclet-0.5_plugin-fld", second = "duration-60_peclet-2_plugin-fld";
  for (int i = 0; i < 600 && !(log_shows_steps(results / (first + ".log")) &&
                               log_shows_steps(results / (second + ".log")));
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  // The rank running the first point: the parent of its `fldsim run`.
  const std::vector<pid_t> point = processes_with("-o " + out_dir + "/" + first + ".h5");
  ASSERT_EQ(point.size(), 1u) << "the first point is not running";
  const pid_t rank = parent_of(point[0]);
  ASSERT_GT(rank, 1);
  ::kill(rank, SIGKILL);
  int status = 0;
  waitpid(launcher, &status, 0);
  EXPECT_NE(WEXITSTATUS(status), 0) << "mpirun reports the dead rank";
  // No point may run on after its rank: both stop within two seconds (a step and a checkpoint),
  // long before an orphan could finish (each point is about 25 s of work).
  bool orphans = true;
  for (int i = 0; i < 20 && orphans; ++i) {
    orphans = !processes_with("-o " + out_dir + "/").empty();
    if (orphans) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_FALSE(orphans) << "a point outlived its rank";
  // Both points stop checkpointed: the dead rank's by its parent-death signal, the other rank's by
  // the SIGTERM its rank passes on before mpirun kills it (the points have their own process
  // groups, so mpirun's SIGKILL of the ranks' groups does not cut their checkpoint short).
  for (const std::string& point_name : {first, second}) {
    std::ifstream log(results / (point_name + ".log"));
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("interrupted by SIGTERM"), std::string::npos)
        << point_name << " must stop checkpointed:\n"
        << text;
    EXPECT_TRUE(fs::exists(results / (point_name + ".h5.checkpoint"))) << point_name;
  }

  const Result again =
      run("cd " + d.string() + " && ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" " + mpirun +
          " --allow-run-as-root --oversubscribe -n 2 " FLDSIM_EXE " sweep study.yaml");
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("2 of 2 points done"), std::string::npos) << again.output;
  const Result straight = run("cd " + d.string() +
                              " && " FLDSIM_EXE
                              " run base.yaml -q -o straight.h5 --set run.duration=60 --set flow.peclet=0.5 "
                              "--set hydro.plugin=fld --set run.threads=1");
  ASSERT_EQ(straight.code, 0) << straight.output;
  EXPECT_EQ(scalar(d / "straight.h5", "stress/eta_r"), scalar(results / (first + ".h5"), "stress/eta_r"));
  EXPECT_EQ(scalar(d / "straight.h5", "stress/Z"), scalar(results / (first + ".h5"), "stress/Z"));
}

}  // namespace
