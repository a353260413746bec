#include "CorpusRunner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace corpus {

namespace fs = std::filesystem;

namespace {

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    names.insert(fs::relative(it->path(), dir).string());
  return names;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

}  // namespace

Outcome run_case(const Case& c, const fs::path& dir, double timeout_s) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& [name, text] : c.files) {
    fs::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << text;
  }
  if (c.setup) c.setup(dir);
  const std::set<std::string> before = listing(dir);

  Outcome o;
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0) return o;
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    ::dup2(out_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    for (const auto& [k, v] : c.env) ::setenv(k.c_str(), v.c_str(), 1);
    std::vector<std::string> args{FLDSIM_EXE};
    args.insert(args.end(), c.args.begin(), c.args.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(FLDSIM_EXE, argv.data());
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int open_fds = 2;
  while (open_fds > 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      o.timed_out = true;
      ::kill(pid, SIGKILL);
      break;
    }
    if (::poll(fds, 2, 200) <= 0) continue;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[4096];
      const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
      if (n <= 0) {
        fds[i].fd = -1;
        --open_fds;
      } else {
        (i == 0 ? o.out : o.err).append(buf, std::size_t(n));
      }
    }
  }
  ::close(out_pipe[0]);
  ::close(err_pipe[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);

  for (const auto& name : listing(dir)) {
    if (before.count(name)) continue;
    bool allowed = false;
    for (const auto& m : c.may_leave) allowed = allowed || name == m;
    if (!allowed) o.left_behind.push_back(name);
  }
  return o;
}

Verdict judge(const Case& c, const Outcome& o) {
  Verdict v;
  std::ostringstream why;
  const bool sanitizer =
      o.err.find("Sanitizer") != std::string::npos || o.err.find("runtime error:") != std::string::npos;
  const bool internal = o.err.find("internal error") != std::string::npos ||
                        o.err.find("terminate called") != std::string::npos;
  const bool odd_exit = o.exit_code != 0 && o.exit_code != 1 && o.exit_code != 2;
  v.crash = o.signal != 0 || o.timed_out || sanitizer || internal || odd_exit;
  v.leftover = !o.left_behind.empty();
  std::vector<std::string> errors;
  for (const auto& line : lines_of(o.err))
    if (line.rfind("warning: ", 0) != 0) errors.push_back(line);
  // Usage errors print the command's help after the message: only the message counts.
  if (!errors.empty() && o.err.find("\nusage:") != std::string::npos) errors.resize(1);
  bool lines_ok = errors.size() == c.lines.size();
  std::vector<bool> used(c.lines.size(), false);
  for (const auto& line : errors) {
    bool matched = false;
    for (std::size_t i = 0; i < c.lines.size() && !matched; ++i)
      if (!used[i] && std::regex_search(line, std::regex(c.lines[i]))) used[i] = matched = true;
    if (!matched) {
      lines_ok = false;
      why << "  unexpected line: " << line << "\n";
    }
  }
  v.clear = !v.crash && o.exit_code == c.exit_code && lines_ok;
  if (o.exit_code != c.exit_code)
    why << "  exit code " << o.exit_code << " (signal " << o.signal << "), expected " << c.exit_code << "\n";
  if (errors.size() != c.lines.size())
    why << "  " << errors.size() << " error lines, expected " << c.lines.size() << "\n";
  if (o.timed_out) why << "  timed out\n";
  for (const auto& f : o.left_behind) why << "  left behind: " << f << "\n";
  if (!v.clear || v.leftover) why << "  stderr:\n" << o.err << "  stdout:\n" << o.out.substr(0, 2000);
  v.why = why.str();
  return v;
}

std::string table_row(const std::string& klass, const Tally& t) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "| %-22s | %5d | %13d | %7d | %9d |", klass.c_str(), t.cases, t.clear,
                t.crashes, t.leftovers);
  return buf;
}

}  // namespace corpus
