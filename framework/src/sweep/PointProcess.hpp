// One sweep point run as its own `fldsim run` process, its output to the point's log file.
// A separate process per point means a point that crashes or is killed loses only itself, the
// scheduler (local or an MPI rank) goes on, and the next `fldsim sweep` resumes that point
// from its checkpoint.
#pragma once

#include <sys/types.h>

#include <string>

#include "sweep/SweepPoints.hpp"

namespace fldsim {

struct PointResult {
  std::size_t index = 0;
  int exit_code = 0;      // the run's exit code; 128 + signal if it was killed
  double seconds = 0.0;   // wall time
  std::string last_line;  // the last line of the point's log (the reason, when it failed)
};

class PointProcess {
 public:
  // `program` is the fldsim executable (normally /proc/self/exe).
  PointProcess(const SweepPlan& plan, const PointState& state, const std::string& program);
  PointProcess(const PointProcess&) = delete;
  PointProcess& operator=(const PointProcess&) = delete;

  // Starts the run (a changed point's old result and checkpoint are first renamed to
  // *.superseded[.N], never deleted). Throws fldsim::Error if it cannot be started.
  void start();
  // True once the process has ended; then result() is final. Does not block.
  bool poll();
  // Blocks until the process ends.
  void wait();
  // Forwards a signal (SIGINT or SIGTERM: the run checkpoints and stops).
  void signal(int sig) const;
  const PointResult& result() const { return result_; }
  std::size_t index() const { return state_.index; }

 private:
  void finish(int status);
  const SweepPlan& plan_;
  const PointState& state_;
  std::string program_;
  pid_t pid_ = -1;
  double started_ = 0.0;
  PointResult result_;
};

// The last non-empty line of a text file ("" if it cannot be read): a run's reason, when it failed.
std::string last_line_of(const std::string& path);

// Wall-clock seconds (steady clock).
double sweep_clock();

// The exit code a run gives when it stopped on SIGINT/SIGTERM after writing its checkpoint.
bool interrupted_exit(int code);

}  // namespace fldsim
