// A sweep file (`fldsim sweep`, docs/sweep.md): a base experiment and the axes over which to
// vary it, expanded into points. Each point is the base experiment with a list of dotted-key
// overrides (the same mechanism as `fldsim run --set`), and every override remembers where in
// the sweep file its value came from, so a point's errors name the sweep file, line and axis.
//
//   base: experiment.yaml            # relative to the sweep file
//   output_dir: results/study        # one result file per point (default: the sweep file's stem)
//   threads: 1                       # run.threads of every point
//   axes:                            # product over the entries, the first varying slowest
//     - flow.peclet: [0.1, 1, 10]
//     - zip:                         # values taken together
//         system.volume_fraction: [0.3, 0.5]
//         run.dt: [1.0e-3, 1.0e-4]
//   repeats: 2                       # run.seed and system.init.seed + 0, 1, ...
//   overrides:                       # per-point: where every `when` key matches, `set` applies
//     - when: {flow.peclet: [0.1, 1]}
//       set: {run.dt: 1.0e-4}
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace fldsim {

struct SweepValue {
  std::string key;     // dotted path, e.g. flow.peclet
  std::string yaml;    // the value as flow-style YAML text
  std::string origin;  // "file:line:col" of the value in the sweep file
  std::string role;    // "axis flow.peclet", "repeats", "overrides[0].set", "threads"
};

struct SweepPoint {
  std::string label;                 // file stem of the point's result, from its axis values
  std::vector<SweepValue> axis;      // the point's axis values (and its repeat), in axis order
  std::vector<SweepValue> settings;  // every override applied, in order (axis, repeat, overrides)
  int repeat = 0;

  // "key=value" strings for read_experiment / `fldsim run --set`.
  std::vector<std::string> overrides() const;
  // The axis values as "key = value, ..." for messages.
  std::string describe() const;
};

struct SweepPlan {
  std::string file;        // the sweep file
  std::string base;        // the base experiment, resolved against the sweep file's directory
  std::string output_dir;  // resolved the same way
  int threads = 1;         // run.threads of each point
  int repeats = 1;
  std::vector<std::string> axis_keys;  // every axis key, in order (the study table's columns)
  std::vector<SweepPoint> points;

  std::string output_of(const SweepPoint& p) const;  // output_dir/label.h5
};

struct BaseSeeds {
  long long run = 42, init = 1;  // the base experiment's run.seed and system.init.seed
};

// Reads and expands a sweep file. `base_seeds` reads the seeds of the base experiment (called
// once, only when `repeats` > 1). Throws ConfigError naming file:line:col and key for every
// problem in the sweep file itself (the points' experiments are checked by the caller).
SweepPlan read_sweep_plan(const std::string& file,
                          const std::function<BaseSeeds(const std::string& base)>& base_seeds);

}  // namespace fldsim
