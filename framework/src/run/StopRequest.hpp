// SIGINT (Ctrl-C) and SIGTERM ask a run to stop at the end of the current step: the run then
// writes its checkpoint and a readable result file holding everything observed so far, says
// so, and exits with 128 + the signal number (130, 143). A second signal ends the process at
// once, the operating system's way (the last periodic checkpoint is kept). With
// FLDSIM_STOP_WITH_PARENT=<pid> set, the death of that parent process counts as a SIGTERM.
#pragma once

namespace fldsim {

// Environment variable: the pid of the process whose death stops this run as SIGTERM does.
inline constexpr const char* kStopWithParent = "FLDSIM_STOP_WITH_PARENT";

class StopRequest {
 public:
  // Installs the handlers (idempotent).
  static void install();
  // The signal received, 0 if none.
  static int signal();
  static const char* signal_name(int sig);
  // Forget a received signal (tests).
  static void reset();
};

}  // namespace fldsim
