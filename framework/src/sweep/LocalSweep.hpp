// Runs a sweep's points on this machine: up to `jobs` points at once, each its own `fldsim run`
// process, longest first; the next point starts as soon as one ends. SIGINT/SIGTERM are passed
// on to the running points (they checkpoint and stop) and no new point starts; the next
// `fldsim sweep` resumes them.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sweep/PointProcess.hpp"

namespace fldsim {

struct SweepRunOutcome {
  std::vector<PointResult> results;  // in the order the points ended
  bool interrupted = false;          // stopped by a signal before every point ran
};

SweepRunOutcome run_sweep_locally(const SweepPlan& plan, const std::vector<PointState>& points,
                                  const std::vector<std::size_t>& order, int jobs, const std::string& program,
                                  std::ostream& log);

// One line for a point that ended: "[3/12] peclet-10: done in 4.2 min" or its failure.
void report_point(const SweepPlan& plan, const PointResult& r, std::size_t finished, std::size_t total,
                  std::ostream& log);

// Installs SIGINT/SIGTERM handlers that record the signal; returns the signal received, 0 if none.
void install_sweep_signal_handlers();
int sweep_signal();

}  // namespace fldsim
