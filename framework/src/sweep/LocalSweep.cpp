#include "sweep/LocalSweep.hpp"

#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <memory>
#include <ostream>

namespace fldsim {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int sig) {
  g_signal = sig;
}

}  // namespace

void install_sweep_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int sweep_signal() {
  return g_signal;
}

void report_point(const SweepPlan& plan, const PointResult& r, std::size_t finished, std::size_t total,
                  std::ostream& log) {
  log << "[" << finished << "/" << total << "] " << plan.points[r.index].label << ": ";
  if (r.exit_code == 0)
    log << "done in " << format_duration(r.seconds) << "\n";
  else if (interrupted_exit(r.exit_code))
    log << "stopped by a signal after " << format_duration(r.seconds) << "; its checkpoint resumes it\n";
  else
    log << "FAILED (exit " << r.exit_code << ") after " << format_duration(r.seconds) << ": " << r.last_line
        << " (log: " << (std::string(plan.output_dir) + "/" + plan.points[r.index].label + ".log") << ")\n";
  log.flush();
}

SweepRunOutcome run_sweep_locally(const SweepPlan& plan, const std::vector<PointState>& points,
                                  const std::vector<std::size_t>& order, int jobs, const std::string& program,
                                  std::ostream& log) {
  SweepRunOutcome outcome;
  std::vector<std::unique_ptr<PointProcess>> running;
  std::size_t next = 0;
  bool forwarded = false;
  while (next < order.size() || !running.empty()) {
    if (sweep_signal() && !forwarded) {
      for (const auto& p : running) p->signal(sweep_signal());
      forwarded = true;
      outcome.interrupted = next < order.size() || !running.empty();
      log << "fldsim sweep: " << (sweep_signal() == SIGINT ? "SIGINT" : "SIGTERM")
          << ": the running points checkpoint and stop; no new point starts\n";
    }
    while (!forwarded && next < order.size() && int(running.size()) < jobs) {
      auto p = std::make_unique<PointProcess>(plan, points[order[next]], program);
      log << "start " << plan.points[order[next]].label << " (" << to_string(points[order[next]].status)
          << ", est. " << format_duration(points[order[next]].cost_seconds) << ")\n";
      p->start();
      running.push_back(std::move(p));
      ++next;
    }
    for (std::size_t i = 0; i < running.size();) {
      if (running[i]->poll()) {
        outcome.results.push_back(running[i]->result());
        report_point(plan, outcome.results.back(), outcome.results.size(), order.size(), log);
        running.erase(running.begin() + std::ptrdiff_t(i));
      } else {
        ++i;
      }
    }
    if (forwarded && next < order.size() && running.empty()) break;
    usleep(20000);
  }
  return outcome;
}

}  // namespace fldsim
