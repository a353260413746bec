// Every point of a sweep checked before anything runs (`fldsim sweep`): its experiment read and
// validated exactly as `fldsim check` would, its state on disk (finished, to resume, changed,
// to run) and its estimated cost.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "sweep/SweepPlan.hpp"

namespace fldsim {

enum class PointStatus {
  Run,      // no result and no checkpoint: run from the start
  Resume,   // a checkpoint of this same experiment: --resume it
  Done,     // a result file of this same experiment: skipped
  Changed,  // a result or checkpoint of a different experiment (the base or the sweep changed)
};

const char* to_string(PointStatus s);

struct PointState {
  std::size_t index = 0;  // into SweepPlan::points
  PointStatus status = PointStatus::Run;
  std::string output, checkpoint, log;
  std::string why_changed;          // for Changed: what differs, and in which file
  bool interrupted_output = false;  // Resume of a run stopped by a signal: its partial result is kept aside
  std::int64_t steps = 0, nodes = 0;
  std::string hydro;
  std::vector<std::int64_t> observer_every;  // each observer's sampling period, in frames
  double frame = 0.0;               // the frame (dt, or dt_max with dt: auto), in the run's time unit
  double cost_seconds = 0.0;        // estimated CPU seconds still to run (cost model, docs/sweep.md)
  double whole_cost_seconds = 0.0;  // the same for the whole point (differs for Resume)
  bool adaptive = false;            // dt: auto: the model counts one step per frame, a lower bound
  bool timed = false;               // cost_seconds from timed frames of the point (--timed; StepProbe.hpp)
};

// Validates every point (all problems of all points at once: ConfigError with one line each,
// naming the sweep file's line and axis for values that came from it) and reads its state.
std::vector<PointState> check_sweep_points(const SweepPlan& plan);

// The cost model: CPU seconds for `steps` frames of `nodes` spheres with this hydro plugin and
// `threads` threads (docs/sweep.md gives its calibration).
double estimated_cpu_seconds(const std::string& hydro, std::int64_t steps, std::int64_t nodes, bool brownian);

// The share of a resumed point's frames still to run, for its estimate: 1 - done / frames, done
// the checkpoint's step (fixed dt: one step per frame; check_run reads it). 1 for dt: auto (steps
// are not frames).
double share_left(std::int64_t frames, std::int64_t done, bool adaptive);

// "12 s", "3.4 min", "2.1 h".
std::string format_duration(double seconds);

// The `--dry-run` listing: one row per point with its status and cost, and the totals.
void print_sweep_listing(const SweepPlan& plan, const std::vector<PointState>& points, std::ostream& out);

// Points to run (Run, Resume and, with rerun_changed, Changed), longest first.
std::vector<std::size_t> run_order(const std::vector<PointState>& points, bool rerun_changed);

}  // namespace fldsim
