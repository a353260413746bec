// An experiment file, read and validated: the core's own keys against the core schema, and
// each plugin block against the schema its plugin declares. All errors are collected and
// reported together (ConfigError, exit code 2) as `file:line:col: key.path: message`.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fldsim/params.hpp"
#include "plugins/PluginRegistry.hpp"

namespace fldsim {

struct PluginBlock {
  std::string kind, name;
  Params params;
  std::string path;  // "hydro", "forces[0]", ...
};

struct ObserverBlock {
  PluginBlock plugin;
  std::int64_t every = 1;
  double start = 0.0;  // in the user's time unit
};

struct Experiment {
  std::string file;                    // as given
  std::string source_text;             // the file byte for byte, for /parameters
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
  std::string resolved_yaml;           // after --set overrides, for /parameters
  std::vector<std::string> plugin_paths;

  PluginBlock shape;
  std::int64_t count = 0;
  double volume_fraction = 0.0;
  double box_edge = 0.0;  // 0 = from count and volume_fraction

  std::string init_method;  // monte_carlo | explicit | file
  std::int64_t init_seed = 1;
  std::int64_t init_sweeps = 0;
  std::vector<std::vector<double>> init_positions, init_orientations;
  std::string init_file;

  double peclet = 0.0;
  bool brownian = true;

  PluginBlock hydro;
  std::vector<PluginBlock> forces;
  std::vector<ObserverBlock> observers;

  double dt = 0.0, duration = 0.0;  // in time_unit; dt is the frame (dt_max with dt: auto)
  bool dt_auto = false;             // run.dt: auto (adaptive steps)
  double dt_max = 0.0, dt_min = 0.0, tolerance = 1e-3, reject_at = 10.0, max_overlap = 0.1;
  double displacement = 0.0;  // run.displacement, a (0: no bound)
  double gap_step = 0.0;      // run.gap_step, a (0: no bound)
  double gap_range = 0.01;    // run.gap_range, a
  bool error_control = true;  // dt: auto with run.tolerance (or without run.displacement)
  int refine = 0;             // every frame in at least 2^refine steps
  std::string time_unit;      // paper | diffusive | strain
  std::int64_t seed = 42;
  std::string integrator;                             // auto | euler_maruyama | rk3
  std::string drift;                                  // midpoint | none
  std::string brownian_stress = "random_difference";  // random_difference | midpoint
  double brownian_stress_delta = 1e-4;                // a
  double brownian_stress_tolerance = 1e-8;            // the probe's solve tolerance
  double skin = 0.3;                                  // a: the fixed skin, or where skin: auto starts
  bool skin_auto = true;                              // run.skin: auto (CellNeighbourList::adapt_skin)
  double checkpoint_every = 0.0;                      // in time_unit; 0 = only at the end
  std::int64_t threads = 0;
  std::string progress = "auto";  // auto | on | off: a default `progress` observer (RunExperiment)

  std::string output;
  std::string output_location;  // file:line:col of `output`

  // The validated core sections, for the checks made after reading (RunCheck): each value
  // knows where it came from (Params::origin).
  Params system_params, init_params, flow_params, run_params;
};

// `overrides` are "dotted.key=value" strings applied before validation (sweeps).
// Throws ConfigError with every problem found.
Experiment read_experiment(const std::string& file, const std::vector<std::string>& overrides,
                           std::unique_ptr<PluginRegistry>& registry);

// The same with plugins from an existing registry (the file's plugins.paths are not searched).
Experiment read_experiment(const std::string& file, const std::vector<std::string>& overrides,
                           const PluginRegistry& registry);

// The resolved experiment stored in a checkpoint or result file (`label` names it in
// messages), read with the plugins of `registry`. Throws ConfigError.
Experiment read_stored_experiment(const std::string& yaml_text, const std::string& label,
                                  const PluginRegistry& registry);

// Human-readable description of the core keys, for `fldsim run --help` and the README.
std::string core_keys_help();

}  // namespace fldsim
