#include "sweep/StepProbe.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "sweep/PointProcess.hpp"

extern char** environ;

namespace fldsim {
namespace {

namespace fs = std::filesystem;

// Runs argv with stdout and stderr to `log_path`; returns the exit code (128 + signal if killed),
// or -1 if it could not be started.
int run_to_log(const std::vector<std::string>& args, const std::string& log_path) {
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, copy[0].c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

double logged_ms_per_frame(const std::string& log_text) {
  std::size_t at = std::string::npos;  // the last line that starts with "done: "
  for (std::size_t pos = log_text.find("done: "); pos != std::string::npos;
       pos = log_text.find("done: ", pos + 1))
    if (pos == 0 || log_text[pos - 1] == '\n') at = pos;
  if (at == std::string::npos) return -1.0;
  const std::size_t open = log_text.find('(', at);
  if (open == std::string::npos || open > log_text.find('\n', at)) return -1.0;
  double ms = -1.0;
  char unit[16] = {0};
  if (std::sscanf(log_text.c_str() + open, "(%lf %15[^,]", &ms, unit) != 2 ||
      std::strcmp(unit, "ms/step") != 0)
    return -1.0;
  return ms;
}

std::size_t time_points(const SweepPlan& plan, std::vector<PointState>& points, int frames,
                        const std::string& program, std::ostream& log) {
  const fs::path scratch = fs::temp_directory_path() / ("fldsim-sweep-probe-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directories(scratch, ec);
  std::size_t timed = 0;
  for (auto& st : points) {
    if (st.status == PointStatus::Done || st.steps <= 0 || st.frame <= 0.0) continue;
    const SweepPoint& p = plan.points[st.index];
    // Long enough for every observer to sample once (up to 10 K frames; a sparser observer samples
    // every 10 K frames in the probe, which overstates its share of the cost).
    std::int64_t k = frames;
    for (std::int64_t every : st.observer_every) k = std::max(k, std::min<std::int64_t>(every, 10 * frames));
    k = std::min(k, st.steps);
    const fs::path out = scratch / "probe.h5", probe_log = scratch / "probe.log";
    std::vector<std::string> args = {program, "run", plan.base, "-o", out.string()};
    for (const auto& o : p.overrides()) args.insert(args.end(), {"--set", o});
    char duration[64];
    std::snprintf(duration, sizeof duration, "run.duration=%.17g", double(k) * st.frame);
    args.insert(args.end(), {"--set", duration, "--set", "run.checkpoint_every=0"});
    // Observers that start later (an averaging window) sample from the first frame: their cost
    // belongs to the point, and a start after the probe's end would be refused.
    for (std::size_t i = 0; i < st.observer_every.size(); ++i) {
      const std::string o = "observers[" + std::to_string(i) + "].";
      args.insert(args.end(), {"--set", o + "start=0"});
      if (st.observer_every[i] > k) args.insert(args.end(), {"--set", o + "every=" + std::to_string(k)});
    }
    log << "timing " << p.label << " (" << k << " frames) ..." << std::flush;
    const int code = run_to_log(args, probe_log.string());
    const std::string text = read_text(probe_log.string());
    const double ms = code == 0 ? logged_ms_per_frame(text) : -1.0;
    if (ms > 0.0) {
      const double share_left = st.whole_cost_seconds > 0.0 ? st.cost_seconds / st.whole_cost_seconds : 1.0;
      st.whole_cost_seconds = 1e-3 * ms * double(st.steps) * double(plan.threads);
      st.cost_seconds = share_left * st.whole_cost_seconds;
      st.timed = true;
      ++timed;
      log << " " << ms << " ms/frame\n";
    } else {
      log << " failed (exit " << code << ": " << last_line_of(probe_log.string())
          << "); the cost model's estimate is kept\n";
    }
    for (const auto& f : {out, fs::path(out.string() + ".checkpoint"), fs::path(out.string() + ".part")})
      fs::remove(f, ec);
  }
  fs::remove_all(scratch, ec);
  return timed;
}

}  // namespace fldsim
