// Formats run progress: step/total, percentage, simulated time, speed over a moving window,
// ETA, minimum gap and CG iterations. Live mode rewrites one line with '\r' (a terminal);
// otherwise a plain line every `interval` seconds (a log file). Wall-clock times are passed
// in, so the reporter is deterministic and testable.
//
// The speed is measured over the last kWindow display periods, not the whole run (which hides
// slow-downs) nor one step (one slow step gives absurd ETAs: HOOMD-blue issue #227).
#pragma once

#include <array>
#include <cstdint>
#include <ostream>
#include <string>

namespace fldsim {

struct ProgressOptions {
  double interval = 10.0;           // seconds between log lines (plain mode)
  double live_refresh = 1.0;        // seconds between rewrites of the live line
  bool live = false;                // '\r' line on a terminal
  double min_gap_warning = 1e-5;    // a: warn once when the minimum gap falls below
  int cg_iterations_warning = 200;  // warn once when one solve needs more CG iterations
};

class ProgressReporter {
 public:
  static constexpr int kWindow = 5;  // display periods in the speed window

  ProgressReporter(ProgressOptions options, std::ostream& out) : options_(options), out_(out) {}

  // `time_unit`/`time_scale`: simulated time is printed as t / time_scale in time_unit.
  void start(std::int64_t step, std::int64_t total_steps, double wall, const std::string& time_unit,
             double time_scale);
  void update(std::int64_t step, double time, double min_gap, int cg_iterations, double wall);
  void finish(double wall);

  // Steps per second over the moving window as of the last display (0 before the first).
  double window_rate() const { return rate_; }
  // Seconds to the last step at window_rate() (negative when unknown).
  double eta() const { return eta_; }
  int warnings() const { return warnings_; }

 private:
  struct Mark {
    double wall;
    std::int64_t step;
  };
  void display(std::int64_t step, double time, double min_gap, int cg_iterations, double wall);
  void warn(const char* text);

  ProgressOptions options_;
  std::ostream& out_;
  std::string time_unit_;
  double time_scale_ = 1.0;
  std::int64_t first_step_ = 0, total_steps_ = 0, last_step_ = 0;
  double start_wall_ = 0.0, last_display_ = 0.0;
  std::array<Mark, kWindow> marks_{};  // ring of (wall, step) at the last kWindow displays
  int mark_count_ = 0, mark_next_ = 0;
  double rate_ = 0.0, eta_ = -1.0;
  bool line_open_ = false;  // a live line without its newline is on screen
  bool gap_warned_ = false, cg_warned_ = false;
  int warnings_ = 0;
};

}  // namespace fldsim
