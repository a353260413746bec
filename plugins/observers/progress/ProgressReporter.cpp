#include "ProgressReporter.hpp"

#include <cmath>
#include <cstdio>

namespace fldsim {

namespace {
// "2h05m", "3m12s", "42s"
void format_duration(double seconds, char* buffer, std::size_t size) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) {
    std::snprintf(buffer, size, "?");
    return;
  }
  const long s = std::lround(seconds);
  if (s >= 3600)
    std::snprintf(buffer, size, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  else if (s >= 60)
    std::snprintf(buffer, size, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buffer, size, "%lds", s);
}
}  // namespace

void ProgressReporter::start(std::int64_t step, std::int64_t total_steps, double wall,
                             const std::string& time_unit, double time_scale) {
  first_step_ = last_step_ = step;
  total_steps_ = total_steps;
  start_wall_ = last_display_ = wall;
  time_unit_ = time_unit;
  time_scale_ = time_scale > 0.0 ? time_scale : 1.0;
  marks_[0] = {wall, step};
  mark_count_ = 1;
  mark_next_ = 1;
}

void ProgressReporter::warn(const char* text) {
  if (line_open_) out_ << '\n';
  line_open_ = false;
  out_ << "warning: " << text << '\n';
  ++warnings_;
}

void ProgressReporter::update(std::int64_t step, double time, double min_gap, int cg_iterations,
                              double wall) {
  last_step_ = step;
  char text[256];
  if (!gap_warned_ && min_gap < options_.min_gap_warning) {
    gap_warned_ = true;
    if (min_gap < 0.0)
      std::snprintf(text, sizeof text,
                    "minimum gap %.3g a at step %lld: bodies overlap by %.3g a; check the repulsion, or "
                    "lower run.max_overlap (the step guard) or the time step",
                    min_gap, static_cast<long long>(step), -min_gap);
    else
      std::snprintf(text, sizeof text,
                    "minimum gap %.3g a < %.3g a at step %lld: bodies nearly touch; reduce dt or check the "
                    "repulsion",
                    min_gap, options_.min_gap_warning, static_cast<long long>(step));
    warn(text);
  }
  if (!cg_warned_ && cg_iterations > options_.cg_iterations_warning) {
    cg_warned_ = true;
    std::snprintf(
        text, sizeof text,
        "CG needed %d iterations (> %d) at step %lld: the resistance is ill-conditioned (near contacts?)",
        cg_iterations, options_.cg_iterations_warning, static_cast<long long>(step));
    warn(text);
  }
  const double period = options_.live ? options_.live_refresh : options_.interval;
  if (wall - last_display_ >= period || step >= total_steps_)
    display(step, time, min_gap, cg_iterations, wall);
}

void ProgressReporter::display(std::int64_t step, double time, double min_gap, int cg_iterations,
                               double wall) {
  // Oldest mark in the ring: the start of the moving window.
  const Mark& oldest = marks_[mark_count_ < static_cast<int>(marks_.size()) ? 0 : mark_next_];
  const double span = wall - oldest.wall;
  rate_ = span > 0.0 ? static_cast<double>(step - oldest.step) / span : 0.0;
  eta_ = rate_ > 0.0 ? static_cast<double>(total_steps_ - step) / rate_ : -1.0;
  marks_[mark_next_] = {wall, step};
  mark_next_ = (mark_next_ + 1) % static_cast<int>(marks_.size());
  if (mark_count_ < static_cast<int>(marks_.size())) ++mark_count_;
  last_display_ = wall;

  char eta[32], gap[32], line[256];
  format_duration(eta_, eta, sizeof eta);
  if (std::isfinite(min_gap))
    std::snprintf(gap, sizeof gap, "%.2e a", min_gap);
  else
    std::snprintf(gap, sizeof gap, "none");
  const double percent =
      total_steps_ > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(total_steps_) : 0;
  std::snprintf(line, sizeof line,
                "step %lld/%lld (%.1f%%)  t = %.4g %s  %.4g steps/s  ETA %s  min gap %s  CG %d",
                static_cast<long long>(step), static_cast<long long>(total_steps_), percent,
                time / time_scale_, time_unit_.c_str(), rate_, eta, gap, cg_iterations);
  if (options_.live) {
    // Pad so a shorter line fully covers the previous one.
    out_ << '\r' << line << "   " << std::flush;
    line_open_ = true;
  } else {
    out_ << line << '\n';
  }
}

void ProgressReporter::finish(double wall) {
  if (line_open_) out_ << '\n';
  line_open_ = false;
  const double elapsed = wall - start_wall_;
  const std::int64_t steps = last_step_ - first_step_;
  char total[32], line[160];
  format_duration(elapsed, total, sizeof total);
  std::snprintf(line, sizeof line, "progress: %lld steps in %s wall time (%.3f s), mean %.4g steps/s",
                static_cast<long long>(steps), total, elapsed,
                elapsed > 0.0 ? static_cast<double>(steps) / elapsed : 0.0);
  out_ << line << '\n' << std::flush;
}

}  // namespace fldsim
