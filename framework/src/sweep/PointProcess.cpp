#include "sweep/PointProcess.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "fldsim/error.hpp"
#include "run/StopRequest.hpp"

extern char** environ;

namespace fldsim {
namespace {

namespace fs = std::filesystem;

// Renames `path` to `path.SUFFIX` (or `.SUFFIX.2`, ...): an old file is kept, never replaced.
void keep_aside(const std::string& path, const std::string& suffix) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  std::string target = path + "." + suffix;
  for (int n = 2; fs::exists(target, ec); ++n) target = path + "." + suffix + "." + std::to_string(n);
  fs::rename(path, target, ec);
  if (ec) throw Error(path + ": cannot move it aside to " + target + ": " + ec.message());
}

}  // namespace

std::string last_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

double sweep_clock() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

bool interrupted_exit(int code) {
  return code == 128 + SIGINT || code == 128 + SIGTERM;
}

PointProcess::PointProcess(const SweepPlan& plan, const PointState& state, const std::string& program)
    : plan_(plan), state_(state), program_(program) {
  result_.index = state.index;
}

void PointProcess::start() {
  std::vector<std::string> args = {program_, "run", plan_.base, "-o", state_.output};
  if (state_.status == PointStatus::Changed) {
    keep_aside(state_.output, "superseded");
    keep_aside(state_.checkpoint, "superseded");
  } else if (state_.status == PointStatus::Resume) {
    if (state_.interrupted_output) keep_aside(state_.output, "interrupted");
    args.insert(args.end(), {"--resume", state_.checkpoint});
  }
  for (const auto& o : plan_.points[state_.index].overrides()) args.insert(args.end(), {"--set", o});

  std::error_code ec;
  fs::create_directories(fs::path(state_.log).parent_path(), ec);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, state_.log.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                   0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  {
    std::ofstream log(state_.log, std::ios::app);
    log << "== fldsim sweep: point " << plan_.points[state_.index].label << " ("
        << plan_.points[state_.index].describe() << ")\n==";
    for (const auto& a : args) log << " " << a;
    log << "\n";
  }
  // The point stops, checkpointed, if this process dies (run/StopRequest.hpp; the signal follows
  // the spawning thread, and the sweep spawns from its only thread).
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, kStopWithParent, std::strlen(kStopWithParent)) != 0) env_text.emplace_back(*e);
  env_text.push_back(std::string(kStopWithParent) + "=" + std::to_string(::getpid()));
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  started_ = sweep_clock();
  // Its own process group: mpirun stops a job by signalling each rank's process group, SIGTERM
  // and about a second later SIGKILL, which would kill the point mid-checkpoint under load (seen:
  // Sweep.ARankThatDies... failed 2 of 4 times on a loaded machine). The point is stopped
  // gracefully instead, by the rank passing the signal on (SweepCommand) or by its parent's death.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int rc = posix_spawn(&pid_, program_.c_str(), &files, &attributes, argv.data(), envp.data());
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0)
    throw Error("cannot start " + program_ + " for point " + plan_.points[state_.index].label + ": " +
                std::strerror(rc));
}

void PointProcess::finish(int status) {
  result_.seconds = sweep_clock() - started_;
  result_.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result_.last_line = last_line_of(state_.log);
  pid_ = -1;
}

bool PointProcess::poll() {
  if (pid_ < 0) return true;
  int status = 0;
  const pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == pid_) finish(status);
  return pid_ < 0;
}

void PointProcess::wait() {
  while (pid_ >= 0) {
    int status = 0;
    const pid_t r = waitpid(pid_, &status, 0);
    if (r == pid_)
      finish(status);
    else if (r < 0 && errno != EINTR) {
      result_.exit_code = 1;
      result_.last_line = std::string("waitpid: ") + std::strerror(errno);
      pid_ = -1;
    }
  }
}

void PointProcess::signal(int sig) const {
  if (pid_ > 0) ::kill(pid_, sig);
}

}  // namespace fldsim
