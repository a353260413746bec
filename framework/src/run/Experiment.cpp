#include "run/Experiment.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "config/YamlValidation.hpp"
#include "dynamics/BrownianStressProbe.hpp"

namespace fldsim {
namespace {

// Paths are relative to where they are written: a path in the experiment file to the file's
// directory (so an experiment runs the same from any directory), one given on the command line
// (--set KEY=PATH) to the current directory, like every other command-line path.
std::string resolve_path(const std::string& path, const std::string& yaml_dir, const std::string& key,
                         const std::vector<std::string>& overrides) {
  if (path.empty() || std::filesystem::path(path).is_absolute() || yaml_dir.empty()) return path;
  for (const auto& item : overrides)
    if (item.rfind(key + "=", 0) == 0) return path;
  return (std::filesystem::path(yaml_dir) / path).lexically_normal().string();
}

const std::vector<std::string> kTopKeys = {"system", "flow",      "hydro",  "forces",
                                           "run",    "observers", "output", "plugins"};

ParamSchema system_schema() {
  ParamSchema s;
  s.integer("count", std::nullopt, "", "number of bodies N (memory is also checked against this machine)")
      .at_least(1)
      .at_most(100000000);
  s.number("volume_fraction", std::nullopt, "", "true volume fraction phi = N V_body / V_box")
      .greater(0.0)
      .less(0.74);
  s.number("box_edge", 0.0, "a", "cubic box edge; 0 = from count and volume_fraction").at_least(0.0);
  return s;
}

ParamSchema init_schema() {
  ParamSchema s;
  s.choice("method", "monte_carlo", {"monte_carlo", "explicit", "file"},
           "monte_carlo: hard-body Monte Carlo from a lattice; explicit: `positions` (and "
           "`orientations`) listed here; file: last frame of an earlier result file");
  s.integer("seed", 1, "", "seed of the Monte Carlo start").at_least(0);
  s.integer("sweeps", 0, "", "Monte Carlo sweeps; 0 = until decorrelated").at_least(0).at_most(1000000);
  s.table("positions", std::vector<std::vector<double>>{}, "a", "explicit start: one [x, y, z] per body")
      .length(3);
  s.table("orientations", std::vector<std::vector<double>>{}, "",
          "explicit start: one director [nx, ny, nz] or quaternion [w, x, y, z] per body");
  s.text("file", std::string(), "file start: an earlier result file (its last trajectory frame)");
  return s;
}

ParamSchema flow_schema() {
  ParamSchema s;
  s.number("peclet", 0.0, "", "Pe = gammadot a^2 / D0; 0 = quiescent").at_least(0.0);
  s.flag("brownian", true, "false for a non-Brownian (kT = 0) run: Pe is then irrelevant and gammadot = 1");
  return s;
}

ParamSchema run_schema() {
  ParamSchema s;
  s.number(
       "dt", std::nullopt, "time_unit",
       "time step; `auto` = adaptive steps of at most dt_max, controlled by tolerance (docs/time_steps.md)")
      .greater(0.0)
      .or_word("auto");
  s.number("dt_max", 0.0, "time_unit",
           "with dt: auto, the longest step and the frame: observers' `every` and checkpoint_every count "
           "frames of dt_max, and samples fall on multiples of it; steps are its dyadic pieces dt_max/2^k, "
           "so for Brownian averages make it a step whose bias is known (docs/time_steps.md, \"Why, "
           "measured\"); required with dt: auto")
      .at_least(0.0);
  s.number("dt_min", 0.0, "time_unit",
           "shortest step: a step that a retry would cut below it stops the run with a checkpoint; "
           "0 = the frame (dt or dt_max) / 2^24")
      .at_least(0.0);
  s.number("tolerance", 1e-4, "a",
           "with dt: auto, the largest local error of a step: the embedded estimate of the displacement "
           "error of any body's surface point (midpoint - Euler for Brownian runs, RK3 - midpoint rule for "
           "kT = 0)")
      .greater(0.0);
  s.number("displacement", 0.0, "a",
           "with dt: auto, a bound on the step's root mean square node displacement relative to the imposed "
           "flow, predicted from the past steps (a weak-error rule for Brownian FLD averages: 0.022 is "
           "measured against the exact equilibrium, docs/time_steps.md \"The displacement bound\"). Alone "
           "(no tolerance) it cuts each dt_max frame into the fewest equal steps below it and only the guard "
           "rejects; with tolerance the step is the shorter of the controller's and the longest dyadic piece "
           "of dt_max below the bound; 0 = none")
      .at_least(0.0);
  s.number(
       "gap_step", 0.0, "a",
       "with dt: auto, a bound on the root mean square change per step of the surface gap of near node "
       "pairs (gap below gap_range), the imposed flow's normal displacement of each pair added, predicted "
       "from the past steps: the repulsion's contact bias, alike at every volume fraction. 0.0048 takes "
       "4e-4 a^2/D0 at phi 0.5, which passes the exact equilibrium, and stays within 2 SE of dt 1e-4 "
       "at Pe 10 and 1000; at phi 0.3 its steps are at the edge of the lubrication taper's bias "
       "(docs/time_steps.md, "
       "\"The pair-gap bound\"); with displacement: 0.028 too, the shorter of the two bounds guards both. "
       "Used like run.displacement (alone: equal steps; with tolerance: the shorter); 0 = none")
      .at_least(0.0);
  s.number(
       "gap_range", 0.01, "a",
       "with gap_step, the pairs it measures: node pairs of different bodies whose surface gap at the start "
       "or the end of the step is below gap_range")
      .greater(0.0);
  s.number("reject_at", 0.0, "",
           "with dt: auto, a step whose error estimate exceeds reject_at x tolerance is rejected and retried "
           "shorter on the same Brownian path; the controller keeps the typical error near the tolerance. "
           "0 = automatic: 10 for Brownian runs (rejecting at every excess biases the thermal drift of "
           "configuration-dependent mobilities such as FLD's: docs/time_steps.md), 1 for kT = 0")
      .at_least(0.0);
  s.integer("refine", 0, "",
            "take every frame in at least 2^refine steps on the frame's own Brownian path (same seed: the "
            "same noise as the unrefined run, resolved finer): strong-convergence references")
      .at_least(0)
      .at_most(20);
  s.number(
       "max_overlap", 0.1, "a",
       "stability guard, in every mode: a step that leaves two nodes overlapping by more than this (and "
       "deepens the deepest overlap by more than a tenth of it) is rejected and retried on a shorter step")
      .greater(0.0);
  s.number("duration", std::nullopt, "time_unit", "length of the run").greater(0.0);
  s.choice("time_unit", "paper", {"paper", "diffusive", "strain"},
           "unit of dt, duration, observer start and checkpoint_every: diffusive = a^2/D0, strain = "
           "1/gammadot, paper = diffusive for Pe < 1 and strain for Pe >= 1 (Kumar & Higdon)");
  s.integer("seed", 42, "", "seed of the Brownian noise (counter-based: same seed, same run)").at_least(0);
  s.choice(
      "integrator", "auto", {"auto", "euler_maruyama", "rk3", "leimkuhler_matthews"},
      "auto = Euler-Maruyama (midpoint drift) for Brownian runs (Leimkuhler-Matthews at fixed steps "
      "with free_draining and bodies without translation-rotation coupling, run.drift not given), "
      "third-order Runge-Kutta for kT = 0; "
      "rk3 with Brownian motion = the paper's scheme (Brownian force frozen over the three stages, "
      "which gives the thermal drift; fixed steps only); leimkuhler_matthews = Euler-Maruyama with "
      "the mean of this and the next step's noise, equilibrium exact to O(dt^2) where the mobility is "
      "constant (free_draining with spheres; also with homonuclear dicolloids and fused dumbbells; fixed "
      "steps, Brownian runs; docs/time_steps.md)");
  s.choice(
      "drift", "midpoint", {"midpoint", "none"},
      "thermal drift kT div M: midpoint step with frozen noise, or none (wrong equilibrium; for comparison)");
  s.choice("brownian_stress", "random_difference", {"random_difference", "midpoint"},
           "estimate of the Brownian stress kT div(R_SU R_FU^-1) on the steps a stress observer samples: "
           "random_difference = two extra solves at x +- (delta/2) W, W normal (independent of dt; any "
           "integrator), midpoint = the change of the stresslets over the midpoint stage (no extra "
           "solves; biased by O(dt), about -2 % in the contact pressure at dt 2.5e-4: "
           "docs/equilibrium-oracle.md)");
  s.number("brownian_stress_delta", BrownianStressProbe::kDefaultDelta, "a",
           "with brownian_stress: random_difference, the probe's displacement scale delta (bias O(delta^2 / "
           "gap^2) for pairs at that gap; the solve error adds tolerance / delta to each sample's noise)")
      .greater(0.0)
      .at_most(0.01);
  s.number("brownian_stress_tolerance", BrownianStressProbe::kDefaultTolerance, "",
           "with brownian_stress: random_difference, the relative residual of the probe's solves (sets the "
           "hydro model's `tolerance` for its own copy of the model)")
      .greater(0.0)
      .less(1e-3);
  s.number("skin", 0.3, "a",
           "neighbour-list skin: the list is rebuilt when the two largest node displacements (less the "
           "affine shear), plus the strain times the pair range, exceed it; `auto` (the default) starts "
           "at 0.3 a and rescales it at every rebuild so that a list lasts about 60 updates (20 "
           "Euler-Maruyama steps), between 0.3 and 2 a. Results do not depend on it (bench/README.md)")
      .greater(0.0)
      .or_word("auto")
      .default_value = std::string("auto");
  s.number("checkpoint_every", 0.0, "time_unit", "write a checkpoint this often (0 = only at the end)")
      .at_least(0.0);
  s.choice("progress", "auto", {"auto", "on", "off"},
           "progress lines on stderr (the `progress` observer with its defaults): auto = on for runs of "
           "1000 steps (with dt: auto, frames of dt_max) or more; off also by -q; an experiment listing "
           "`progress` itself uses that");
  s.integer("threads", 0, "",
            "OpenMP threads; 0 = automatic: OMP_NUM_THREADS if set, else the idle usable cores, at most one "
            "per 2000 bodies, kept after the first 13 steps only if measurably faster than one thread "
            "(runs of 200 steps or more)")
      .at_least(0)
      .at_most(1024);
  return s;
}

// "observers[0].bins" and "observers.0.bins" name the same key.
std::vector<std::string> split_key_path(const std::string& path) {
  std::vector<std::string> keys;
  std::string current;
  for (char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      if (!current.empty()) keys.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) keys.push_back(current);
  return keys;
}

// Applies one --set to the document; a problem goes to `errors`, labelled with the option.
void apply_override(YAML::Node root, const std::string& item, ConfigErrors& errors) {
  const std::string label = "--set " + item;
  const auto eq = item.find('=');
  const std::string path = eq == std::string::npos ? "" : item.substr(0, eq);
  const std::vector<std::string> keys = split_key_path(path);
  if (eq == std::string::npos || keys.empty() || path.find_first_of(" \t") != std::string::npos ||
      path.find("..") != std::string::npos) {
    errors.add(
        label, "",
        "expected KEY=VALUE with a dotted key, e.g. --set run.duration=10 or --set observers[0].every=5");
    return;
  }
  YAML::Node value;
  try {
    value = YAML::Load(item.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    errors.add(label, "", "the value is not valid YAML: " + e.msg);
    return;
  }
  if (!root.IsMap()) return;  // reported with the file
  std::string walked;
  // Walk with reset() copies: yaml-cpp nodes are handles, assignment would overwrite.
  YAML::Node cur;
  cur.reset(root);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string& key = keys[i];
    const bool last = i + 1 == keys.size();
    YAML::Node next;
    if (cur.IsSequence()) {
      // A list (observers, forces) is addressed by its index: observers[2].every=10.
      const bool digits =
          !key.empty() && key.size() < 10 && key.find_first_not_of("0123456789") == std::string::npos;
      const std::size_t size = cur.size();
      if (!digits || std::stoul(key) >= size) {
        const std::string entries = std::to_string(size) + (size == 1 ? " entry" : " entries");
        errors.add(label, walked,
                   !digits ? "is a list: expected an index 0.." + std::to_string(size ? size - 1 : 0) +
                                 ", got '" + key + "'"
                           : "has " + entries + ": index " + key + " is out of range");
        return;
      }
      if (last) {
        cur[std::stoul(key)] = value;
        errors.add_override(YAML::Node(), value, label);
        return;
      }
      next.reset(cur[std::stoul(key)]);
    } else if (cur.IsMap() || cur.IsNull()) {
      if (last) {
        cur[key] = value;
        for (const auto& kv : cur)
          if (kv.first.IsScalar() && kv.first.Scalar() == key)
            errors.add_override(kv.first, kv.second, label);
        return;
      }
      if (!cur[key]) {
        // A section the file does not have: made here, so its keys are reported as the option.
        cur[key] = YAML::Node(YAML::NodeType::Map);
        for (const auto& kv : cur)
          if (kv.first.IsScalar() && kv.first.Scalar() == key)
            errors.add_override(kv.first, kv.second, label);
      }
      next.reset(cur[key]);
    } else {
      errors.add(label, walked,
                 "is a value (" + describe_yaml_value(cur) + "), not a section: '" + key +
                     "' cannot be set inside it");
      return;
    }
    walked += (walked.empty() ? "" : ".") + key;
    cur.reset(next);
  }
}

// Validate a `{plugin: name, ...}` block of the given kind against that plugin's schema.
bool read_plugin_block(const YAML::Node& node, const std::string& kind, const std::string& path,
                       const PluginRegistry& registry, ConfigErrors& errors, PluginBlock& out,
                       const ParamSchema* core_keys = nullptr) {
  out.kind = kind;
  out.path = path;
  if (!node || !node.IsMap()) {
    errors.add(node, path, "expected a map with a `plugin` key, got " + describe_yaml_value(node));
    return false;
  }
  const YAML::Node name = node["plugin"];
  if (!name || !name.IsScalar()) {
    errors.add(node, path + ".plugin", "missing required key (the name of a " + kind + " plugin)");
    return false;
  }
  out.name = name.as<std::string>();
  const PluginInfo* info = nullptr;
  try {
    info = &registry.find(kind, out.name);
  } catch (const PluginError& e) {
    errors.add(name, path + ".plugin", e.what());
    return false;
  }
  // The core's own keys in a plugin block (observer `every`, `start`) are validated with it.
  ParamSchema schema = info->schema;
  if (core_keys)
    for (const auto& spec : core_keys->specs()) schema.add(spec);
  out.params = validate_params(node, schema, path, errors, {"plugin"});
  return true;
}

}  // namespace

namespace {

// The document after loading: `registry` is made from the document's plugin paths unless
// `given` is passed (re-reading a stored experiment with the registry already in use).
Experiment parse_experiment(YAML::Node root, const std::string& file,
                            const std::vector<std::string>& overrides,
                            std::unique_ptr<PluginRegistry>& registry, const PluginRegistry* given) {
  ConfigErrors errors(file);
  if (!root.IsMap()) {
    errors.add(
        root, "(top level)",
        "expected a map of sections (system, flow, hydro, run, ...), got " + describe_yaml_value(root));
    errors.throw_if_any();
  }
  for (const auto& item : overrides) apply_override(root, item, errors);
  Experiment ex;
  ex.file = file;
  ex.overrides = overrides;
  {
    std::ifstream in(file, std::ios::binary);
    ex.source_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  {
    YAML::Emitter emit;
    emit << root;
    ex.resolved_yaml = emit.c_str();
  }
  for (const auto& kv : root) {
    if (!kv.first.IsScalar()) {
      errors.add(kv.first, "(top level)", "expected a section name, got " + describe_yaml_value(kv.first));
      continue;
    }
    const std::string key = kv.first.Scalar();
    if (std::find(kTopKeys.begin(), kTopKeys.end(), key) == kTopKeys.end()) {
      const std::string hint = did_you_mean(key, kTopKeys);
      errors.add(kv.first, key, hint.empty() ? "unknown key" : "unknown key (did you mean '" + hint + "'?)");
    }
  }

  // Plugin search path first: every plugin block depends on it.
  const YAML::Node plugins = root["plugins"];
  if (plugins) {
    const YAML::Node paths = plugins.IsMap() ? plugins["paths"] : YAML::Node();
    bool unknown = false;
    if (plugins.IsMap())
      for (const auto& kv : plugins)
        if (!kv.first.IsScalar() || kv.first.Scalar() != "paths") {
          const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
          const std::string hint = did_you_mean(key, {"paths"});
          errors.add(
              kv.first, "plugins." + key,
              hint.empty() ? "unknown key (known keys: paths)" : "unknown key (did you mean 'paths'?)");
          unknown = true;
        }
    if ((!paths || !paths.IsSequence()) && !(unknown && !paths))
      errors.add(plugins.IsMap() && paths ? paths : plugins, "plugins.paths",
                 "expected a list of directories");
    else if (paths)
      for (std::size_t i = 0; i < paths.size(); ++i) {
        if (paths[i].IsScalar())
          ex.plugin_paths.push_back(paths[i].Scalar());
        else
          errors.add(paths[i], "plugins.paths[" + std::to_string(i) + "]",
                     "expected a directory name, got " + describe_yaml_value(paths[i]));
      }
  }
  const std::string dir = std::filesystem::path(file).parent_path().string();
  if (!given) {
    registry = std::make_unique<PluginRegistry>(PluginRegistry::search_path(ex.plugin_paths, dir));
    given = registry.get();
  }
  const PluginRegistry& plugins_found = *given;

  // A section that is missing or not a map is reported once: the keys it would hold are then
  // checked against `unreported` (their defaults still fill the Params).
  ConfigErrors unreported(file);
  auto section = [&](const char* key, bool required, ConfigErrors*& sink) -> YAML::Node {
    const YAML::Node n = root[key];
    sink = &unreported;
    if (!n) {
      if (required) errors.add(root, key, "missing required section");
      if (!required) sink = &errors;
      return YAML::Node(YAML::NodeType::Map);
    }
    if (!n.IsMap()) {
      errors.add(n, key, "expected a map, got " + describe_yaml_value(n));
      return YAML::Node(YAML::NodeType::Map);
    }
    sink = &errors;
    return n;
  };

  ConfigErrors* system_errors = nullptr;
  const YAML::Node sys = section("system", true, system_errors);
  const Params sp = validate_params(sys, system_schema(), "system", *system_errors, {"shape", "init"});
  ex.system_params = sp;
  if (sp.has("count")) ex.count = sp.integer("count");
  if (sp.has("volume_fraction")) ex.volume_fraction = sp.number("volume_fraction");
  if (sp.has("box_edge")) ex.box_edge = sp.number("box_edge");
  if (!sys["shape"])
    system_errors->add(sys, "system.shape",
                       "missing required key (a map with `plugin: sphere|dicolloid|cluster`)");
  else
    read_plugin_block(sys["shape"], "shape", "system.shape", plugins_found, errors, ex.shape);
  {
    const YAML::Node init = sys["init"] ? sys["init"] : YAML::Node(YAML::NodeType::Map);
    const Params ip = validate_params(init, init_schema(), "system.init", errors);
    ex.init_params = ip;
    if (ip.has("method")) {
      ex.init_method = ip.text("method");
      ex.init_seed = ip.integer("seed");
      ex.init_sweeps = ip.integer("sweeps");
      ex.init_positions = ip.table("positions");
      ex.init_orientations = ip.table("orientations");
      ex.init_file = resolve_path(ip.text("file"), dir, "system.init.file", overrides);
      if (ex.init_method == "explicit" && ex.init_positions.empty())
        errors.add(init, "system.init.positions", "method explicit needs a list of positions");
      if (ex.init_method == "file" && ex.init_file.empty())
        errors.add(init, "system.init.file", "method file needs the path of an earlier result file");
    }
  }

  ConfigErrors* flow_errors = nullptr;
  const YAML::Node flow = section("flow", false, flow_errors);
  const Params fp = validate_params(flow, flow_schema(), "flow", *flow_errors);
  ex.flow_params = fp;
  if (fp.has("peclet")) {
    ex.peclet = fp.number("peclet");
    ex.brownian = fp.flag("brownian");
  }

  const YAML::Node hydro = root["hydro"];
  if (!hydro)
    errors.add(root, "hydro", "missing required section (e.g. {plugin: fld})");
  else
    read_plugin_block(hydro, "hydro", "hydro", plugins_found, errors, ex.hydro);

  // `forces:` and `observers:` are lists of plugin blocks, each validated against its plugin.
  auto read_list = [&](const char* key, const char* kind, const ParamSchema* core_keys) {
    std::vector<PluginBlock> blocks;
    const YAML::Node list = root[key];
    if (!list) return blocks;
    if (!list.IsSequence()) {
      errors.add(list, key, "expected a list of {plugin: ...} maps");
      return blocks;
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      PluginBlock b;
      if (read_plugin_block(list[i], kind, std::string(key) + "[" + std::to_string(i) + "]", plugins_found,
                            errors, b, core_keys))
        blocks.push_back(std::move(b));
    }
    return blocks;
  };
  ex.forces = read_list("forces", "force", nullptr);
  ParamSchema schedule;
  schedule.integer("every", 1, "steps", "sample every this many steps").at_least(1);
  schedule.number("start", 0.0, "time_unit", "sample only from this time on").at_least(0.0);
  for (auto& b : read_list("observers", "observer", &schedule))
    if (b.params.has("every")) {
      const std::int64_t every = b.params.integer("every");
      const double start = b.params.number("start");
      ex.observers.push_back(ObserverBlock{std::move(b), every, start});
    }

  ConfigErrors* run_errors = nullptr;
  const YAML::Node run = section("run", true, run_errors);
  const Params rp = validate_params(run, run_schema(), "run", *run_errors);
  ex.run_params = rp;
  if (rp.has("dt")) {
    ex.dt_auto = std::holds_alternative<std::string>(rp.values().at("dt"));
    ex.dt_max = rp.number("dt_max");
    ex.dt_min = rp.number("dt_min");
    ex.tolerance = rp.number("tolerance");
    ex.max_overlap = rp.number("max_overlap");
    ex.reject_at = rp.number("reject_at");  // 0: set below, once flow.brownian is known
    ex.displacement = rp.number("displacement");
    ex.gap_step = rp.number("gap_step");
    ex.gap_range = rp.number("gap_range");
    ex.error_control = !(ex.displacement > 0.0 || ex.gap_step > 0.0) || rp.given("tolerance");
    if (rp.given("gap_range") && !(ex.gap_step > 0.0))
      run_errors->add(run["gap_range"], "run.gap_range", "only with run.gap_step (the pairs it measures)");
    ex.refine = int(rp.integer("refine"));
    // The frame: observers, checkpoints and the step counter count it.
    ex.dt = ex.dt_auto ? ex.dt_max : rp.number("dt");
    if (ex.dt_auto && ex.dt_max == 0.0)
      run_errors->add(run["dt"], "run.dt_max",
                      "dt: auto needs dt_max (the longest step, and the sampling frame)");
    if (!ex.dt_auto && rp.given("dt_max"))
      run_errors->add(run["dt_max"], "run.dt_max", "only with dt: auto (a fixed dt is its own frame)");
    for (const char* key : {"tolerance", "reject_at", "displacement", "gap_step"})
      if (!ex.dt_auto && rp.given(key))
        run_errors->add(run[key], std::string("run.") + key,
                        "only with dt: auto (a fixed step has no error control)");
    if (ex.dt > 0.0 && ex.dt_min > ex.dt)
      run_errors->add(run["dt_min"], "run.dt_min",
                      "expected a number <= the frame (dt, or dt_max with dt: auto)");
  }
  if (rp.has("duration")) ex.duration = rp.number("duration");
  if (rp.has("time_unit")) {
    ex.time_unit = rp.text("time_unit");
    ex.seed = rp.integer("seed");
    ex.integrator = rp.text("integrator");
    ex.drift = rp.text("drift");
    ex.brownian_stress = rp.text("brownian_stress");
    ex.brownian_stress_delta = rp.number("brownian_stress_delta");
    ex.brownian_stress_tolerance = rp.number("brownian_stress_tolerance");
    ex.skin_auto = std::holds_alternative<std::string>(rp.values().at("skin"));
    if (!ex.skin_auto) ex.skin = rp.number("skin");
    ex.checkpoint_every = rp.number("checkpoint_every");
    ex.threads = rp.integer("threads");
    ex.progress = rp.text("progress");
  }
  if (ex.dt > 0 && ex.duration > 0 && ex.dt > ex.duration)
    errors.add(ex.dt_auto ? run["dt_max"] : run["dt"], ex.dt_auto ? "run.dt_max" : "run.dt",
               "expected a time step no longer than run.duration");
  if (ex.reject_at == 0.0)
    ex.reject_at = ex.brownian ? 10.0 : 1.0;
  else if (ex.reject_at < 1.0)
    errors.add(run["reject_at"], "run.reject_at", "expected 0 (automatic) or a number >= 1");
  if (ex.dt_auto && !ex.error_control && rp.given("reject_at"))
    errors.add(run["reject_at"], "run.reject_at",
               "only with run.tolerance (with run.displacement or run.gap_step alone no step is rejected for "
               "its error)");
  if (ex.dt_auto && ex.error_control && ex.brownian && ex.drift == "none")
    errors.add(run["drift"], "run.drift",
               "dt: auto needs the midpoint stage for its error estimate; drift: none has none");
  if (ex.dt_auto && ex.error_control && ex.integrator == "euler_maruyama" && !ex.brownian)
    errors.add(run["integrator"], "run.integrator",
               "dt: auto without Brownian motion needs rk3 (Euler has no embedded error estimate)");
  if (ex.brownian && ex.integrator == "rk3") {
    // Its stages make the thermal drift themselves; it has no error estimate for the noise and
    // no midpoint stage for the midpoint stress estimate.
    if (ex.dt_auto && ex.error_control)
      errors.add(run["integrator"], "run.integrator",
                 "rk3 with Brownian motion has no error estimate for the noise: with dt: auto use "
                 "euler_maruyama, or run.displacement or run.gap_step alone");
    if (ex.drift == "none")
      errors.add(run["drift"], "run.drift",
                 "rk3 with Brownian motion always has the thermal drift (its stages make it); drift: none "
                 "needs euler_maruyama");
    if (ex.brownian_stress == "midpoint")
      errors.add(
          run["brownian_stress"], "run.brownian_stress",
          "brownian_stress: midpoint needs Euler-Maruyama's midpoint stage; use random_difference with rk3");
  }
  if (ex.integrator == "leimkuhler_matthews") {
    // Its noise has memory from one fixed step to the next; the hydro model and shape are
    // checked against it once built (RunCheck: averaged_noise_unbiased).
    if (!ex.brownian)
      errors.add(run["integrator"], "run.integrator",
                 "leimkuhler_matthews is a Brownian scheme; without Brownian motion use auto or rk3");
    if (ex.dt_auto)
      errors.add(run["integrator"], "run.integrator",
                 "leimkuhler_matthews takes fixed steps (its noise is the mean of consecutive steps'); "
                 "give run.dt a number");
    if (ex.refine > 0)
      errors.add(run["refine"], "run.refine",
                 "run.refine splits steps on the Brownian path; not with leimkuhler_matthews, whose steps "
                 "are whole");
    if (rp.given("drift") && ex.drift == "midpoint")
      errors.add(run["drift"], "run.drift",
                 "leimkuhler_matthews has no midpoint stage (where it is allowed there is no thermal drift)");
    if (ex.brownian_stress == "midpoint")
      errors.add(run["brownian_stress"], "run.brownian_stress",
                 "brownian_stress: midpoint needs Euler-Maruyama's midpoint stage; use random_difference");
  }
  if (!ex.brownian && root["flow"] && root["flow"]["peclet"] && ex.peclet == 0.0)
    errors.add(root["flow"]["peclet"], "flow.peclet",
               "a non-Brownian run (brownian: false) needs shear; remove peclet or set it > 0");

  if (const YAML::Node out = root["output"]) {
    if (!out.IsScalar())
      errors.add(out, "output", "expected a file name, got " + describe_yaml_value(out));
    else {
      ex.output = resolve_path(out.Scalar(), dir, "output", overrides);
      ex.output_location = errors.location(out);
    }
  }
  errors.throw_if_any();
  return ex;
}

}  // namespace

Experiment read_experiment(const std::string& file, const std::vector<std::string>& overrides,
                           std::unique_ptr<PluginRegistry>& registry) {
  return parse_experiment(load_yaml_file(file), file, overrides, registry, nullptr);
}

Experiment read_experiment(const std::string& file, const std::vector<std::string>& overrides,
                           const PluginRegistry& registry) {
  std::unique_ptr<PluginRegistry> unused;
  return parse_experiment(load_yaml_file(file), file, overrides, unused, &registry);
}

Experiment read_stored_experiment(const std::string& yaml_text, const std::string& label,
                                  const PluginRegistry& registry) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(label + ": the stored experiment is not valid YAML: " + e.msg);
  }
  std::unique_ptr<PluginRegistry> unused;
  return parse_experiment(root, label, {}, unused, &registry);
}

std::string core_keys_help() {
  std::ostringstream out;
  auto print = [&](const std::string& title, const ParamSchema& s) {
    out << title << "\n";
    for (const auto& spec : s.specs()) {
      out << "  " << spec.name << "  (" << spec.expectation();
      if (!spec.unit.empty()) out << ", unit " << spec.unit;
      out << ")  " << spec.help << "\n";
    }
  };
  print("system: (also `shape: {plugin: ...}` and `init: {...}`)", system_schema());
  print("system.init:", init_schema());
  print("flow:", flow_schema());
  print("run:", run_schema());
  out << "hydro: {plugin: NAME, ...}   forces: [{plugin: NAME, ...}]   observers: [{plugin: NAME, every: N, "
         "start: T, ...}]\n"
         "output: result file (HDF5)   plugins: {paths: [DIR, ...]}\n";
  return out.str();
}

}  // namespace fldsim
