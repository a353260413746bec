#include "run/StopRequest.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>

namespace fldsim {

namespace {

volatile std::sig_atomic_t received = 0;

// The parent-death signal of a sweep point (below). It arrives when the sweep process dies, which
// under mpirun often follows the SIGTERM the sweep passed on: it must not count as "asked twice".
constexpr int kParentDied = SIGHUP;

extern "C" void on_stop_signal(int sig) {
  if (received != 0) {
    if (sig == kParentDied) return;  // already stopping: finish the checkpoint
    // Asked twice: stop now.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  received = sig == kParentDied ? SIGTERM : sig;
}

}  // namespace

void StopRequest::install() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // an interrupted write or read resumes; the flag is read between steps
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // A point of `fldsim sweep` (sweep/PointProcess.cpp) stops as on SIGTERM, checkpointed, when
  // the sweep process that started it dies (an MPI rank killed, a node lost): otherwise it would
  // run on as an orphan and write its files while the next invocation resumes the same point.
  if (const char* parent = std::getenv(kStopWithParent)) {
    sigaction(kParentDied, &action, nullptr);
    ::prctl(PR_SET_PDEATHSIG, kParentDied);
    if (::getppid() != static_cast<pid_t>(std::atol(parent))) received = SIGTERM;  // already gone
  }
}

int StopRequest::signal() {
  return received;
}

const char* StopRequest::signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

void StopRequest::reset() {
  received = 0;
}

}  // namespace fldsim
