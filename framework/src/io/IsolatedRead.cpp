#include "io/IsolatedRead.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <thread>

#include "fldsim/error.hpp"

namespace fldsim::io {

namespace {

// Exit status of a child whose `read` returned or threw: any other status means it crashed.
constexpr int kReadFinished = 0;

[[noreturn]] void child(const std::function<void()>& read) {
  // Neither a sanitizer report nor HDF5's diagnostics are for the user: the parent says it once.
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
  }
  try {
    read();
  } catch (...) {
  }
  // _exit, not exit: the parent's atexit handlers (HDF5's H5close among them) must not run
  // here and flush or close the parent's open files.
  ::_exit(kReadFinished);
}

}  // namespace

void probe_read_in_child(const std::string& path, const std::string& what, const std::function<void()>& read,
                         double limit_seconds) {
  const pid_t pid = ::fork();
  if (pid < 0) return;  // no process to spare: read in-process as before (best effort)
  if (pid == 0) child(read);

  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(limit_seconds);
  int status = 0;
  for (auto pause = std::chrono::microseconds(200);;
       pause = std::min(pause * 2, std::chrono::microseconds(20000))) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return;  // the child was reaped elsewhere: nothing to judge
    if (Clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw Error(path + ": " + what + " is damaged: reading it did not finish in " +
                  std::to_string(static_cast<int>(limit_seconds)) + " s; the file is not used");
    }
    std::this_thread::sleep_for(pause);
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == kReadFinished) return;
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGINT || signal == SIGTERM || signal == SIGHUP)
      throw Error(path + ": reading the " + what + " was interrupted (" + ::strsignal(signal) + ")");
    throw Error(path + ": " + what + " is damaged: reading it crashed the HDF5 library (" +
                ::strsignal(signal) + "); the file is not used");
  }
  throw Error(path + ": " + what + " is damaged: reading it failed inside the HDF5 library (exit status " +
              std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "); the file is not used");
}

}  // namespace fldsim::io
