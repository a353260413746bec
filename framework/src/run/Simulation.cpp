#include "run/Simulation.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "dynamics/TimeIntegrator.hpp"
#include "dynamics/VelocityEvaluator.hpp"
#include "fldsim/observer.hpp"
#include "geometry/CellNeighbourList.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "io/Checkpoint.hpp"
#include "io/FrameReader.hpp"
#include "io/Hdf5ResultSink.hpp"
#include "run/StepLoop.hpp"
#include "run/ThreadPlan.hpp"
#include "run/ThreadTrial.hpp"

namespace fldsim {
using namespace geometry;
namespace {

Quat orientation_from_row(const std::vector<double>& row, std::size_t i) {
  if (row.size() == 4) return Quat(row[0], row[1], row[2], row[3]).normalized();
  if (row.size() == 3) {
    const Vec3 n(row[0], row[1], row[2]);
    if (n.norm() == 0.0) throw Error("system.init.orientations[" + std::to_string(i) + "]: zero director");
    return Quat::FromTwoVectors(Vec3::UnitZ(), n.normalized());
  }
  throw Error("system.init.orientations[" + std::to_string(i) +
              "]: expected a director [nx, ny, nz] or a quaternion [w, x, y, z]");
}

void initialise(System& sys, const Experiment& ex, std::ostream& log) {
  if (ex.init_method == "explicit") {
    if (ex.init_positions.size() != sys.size())
      throw Error(ex.file + ": system.init.positions: expected " + std::to_string(sys.size()) +
                  " positions (system.count), got " + std::to_string(ex.init_positions.size()));
    std::vector<Vec3> x;
    std::vector<Quat> q;
    for (std::size_t i = 0; i < sys.size(); ++i) {
      const auto& p = ex.init_positions[i];
      if (p.size() != 3)
        throw Error(ex.file + ": system.init.positions[" + std::to_string(i) + "]: expected [x, y, z]");
      x.emplace_back(p[0], p[1], p[2]);
      q.push_back(i < ex.init_orientations.size() ? orientation_from_row(ex.init_orientations[i], i)
                                                  : Quat::Identity());
    }
    place_explicit(sys, x, q);
    log << "start: " << sys.size() << " bodies placed as listed in the experiment\n";
  } else if (ex.init_method == "file") {
    const Checkpoint c = read_last_frame(ex.init_file);
    if (c.positions.size() != sys.size())
      throw Error(ex.init_file + ": has " + std::to_string(c.positions.size()) +
                  " bodies, the experiment asks for " + std::to_string(sys.size()));
    sys.positions() = c.positions;
    sys.orientations() = c.orientations;
    sys.box().set_strain(c.strain);
    sys.update_nodes();
    log << "start: last frame of " << ex.init_file << "\n";
  } else {
    MonteCarloOptions opt;
    opt.seed = std::uint64_t(ex.init_seed);
    opt.sweeps = ex.init_sweeps;
    const auto t0 = std::chrono::steady_clock::now();
    const MonteCarloReport r =
        initialise_monte_carlo(sys, opt, [&](const std::string& m) { log << "  mc: " << m << "\n"; });
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    log << "start: hard-body Monte Carlo, " << r.sweeps << " sweeps in " << std::fixed << std::setprecision(1)
        << secs << " s (acceptance " << std::setprecision(2) << r.acceptance_translation << " / "
        << r.acceptance_rotation << "), phi = " << std::setprecision(4) << r.final_volume_fraction
        << ", overlaps " << r.overlaps << "\n"
        << std::defaultfloat;
    if (r.overlaps != 0) throw Error("Monte Carlo start left " + std::to_string(r.overlaps) + " overlaps");
  }
}

std::string format_time(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << seconds << " s";
  return s.str();
}

}  // namespace

int run_experiment(const Experiment& ex, const PluginRegistry& registry, const RunOptions& opt,
                   std::ostream& log) {
  const auto wall0 = std::chrono::steady_clock::now();
  const ThreadPlan threads = plan_threads(ex.threads, std::size_t(ex.count));
#ifdef _OPENMP
  omp_set_num_threads(threads.threads);
#endif
  const std::string output = !opt.output.empty() ? opt.output : ex.output;
  if (output.empty()) throw ConfigError(ex.file + ": output: no result file named (set `output:` or use -o)");
  // Opened first: it refuses an existing file before any Monte Carlo work is spent.
  Hdf5ResultSink sink(output, opt.overwrite);

  auto shape = registry.create<Shape>("shape", ex.shape.name, ex.shape.params);

  // Physical parameters in internal units (a = 1, 6 pi mu a = 1, kT = 1 when Brownian).
  Physics ph;
  ph.kT = ex.brownian ? 1.0 : 0.0;
  ph.shear_rate = ex.brownian ? ex.peclet : 1.0;
  const double diffusive = 1.0;  // a^2/D0 in internal time units
  const double strain_unit = ph.shear_rate > 0 ? 1.0 / ph.shear_rate : 0.0;
  std::string unit_name;
  double time_scale = 0.0;
  if (ex.time_unit == "diffusive" || (ex.time_unit == "paper" && ex.brownian && ex.peclet < 1.0)) {
    if (!ex.brownian) throw ConfigError(ex.file + ": run.time_unit: diffusive time needs a Brownian run");
    time_scale = diffusive;
    unit_name = "a^2/D0";
  } else {
    if (strain_unit == 0.0)
      throw ConfigError(ex.file + ": run.time_unit: strain units (1/gammadot) need flow.peclet > 0");
    time_scale = strain_unit;
    unit_name = "1/gammadot";
  }

  const double v_body = shape->volume();
  double edge = ex.box_edge;
  ph.volume_fraction = ex.volume_fraction;
  if (edge > 0.0)
    ph.volume_fraction = double(ex.count) * v_body / (edge * edge * edge);
  else
    edge = std::cbrt(double(ex.count) * v_body / ex.volume_fraction);

  System sys(shape, std::size_t(ex.count), edge, ph);
  log << "fldsim: " << ex.file << "\n"
      << "system: " << ex.count << " x " << ex.shape.name << " (" << shape->nodes().size()
      << " nodes, volume " << v_body << " a^3), phi = " << ph.volume_fraction << ", box edge " << edge
      << " a\n"
      << "flow: "
      << (ex.brownian ? "Pe = " + std::to_string(ex.peclet)
                      : std::string("non-Brownian (kT = 0), gammadot = 1"))
      << "; times in " << unit_name << "\n";

  auto hydro = registry.create<HydroModel>("hydro", ex.hydro.name, ex.hydro.params);
  std::vector<std::shared_ptr<ForceLaw>> forces;
  for (const auto& f : ex.forces) forces.push_back(registry.create<ForceLaw>("force", f.name, f.params));
  std::vector<std::shared_ptr<Observer>> observers;
  bool need_stress = false;
  for (const auto& o : ex.observers) {
    auto ob = registry.create<Observer>("observer", o.plugin.name, o.plugin.params);
    ob->set_schedule(o.every, o.start * time_scale);
    need_stress = need_stress || ob->needs().stress;
    observers.push_back(ob);
  }

  Checkpoint resume;
  if (!opt.resume.empty()) {
    resume = read_checkpoint(opt.resume);
    if (resume.positions.size() != sys.size())
      throw Error(opt.resume + ": checkpoint has " + std::to_string(resume.positions.size()) +
                  " bodies, experiment " + std::to_string(sys.size()));
    if (resume.experiment_yaml != ex.resolved_yaml)
      log << "warning: " << opt.resume << " was written by a different experiment file; resuming anyway\n";
    sys.positions() = resume.positions;
    sys.orientations() = resume.orientations;
    sys.displacement() = resume.displacement;
    sys.nonaffine_displacement() = resume.nonaffine;
    sys.box().set_strain(resume.strain);
    sys.set_time(resume.time);
    sys.set_step(resume.step);
    sys.update_nodes();
    log << "start: resumed from " << opt.resume << " at step " << resume.step << "\n";
  } else {
    initialise(sys, ex, log);
  }

  double range = hydro->pair_range(sys);
  for (const auto& f : forces) range = std::max(range, f->range(sys));
  CellNeighbourList list;
  list.configure(range, ex.skin);
  sys.update_nodes();
  list.update(sys);

  HydroRequest request;
  request.brownian = ph.kT > 0.0;
  request.shear = ph.shear_rate != 0.0;
  request.stresslets = need_stress;
  std::vector<std::string> skipped = hydro->configure(sys, request);
  if (!need_stress) skipped.push_back("no interparticle virial (no stress observer)");
  if (need_stress && request.brownian && ex.drift != "midpoint")
    skipped.push_back("no Brownian stress (it needs the midpoint stage: run.drift: midpoint)");

  const bool use_rk3 = ex.integrator == "rk3" || (ex.integrator == "auto" && !ex.brownian);
  std::unique_ptr<TimeIntegrator> integrator;
  if (use_rk3)
    integrator = std::make_unique<RungeKutta3>(sys.size());
  else
    integrator = std::make_unique<EulerMaruyama>(
        std::uint64_t(ex.seed), request.brownian,
        ex.drift == "none" ? DriftScheme::None : DriftScheme::Midpoint, sys.size());
  VelocityEvaluator evaluator(hydro, forces, list, sys.size());
  if (!opt.resume.empty() && resume.warm_start.size() == evaluator.warm_start().size())
    evaluator.warm_start() = resume.warm_start;

  const double dt = ex.dt * time_scale;
  const std::int64_t total_steps = std::int64_t(std::llround(ex.duration / ex.dt));
  const std::int64_t checkpoint_steps =
      ex.checkpoint_every > 0 ? std::max<std::int64_t>(1, std::llround(ex.checkpoint_every / ex.dt)) : 0;
  StepControlSettings control;
  control.adaptive = ex.dt_auto;
  control.frame = dt;
  control.dt_min = ex.dt_min * time_scale;
  control.tolerance = ex.tolerance;
  control.reject_at = ex.reject_at;
  control.refine = ex.refine;
  control.order = integrator->error_order();
  StepGuard guard;
  guard.max_overlap = ex.max_overlap;
  log << "hydro: " << ex.hydro.name << "; integrator: " << integrator->describe() << "; ";
  if (ex.dt_auto)
    log << "dt: auto (adaptive, local error <= " << ex.tolerance << " a, steps up to dt_max = " << ex.dt
        << " " << unit_name << "), " << total_steps << " frames of dt_max";
  else
    log << "dt = " << ex.dt << " " << unit_name << ", " << total_steps << " steps";
  if (ex.refine > 0)
    log << ", each in " << (1 << ex.refine) << " equal steps on its Brownian path (run.refine)";
  log << "; guard: overlap > " << ex.max_overlap << " a rejects a step; pair range " << range << " a + skin "
      << ex.skin << " a\n"
      << "threads: " << threads.threads << " (" << threads.reason << ")\n";
  for (const auto& w : threads.warnings) log << "warning: " << w << "\n";
  for (const auto& s : skipped) log << "skipped: " << s << "\n";

  RunInfo info;
  info.total_steps = total_steps;
  info.dt = dt;
  info.time_unit = unit_name;
  info.time_scale = time_scale;
  info.output_path = output;
  info.seed = std::uint64_t(ex.seed);

  {
    std::vector<std::array<std::string, 4>> table;
    auto add = [&](const std::string& kind, const std::string& name) {
      const PluginInfo& p = registry.find(kind, name);
      table.push_back({kind, name, p.version, p.file});
    };
    add("shape", ex.shape.name);
    add("hydro", ex.hydro.name);
    for (const auto& f : ex.forces) add("force", f.name);
    for (const auto& o : ex.observers) add("observer", o.plugin.name);
    std::map<std::string, std::string> extra{
        {"time_unit", unit_name},
        {"units", "lengths a (node radius), energies kT, time a^2/D0 internally"},
        {"peclet", std::to_string(ex.peclet)},
        {"volume_fraction", std::to_string(ph.volume_fraction)},
        {"shape", ex.shape.name},
        {"brownian", ex.brownian ? "true" : "false"},
        {"integrator", integrator->describe()},
        {"experiment_file", ex.file}};
    if (ex.shape.params.has("c")) extra["shape_c"] = std::to_string(ex.shape.params.number("c"));
    sink.write_parameters(ex.resolved_yaml, table, std::uint64_t(ex.seed), extra);
  }
  for (auto& o : observers) o->begin(sys, info, sink);
  // Observer state in the checkpoint is keyed by position and plugin, "observers[2].stress".
  auto observer_key = [&](std::size_t i) {
    return "observers[" + std::to_string(i) + "]." + ex.observers[i].plugin.name;
  };
  if (!opt.resume.empty())
    for (std::size_t i = 0; i < observers.size(); ++i) {
      const auto it = resume.blobs.find(observer_key(i));
      if (it != resume.blobs.end()) {
        observers[i]->restore_state(it->second);
      } else if (!observers[i]->save_state().empty()) {
        log << "warning: " << opt.resume << " holds no state for " << observer_key(i)
            << ": its averages start afresh\n";
      }
    }

  std::function<std::vector<double>()> step_state;  // set once the step loop exists
  auto write_checkpoint_now = [&](const std::string& path) {
    Checkpoint c;
    c.positions = sys.positions();
    c.orientations = sys.orientations();
    c.displacement = sys.displacement();
    c.nonaffine = sys.nonaffine_displacement();
    c.time = sys.time();
    c.strain = sys.box().strain();
    c.box_edge = sys.box().edge();
    c.step = sys.step();
    c.seed = std::uint64_t(ex.seed);
    c.experiment_yaml = ex.resolved_yaml;
    c.warm_start = evaluator.warm_start();
    for (std::size_t i = 0; i < observers.size(); ++i) {
      std::vector<double> state = observers[i]->save_state();
      if (!state.empty()) c.blobs[observer_key(i)] = std::move(state);
    }
    if (step_state) c.blobs["run.steps"] = step_state();
    write_checkpoint(path, c);
  };
  const std::string checkpoint_path = output + ".checkpoint";

  const std::int64_t cg_first = evaluator.total_iterations();
  const std::int64_t rebuilds_first = list.rebuilds();
  const auto loop0 = std::chrono::steady_clock::now();
  const std::int64_t first = sys.step();
  StepLoop steps(sys, *integrator, evaluator, list, observers, info, request.brownian,
                 !use_rk3 && ex.drift == "midpoint", control, guard, &log);
  const std::string steps_key = "run.steps";
  if (!opt.resume.empty()) {
    const auto it = resume.blobs.find(steps_key);
    if (it != resume.blobs.end()) steps.restore_state(it->second);
  }
  step_state = [&] { return steps.save_state(); };
  ThreadTrial trial(threads.threads,
                    ThreadTrial::should_run(threads.threads, threads.automatic, total_steps - first));
  if (trial.running())
    log << "threads: the first " << ThreadTrial::kSteps << " steps compare " << threads.threads
        << " threads with 1 (results do not depend on it)\n";
  while (sys.step() < total_steps) {
#ifdef _OPENMP
    if (trial.running()) omp_set_num_threads(trial.threads_for_next_step());
#endif
    const auto step0 = std::chrono::steady_clock::now();
    try {
      steps.step(sink);
    } catch (const StepFailure& e) {
      // The loop put the system back to the start of the frame: resumable from there.
      write_checkpoint_now(checkpoint_path);
      log << "steps: " << steps.statistics().text(time_scale, unit_name) << "\n";
      throw Error(std::string(e.what()) + "; checkpoint at that time: " + checkpoint_path);
    }
    if (trial.running() &&
        trial.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - step0).count())) {
#ifdef _OPENMP
      omp_set_num_threads(trial.chosen());
#endif
      log << "threads: " << trial.report() << "\n" << std::flush;
    }
    if (checkpoint_steps > 0 && sys.step() % checkpoint_steps == 0) write_checkpoint_now(checkpoint_path);
  }
  for (auto& o : observers) o->finish(info, sink);
  steps.statistics().write(sink, time_scale, unit_name);
  write_checkpoint_now(checkpoint_path);
  sink.commit();

  const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const std::int64_t done = sys.step() - first;
  log << "done: " << done << " steps in " << format_time(loop_s) << " ("
      << (done > 0 ? std::to_string(1000.0 * loop_s / double(done)) : std::string("-")) << " ms/step, "
      << (done > 0 ? double(evaluator.total_iterations() - cg_first) / double(done) : 0.0)
      << " CG iterations/step (all solves), " << list.rebuilds() - rebuilds_first
      << " neighbour rebuilds); total " << format_time(wall_s) << "\n"
      << "steps: " << steps.statistics().text(time_scale, unit_name) << "; " << steps.overlap_frames()
      << " of " << done << " frames ended with an overlap\n"
      << "results: " << output << "   (fldsim summary " << output << "; /usr/bin/python3 tools/plot_run.py "
      << output << ")\ncheckpoint: " << checkpoint_path << "\n";
  // Frequent rebuilds mean the nodes' Brownian steps are comparable to the skin (the affine shear
  // is already allowed for): a larger skin trades more listed pairs for fewer rebuilds.
  const std::int64_t rebuilds = list.rebuilds() - rebuilds_first;
  if (done >= 100 && 2 * rebuilds > done)
    log << "hint: the neighbour list was rebuilt " << rebuilds << " times in " << done
        << " steps; the Brownian steps are large against run.skin = " << ex.skin
        << " a, and a larger skin (say " << 2.0 * ex.skin << ") may be faster\n";
  return 0;
}

}  // namespace fldsim
