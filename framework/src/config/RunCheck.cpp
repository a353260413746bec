#include "config/RunCheck.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "config/ConfigErrors.hpp"
#include "config/NumberText.hpp"
#include "config/ParamOrigins.hpp"
#include "dynamics/PairGapStep.hpp"
#include "dynamics/TimeIntegrator.hpp"
#include "fldsim/force.hpp"
#include "fldsim/hydro.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/shape.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "io/Checkpoint.hpp"
#include "io/FrameReader.hpp"
#include "run/Simulation.hpp"

namespace fldsim {

namespace fs = std::filesystem;

namespace {

// What a run needs per node: positions, pair list, block-sparse R and its IC(0) factor. Measured
// (peak RSS less the 20 MB of an empty run) at 8.5 KiB per node for 1000 dicolloids at phi = 0.5
// with FLD, repulsion and four observers; twice that, for denser scenes and larger cutoffs.
constexpr double kBytesPerNode = 16.0 * 1024.0;
// What an observer keeps per sample for its block averages (the orientation observer, the
// largest, keeps about 40 doubles), rounded up.
constexpr double kBytesPerSample = 512.0;

// Observers' begin() on the stand-in system writes here: nothing is kept.
class DiscardingSink final : public ResultSink {
 public:
  void write_scalar(const std::string&, double, double, const std::string&, const std::string&) override {}
  void write_array(const std::string&, const std::vector<std::size_t>&, const double*, const std::string&,
                   const std::string&) override {}
  void append_sample(const std::string&, std::int64_t, double, const std::vector<std::size_t>&, const double*,
                     const std::string&) override {}
  void write_attribute(const std::string&, const std::string&, const std::string&) override {}
  void write_int_attribute(const std::string&, const std::string&,
                           const std::vector<std::int64_t>&) override {}
  void write_string_list_attribute(const std::string&, const std::string&,
                                   const std::vector<std::string>&) override {}
};

// Silences what plugins log on std::clog / std::cerr while they are tried out on the stand-in
// system (the real run logs it once, when it happens).
class QuietLogs {
 public:
  QuietLogs() : clog_(std::clog.rdbuf(nullptr)), cerr_(std::cerr.rdbuf(nullptr)) {}
  ~QuietLogs() {
    std::clog.rdbuf(clog_);
    std::cerr.rdbuf(cerr_);
    std::clog.clear();
    std::cerr.clear();
  }
  QuietLogs(const QuietLogs&) = delete;
  QuietLogs& operator=(const QuietLogs&) = delete;

 private:
  std::streambuf* clog_;
  std::streambuf* cerr_;
};

std::string bytes_text(double b) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (b >= 1024.0 && u < 6) {
    b /= 1024.0;
    ++u;
  }
  std::ostringstream o;
  o << std::setprecision(3) << b << " " << units[u];
  return o.str();
}

double machine_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

// Collects problems; every message says where (file:line:col and key path, or the option).
class Problems {
 public:
  explicit Problems(ConfigErrors& errors) : errors_(errors) {}
  void at(const Params& p, const std::string& key, const std::string& message) {
    const ParamOrigin o = origin_of(p, key);
    errors_.add(o.location, o.path, message);
  }
  void at_block(const PluginBlock& b, const std::string& message) {
    errors_.add(origin_of(b.params, "plugin").location, b.path, message);
  }
  void at(const std::string& location, const std::string& path, const std::string& message) {
    errors_.add(location, path, message);
  }
  // A ConfigError's text (already "file:line:col: key: message" lines).
  void formatted(const std::string& text) { errors_.add_formatted(text); }
  ConfigErrors& errors() { return errors_; }

 private:
  ConfigErrors& errors_;
};

template <class T>
std::shared_ptr<T> construct(const PluginRegistry& registry, const PluginBlock& b, Problems& problems) {
  try {
    return registry.create<T>(b.kind, b.name, b.params);
  } catch (const ConfigError& e) {
    problems.formatted(e.what());
  } catch (const std::exception& e) {
    problems.at_block(b, e.what());
  }
  return nullptr;
}

// Samples an observer takes in steps (first, total]: every `every`-th step from time `start`.
std::int64_t samples_taken(std::int64_t total, std::int64_t every, double start, double dt) {
  if (every <= 0) return 0;
  const double first_due = std::max(1.0, std::ceil(start / dt - 1e-9));
  if (first_due > double(total)) return 0;
  const auto from = std::int64_t(first_due);
  return total / every - (from - 1) / every;
}

void check_output(const Experiment& ex, const RunTargets& t, const std::string& output, Problems& problems) {
  const std::string where = !t.output.empty() ? "-o " + t.output : ex.output_location;
  const std::string key = !t.output.empty() ? "" : "output";
  if (output.empty()) {
    problems.at(ex.file, "output", "no result file named (set `output:` or give -o OUT.h5)");
    return;
  }
  std::error_code ec;
  const fs::path out(output);
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (fs::is_directory(out, ec)) {
    problems.at(where, key, "'" + output + "' is a directory, not a result file name");
    return;
  }
  // The run creates missing directories: the nearest existing one must be a writable directory.
  fs::path existing = dir;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::exists(existing, ec)) existing = ".";
  if (!fs::is_directory(existing, ec)) {
    problems.at(where, key,
                "'" + existing.string() + "' is not a directory: the result file cannot go below it");
    return;
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    problems.at(where, key, "cannot write in '" + existing.string() + "': " + std::strerror(errno));
    return;
  }
  if (fs::exists(out, ec) && !t.overwrite)
    problems.at(where, key, "'" + output + "' exists; give --overwrite to replace it, or another -o");
  const std::string checkpoint = output + ".checkpoint";
  const bool resuming_it =
      !t.resume.empty() && fs::exists(t.resume, ec) && fs::equivalent(t.resume, checkpoint, ec);
  if (fs::exists(checkpoint, ec) && !t.overwrite && !resuming_it)
    problems.at(where, key,
                "'" + checkpoint +
                    "' exists (the state of an earlier run, perhaps the only one left): continue it "
                    "with --resume " +
                    checkpoint + ", or give --overwrite to start afresh");
}

}  // namespace

void check_resume_compatible(const Experiment& now, const Experiment& then, const std::string& checkpoint,
                             ConfigErrors& errors) {
  const std::string why =
      "; resuming would mix two different runs in one set of statistics (on resume only run.duration, "
      "run.checkpoint_every, run.threads, output, plugins.paths and system.init may change)";
  auto value_text = [](const ParamValue& v) {
    std::ostringstream o;
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, bool>)
            o << (x ? "true" : "false");
          else if constexpr (std::is_same_v<T, std::vector<double>> ||
                             std::is_same_v<T, std::vector<std::vector<double>>>)
            o << "a list of " << x.size();
          else if constexpr (std::is_same_v<T, double>)
            o << format_number(x);
          else
            o << x;
        },
        v);
    return o.str();
  };
  auto compare_params = [&](const Params& a, const Params& b, const std::set<std::string>& allowed) {
    for (const auto& [key, value] : a.values()) {
      if (allowed.count(key)) continue;
      const auto it = b.values().find(key);
      if (it == b.values().end()) {
        const ParamOrigin o = origin_of(a, key);
        errors.add(o.location, o.path, "not in the experiment of " + checkpoint + why);
      } else if (!(it->second == value)) {
        const ParamOrigin o = origin_of(a, key);
        errors.add(o.location, o.path,
                   value_text(value) + " now, " + value_text(it->second) + " when " + checkpoint +
                       " was written" + why);
      }
    }
  };
  auto compare_block = [&](const PluginBlock& a, const PluginBlock* b) {
    if (!b) {
      errors.add(origin_of(a.params, "plugin").location, a.path,
                 "not in the experiment of " + checkpoint + why);
      return;
    }
    if (a.name != b->name) {
      errors.add(origin_of(a.params, "plugin").location, a.path + ".plugin",
                 "'" + a.name + "' now, '" + b->name + "' when " + checkpoint + " was written" + why);
      return;
    }
    compare_params(a.params, b->params, {});
  };
  compare_params(now.system_params, then.system_params, {});
  compare_block(now.shape, &then.shape);
  compare_params(now.flow_params, then.flow_params, {});
  compare_block(now.hydro, &then.hydro);
  compare_params(now.run_params, then.run_params, {"duration", "checkpoint_every", "threads"});
  for (std::size_t i = 0; i < now.forces.size(); ++i)
    compare_block(now.forces[i], i < then.forces.size() ? &then.forces[i] : nullptr);
  for (std::size_t i = 0; i < now.observers.size(); ++i)
    compare_block(now.observers[i].plugin, i < then.observers.size() ? &then.observers[i].plugin : nullptr);
  auto fewer = [&](std::size_t n_now, std::size_t n_then, const char* what) {
    if (n_now < n_then)
      errors.add(now.file, what,
                 std::to_string(n_then - n_now) + " fewer than in the experiment of " + checkpoint + why);
  };
  fewer(now.forces.size(), then.forces.size(), "forces");
  fewer(now.observers.size(), then.observers.size(), "observers");
}

RunCheckReport check_run(const Experiment& ex, const PluginRegistry& registry, const RunTargets& targets) {
  ConfigErrors errors(ex.file);
  Problems problems(errors);
  RunCheckReport report;

  // Plugins that shadow others with the same name: the user may expect the other one.
  auto note_shadowed = [&](const PluginBlock& b) {
    for (const auto& s : registry.shadowed())
      if (s.find(" " + b.kind + " plugin '" + b.name + "' ") != std::string::npos)
        report.warnings.push_back(b.path + ": " + s);
  };

  // Plugins tried out here log nothing: the run logs what they say once, when it happens.
  const QuietLogs quiet;

  // 1. Every plugin constructed, as `run` makes them.
  auto shape = construct<Shape>(registry, ex.shape, problems);
  auto hydro = construct<HydroModel>(registry, ex.hydro, problems);
  std::vector<std::shared_ptr<ForceLaw>> forces;
  for (const auto& f : ex.forces) forces.push_back(construct<ForceLaw>(registry, f, problems));
  std::vector<std::shared_ptr<Observer>> observers;
  for (const auto& o : ex.observers) observers.push_back(construct<Observer>(registry, o.plugin, problems));
  note_shadowed(ex.shape);
  note_shadowed(ex.hydro);
  for (const auto& f : ex.forces) note_shadowed(f);
  for (const auto& o : ex.observers) note_shadowed(o.plugin);
  // What an observer needs from the hydro model (stresslets), refused as the run would.
  if (hydro && std::all_of(observers.begin(), observers.end(), [](const auto& o) { return o != nullptr; })) {
    try {
      check_observer_needs(ex, *hydro, observers);
    } catch (const ConfigError& e) {
      problems.formatted(e.what());
    }
  }

  // One result dataset per observer: two instances of one plugin would write (append to) the
  // same paths.
  for (std::size_t i = 0; i < ex.observers.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (ex.observers[i].plugin.name == ex.observers[j].plugin.name &&
          ex.observers[i].plugin.name != "progress") {
        problems.at_block(ex.observers[i].plugin,
                          "a second '" + ex.observers[i].plugin.name + "' observer (the first is " +
                              ex.observers[j].plugin.path +
                              "): both would write the same result datasets; keep one");
        break;
      }

  // 2. Time: units, step count.
  const Params& run = ex.run_params;
  const double shear_rate = ex.brownian ? ex.peclet : 1.0;
  if (ex.time_unit == "diffusive" && !ex.brownian)
    problems.at(run, "time_unit", "diffusive time (a^2/D0) needs a Brownian run (flow.brownian: true)");
  const bool strain_unit =
      ex.time_unit == "strain" || (ex.time_unit == "paper" && !(ex.brownian && ex.peclet < 1.0));
  if (strain_unit && !(shear_rate > 0.0))
    problems.at(run, ex.time_unit == "strain" ? "time_unit" : "dt",
                "times in strain units (1/gammadot" +
                    std::string(ex.time_unit == "paper" ? ", the paper's unit for Pe >= 1" : "") +
                    ") need flow.peclet > 0");
  std::int64_t total_steps = 0;
  if (ex.dt > 0.0 && ex.duration > 0.0) {
    const double steps = ex.duration / ex.dt;
    // run.refine takes every frame in 2^refine steps: those are the steps that must fit.
    const double refined = std::ldexp(steps, ex.refine);
    if (!(steps <= kMaxSteps))
      problems.at(run, "duration",
                  "run.duration / run.dt = " + log_number(steps) + " steps; at most " +
                      log_number(kMaxSteps) +
                      " steps per run (a longer dt, a shorter duration, or several resumed runs)");
    else if (!(refined <= kMaxSteps))
      problems.at(run, "refine",
                  std::to_string(ex.refine) + ": run.duration / run.dt x 2^refine = " + log_number(refined) +
                      " steps; at most " + log_number(kMaxSteps) + " steps per run");
    else
      total_steps = std::max<std::int64_t>(1, std::llround(steps));
  }
  if (ex.checkpoint_every > 0.0 && ex.dt > 0.0 && ex.checkpoint_every < ex.dt)
    problems.at(run, "checkpoint_every", "shorter than one step (run.dt = " + log_number(ex.dt) + ")");

  // 3. Observers: each must record something; their sample buffers must fit.
  double sample_bytes = 0.0;
  for (std::size_t i = 0; i < ex.observers.size(); ++i) {
    const ObserverBlock& o = ex.observers[i];
    if (total_steps == 0 || !observers[i]) continue;
    if (observers[i]->needs().every_step) continue;
    // The core samples after steps; the trajectory observer also writes the start frame in its
    // begin() when `start` is 0 (a run that wants only the start configuration is valid).
    // TODO(plugin API 5): an ObserverNeeds flag instead of the name.
    const std::int64_t n = samples_taken(total_steps, o.every, o.start, ex.dt) +
                           (o.plugin.name == "trajectory" && o.start <= 0.0 ? 1 : 0);
    if (n == 0) {
      if (o.start > ex.duration)
        problems.at(o.plugin.params, "start",
                    log_number(o.start) + " is after the end of the run (run.duration " +
                        log_number(ex.duration) + "): the observer would record nothing");
      else
        problems.at(o.plugin.params, "every",
                    std::to_string(o.every) + " steps: no sample falls in the run's " +
                        std::to_string(total_steps) +
                        " steps after `start`; the observer would record nothing");
    }
    sample_bytes += double(n) * kBytesPerSample;
  }

  // 4. The scene: box, volume fraction, feasibility, memory.
  double edge = 0.0, phi = 0.0;
  std::unique_ptr<System> sys;
  if (shape && ex.count > 0) {
    const double volume = shape->volume();
    const double reach = shape->bounding_radius();
    double node_radius = 0.0;
    for (const auto& n : shape->nodes()) node_radius = std::max(node_radius, n.radius);
    const double n_bodies = double(ex.count);
    const std::string phi_key = ex.box_edge > 0.0 ? "box_edge" : "volume_fraction";
    if (!(volume > 0.0) || !std::isfinite(volume)) {
      problems.at_block(ex.shape, "body volume " + log_number(volume) + " a^3: expected a positive volume");
    } else {
      edge = ex.box_edge > 0.0 ? ex.box_edge : std::cbrt(n_bodies * volume / ex.volume_fraction);
      phi = n_bodies * volume / (edge * edge * edge);
      const std::string scene = std::to_string(ex.count) + " bodies of " + log_number(volume) +
                                " a^3 in a box of edge " + log_number(edge) + " a: phi = " + log_number(phi);
      if (!(phi < 0.74))
        problems.at(ex.system_params, phi_key, scene + "; no packing of hard bodies exceeds 0.74");
      else if (ex.init_method == "monte_carlo" && phi >= kMonteCarloPhiLimit)
        problems.at(ex.system_params, phi_key,
                    scene + "; the hard-body Monte Carlo start cannot compress beyond phi = " +
                        log_number(kMonteCarloPhiLimit) +
                        " (start from system.init.file of a denser earlier run)");
      // A body must not reach its own periodic image, nor a pair its own second image.
      if (2.0 * (reach + node_radius) >= edge)
        problems.at(ex.system_params, phi_key,
                    "a " + ex.shape.name + " body spans " + log_number(2.0 * (reach + node_radius)) +
                        " a, not less than the box edge " + log_number(edge) +
                        " a: it would touch its own periodic image");
    }
    const double memory = n_bodies * double(shape->nodes().size()) * kBytesPerNode + sample_bytes;
    const double machine = machine_memory_bytes();
    if (machine > 0.0 && memory > 0.8 * machine)
      problems.at(ex.system_params, "count",
                  std::to_string(ex.count) + " bodies of " + std::to_string(shape->nodes().size()) +
                      " nodes (and the observers' samples) need about " + bytes_text(memory) +
                      "; this machine has " + bytes_text(machine));
    else if (edge > 0.0 && std::isfinite(edge) && phi < 0.74) {
      Physics ph;
      ph.kT = ex.brownian ? 1.0 : 0.0;
      ph.shear_rate = shear_rate;
      ph.volume_fraction = phi;
      try {
        sys = std::make_unique<System>(shape, std::size_t(ex.count), edge, ph);
      } catch (const std::exception& e) {
        problems.at_block(ex.shape, std::string("cannot build the system: ") + e.what());
      }
    }
  }

  // 5. Pair range against the box (minimum image), hydro set-up, observers begun.
  if (sys) {
    double range = 0.0;
    try {
      if (hydro) range = std::max(range, hydro->pair_range(*sys));
      for (std::size_t i = 0; i < forces.size(); ++i)
        if (forces[i]) range = std::max(range, forces[i]->range(*sys));
      if (ex.dt_auto && ex.gap_step > 0.0)  // the list holds the pairs run.gap_step measures
        range = std::max(range, pair_gap_list_range(sys->shape(), ex.gap_range));
      if (hydro && ex.integrator == "leimkuhler_matthews") {
        const std::string refusal = leimkuhler_matthews_refusal(*hydro, *sys);
        if (!refusal.empty()) problems.at(ex.run_params, "integrator", refusal);
      }
    } catch (const std::exception& e) {
      problems.at_block(ex.hydro, e.what());
    }
    if (range + ex.skin >= 0.5 * edge)
      problems.at(ex.system_params, ex.box_edge > 0.0 ? "box_edge" : "count",
                  "the pair range " + log_number(range) + " a + run.skin " + log_number(ex.skin) +
                      " a must be less than half the box edge (" + log_number(0.5 * edge) +
                      " a): more bodies, or a larger box_edge");
    // Listed positions: as `run` places them.
    if (ex.init_method == "explicit") {
      const Params& ip = ex.init_params;
      if (ex.init_positions.size() != sys->size())
        problems.at(ip, "positions",
                    "expected " + std::to_string(sys->size()) + " positions (system.count), got " +
                        std::to_string(ex.init_positions.size()));
      else if (!ex.init_orientations.empty() && ex.init_orientations.size() != sys->size())
        problems.at(ip, "orientations",
                    "expected " + std::to_string(sys->size()) + " orientations (one per body) or none, got " +
                        std::to_string(ex.init_orientations.size()));
      else {
        std::vector<Vec3> x;
        std::vector<Quat> q;
        bool ok = true;
        for (std::size_t i = 0; i < sys->size(); ++i) {
          const auto& p = ex.init_positions[i];
          x.emplace_back(p[0], p[1], p[2]);
          if (i >= ex.init_orientations.size()) {
            q.push_back(Quat::Identity());
            continue;
          }
          const auto& r = ex.init_orientations[i];
          const std::string row = "orientations[" + std::to_string(i) + "]";
          if (r.size() == 4 && Eigen::Vector4d(r[0], r[1], r[2], r[3]).norm() > 0.0) {
            q.push_back(Quat(r[0], r[1], r[2], r[3]).normalized());
          } else if (r.size() == 3 && Vec3(r[0], r[1], r[2]).norm() > 0.0) {
            q.push_back(Quat::FromTwoVectors(shape->director(), Vec3(r[0], r[1], r[2]).normalized()));
          } else {
            problems.at(ip, "orientations",
                        row + ": expected a non-zero director [nx, ny, nz] or quaternion [w, x, y, z]");
            ok = false;
          }
        }
        if (ok) try {
            geometry::place_explicit(*sys, x, q);
          } catch (const std::exception& e) {
            problems.at(ip, "positions", e.what());
          }
      }
    } else if (ex.init_method == "file") {
      try {
        const Checkpoint c = read_last_frame(ex.init_file);
        if (c.positions.size() != sys->size())
          problems.at(ex.init_params, "file",
                      ex.init_file + " holds " + std::to_string(c.positions.size()) +
                          " bodies, the experiment asks for " + std::to_string(sys->size()));
      } catch (const std::exception& e) {
        problems.at(ex.init_params, "file", e.what());
      }
    }
    if (hydro) {
      HydroRequest request;
      request.brownian = ex.brownian;
      request.shear = shear_rate != 0.0;
      for (const auto& o : observers) request.stresslets = request.stresslets || (o && o->needs().stress);
      try {
        hydro->configure(*sys, request);
      } catch (const ConfigError& e) {
        problems.formatted(e.what());
      } catch (const std::exception& e) {
        problems.at_block(ex.hydro, e.what());
      }
    }
    RunInfo info;
    info.total_steps = total_steps;
    info.dt = ex.dt;
    info.output_path = targets.output.empty() ? ex.output : targets.output;
    info.seed = std::uint64_t(ex.seed);
    DiscardingSink discard;
    for (std::size_t i = 0; i < observers.size(); ++i) {
      if (!observers[i] || total_steps == 0) continue;
      observers[i]->set_schedule(ex.observers[i].every, ex.observers[i].start);
      try {
        observers[i]->begin(*sys, info, discard);
      } catch (const ConfigError& e) {
        problems.formatted(e.what());
      } catch (const std::exception& e) {
        problems.at_block(ex.observers[i].plugin, e.what());
      }
    }
  }

  // 6. Files: the result and checkpoint, the checkpoint to resume.
  const std::string output = !targets.output.empty() ? targets.output : ex.output;
  check_output(ex, targets, output, problems);
  if (!targets.resume.empty()) {
    const std::string where = "--resume " + targets.resume;
    try {
      const Checkpoint c = read_checkpoint(targets.resume);
      report.resume_step = c.step;
      if (ex.count > 0 && c.positions.size() != std::size_t(ex.count))
        problems.at(where, "",
                    "the checkpoint holds " + std::to_string(c.positions.size()) +
                        " bodies, the experiment (system.count) " + std::to_string(ex.count));
      if (total_steps > 0 && c.step > total_steps)
        problems.at(ex.run_params, "duration",
                    "the checkpoint is at step " + std::to_string(c.step) + ", past the end of this run (" +
                        std::to_string(total_steps) + " steps)");
      try {
        const Experiment then =
            read_stored_experiment(c.experiment_yaml, targets.resume + " (its experiment)", registry);
        check_resume_compatible(ex, then, targets.resume, errors);
      } catch (const ConfigError& e) {
        problems.at(where, "",
                    "its stored experiment cannot be read with these plugins: " +
                        std::string(e.what()).substr(0, 300));
      }
    } catch (const std::exception& e) {
      problems.at(where, "", e.what());
    }
  }

  errors.throw_if_any();
  std::ostringstream s;
  s << ex.count << " x " << ex.shape.name << ", phi = " << log_number(phi) << " (box edge "
    << log_number(edge) << " a), hydro " << ex.hydro.name << ", " << ex.forces.size() << " force(s), "
    << ex.observers.size() << " observer(s), " << total_steps << " steps";
  report.summary = s.str();
  report.steps = total_steps;
  report.nodes = shape ? ex.count * std::int64_t(shape->nodes().size()) : 0;
  report.volume_fraction = phi;
  return report;
}

}  // namespace fldsim
