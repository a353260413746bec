#include "run/Simulation.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "config/NumberText.hpp"
#include "dynamics/PairGapStep.hpp"
#include "run/RunUnits.hpp"
#include "run/StartConfiguration.hpp"

namespace fldsim {
namespace {

const char* const kStepStateKey = "run.steps";           // the step control's state in a checkpoint
const char* const kStressStartKey = "run.stress_start";  // the stress solve's CG start
const char* const kHydroStateKey = "hydro.state";        // HydroModel::save_state (e.g. its preconditioner)
const char* const kProbeStateKey = "hydro.probe_state";  // the same of the stress probe's own model

// run.skin: auto (CellNeighbourList::adapt_skin): a list should last about 60 updates, 20 steps of
// Euler-Maruyama with the midpoint drift (three updates a step, one at the state of the last).
// Measured on N = 1000 scenes of the study (bench/README.md, "The neighbour skin"): lists that lasted
// one to three steps cost fused dumbbells at Pe 1 and dt 1e-3 a^2/D0 10-20 % of a step, while a skin
// of 1.2 a cost spheres at Pe 10 (lists of 100 steps) nothing measurable. The floor is the fixed
// default, 0.3 a: thinner shells measured no faster (Pe 1000, free draining at dt 1e-5).
constexpr double kMinAutoSkin = 0.3, kMaxAutoSkin = 2.0;
constexpr int kAutoSkinUpdates = 60;

// The bodies' part of a checkpoint; the one place that knows which System fields a restart sets.
void place_checkpoint_bodies(System& sys, const Checkpoint& c, const std::string& source) {
  if (c.positions.size() != sys.size())
    throw Error(source + ": checkpoint has " + std::to_string(c.positions.size()) + " bodies, experiment " +
                std::to_string(sys.size()));
  sys.positions() = c.positions;
  sys.orientations() = c.orientations;
  sys.displacement() = c.displacement;
  sys.nonaffine_displacement() = c.nonaffine;
  sys.box().set_strain(c.strain);
  sys.set_time(c.time);
  sys.set_step(c.step);
  sys.update_nodes();
}

SimulationParts build_parts(const Experiment& ex, const PluginRegistry& registry, std::ostream& log,
                            const Checkpoint* resume, const std::string& resume_name) {
  SimulationParts parts;
  auto shape = registry.create<Shape>("shape", ex.shape.name, ex.shape.params);
  Physics ph = physics_of(ex);
  const UserTimeUnit unit = user_time_unit(ex, ph);

  // The cubic box edge follows from N and the true volume fraction, or fixes it.
  const double v_body = shape->volume();
  double edge = ex.box_edge;
  ph.volume_fraction = ex.volume_fraction;
  if (edge > 0.0)
    ph.volume_fraction = double(ex.count) * v_body / (edge * edge * edge);
  else
    edge = std::cbrt(double(ex.count) * v_body / ex.volume_fraction);
  parts.system = std::make_unique<System>(shape, std::size_t(ex.count), edge, ph);
  log << "fldsim: " << ex.file << "\n"
      << "system: " << ex.count << " x " << ex.shape.name << " (" << shape->nodes().size()
      << " nodes, volume " << v_body << " a^3), phi = " << ph.volume_fraction << ", box edge " << edge
      << " a\n"
      << "flow: "
      << (ex.brownian ? "Pe = " + format_number(ex.peclet)
                      : std::string("non-Brownian (kT = 0), gammadot = 1"))
      << "; times in " << unit.name << "\n";

  parts.hydro_name = ex.hydro.name;
  parts.hydro = registry.create<HydroModel>("hydro", ex.hydro.name, ex.hydro.params);
  for (const auto& f : ex.forces)
    parts.forces.push_back(registry.create<ForceLaw>("force", f.name, f.params));
  for (std::size_t i = 0; i < ex.observers.size(); ++i) {
    const ObserverBlock& o = ex.observers[i];
    auto ob = registry.create<Observer>("observer", o.plugin.name, o.plugin.params);
    ob->set_schedule(o.every, o.start * unit.scale);
    parts.observers.push_back(ob);
    parts.observer_keys.push_back("observers[" + std::to_string(i) + "]." + o.plugin.name);
  }
  check_observer_needs(ex, *parts.hydro, parts.observers);
  bool need_stress = false;
  for (const auto& o : parts.observers) need_stress = need_stress || o->needs().stress;
  if (need_stress && ex.brownian && ex.brownian_stress == "random_difference" &&
      parts.hydro->provides_stresslets()) {
    // The probe's own copy of the model: same parameters, its solve tolerance (if the model has one).
    Params probe_params = ex.hydro.params;
    if (probe_params.has("tolerance"))
      probe_params.set("tolerance", ParamValue(ex.brownian_stress_tolerance),
                       ParamOrigin{"run.brownian_stress_tolerance", "run.brownian_stress_tolerance"}, false);
    parts.probe_hydro = registry.create<HydroModel>("hydro", ex.hydro.name, probe_params);
  }

  if (resume) {
    if (resume->experiment_yaml != ex.resolved_yaml)
      log << "warning: " << resume_name << " was written by a different experiment file; resuming anyway\n";
    place_checkpoint_bodies(*parts.system, *resume, resume_name);
    log << "start: resumed from " << resume_name << " at step " << resume->step << "\n";
  } else {
    place_start_configuration(*parts.system, ex, log);
  }
  return parts;
}

SimulationSettings settings_of(const Experiment& ex, const UserTimeUnit& unit, ThreadPlan threads) {
  SimulationSettings s;
  s.dt = ex.dt * unit.scale;
  s.total_steps = std::int64_t(std::llround(ex.duration / ex.dt));
  s.integrator = ex.integrator;
  s.drift = ex.drift;
  s.auto_may_average_noise = ex.integrator == "auto" && ex.brownian && !ex.dt_auto && ex.refine == 0 &&
                             !ex.run_params.given("drift") && ex.brownian_stress != "midpoint";
  s.probe_delta = ex.brownian_stress_delta;
  s.skin = ex.skin;
  s.skin_auto = ex.skin_auto;
  s.seed = std::uint64_t(ex.seed);
  s.time_unit = unit.name;
  s.time_scale = unit.scale;
  s.user_dt = ex.dt;
  s.output_path = ex.output;
  s.experiment_yaml = ex.resolved_yaml;
  s.control.adaptive = ex.dt_auto;
  s.control.dt_min = ex.dt_min * unit.scale;
  s.control.tolerance = ex.tolerance;
  s.control.reject_at = ex.reject_at;
  s.control.error_control = ex.error_control;
  s.control.displacement = ex.displacement;
  s.control.gap_step = ex.gap_step;
  s.control.gap_range = ex.gap_range;
  s.control.refine = ex.refine;
  s.guard.max_overlap = ex.max_overlap;
  s.threads = std::move(threads);
  return s;
}

}  // namespace

void check_observer_needs(const Experiment& ex, const HydroModel& hydro,
                          const std::vector<std::shared_ptr<Observer>>& observers) {
  for (std::size_t i = 0; i < observers.size() && i < ex.observers.size(); ++i)
    if (observers[i]->needs().stress && !hydro.provides_stresslets())
      ex.observers[i].plugin.params.fail(
          "plugin", "observer '" + ex.observers[i].plugin.name +
                        "' needs the hydrodynamic stresslets, which hydro plugin '" + ex.hydro.name +
                        "' does not provide (HydroModel::provides_stresslets)");
}

std::unique_ptr<Simulation> Simulation::from_experiment(const Experiment& ex, const PluginRegistry& registry,
                                                        ResultSink& sink, std::ostream& log,
                                                        const Checkpoint* resume,
                                                        const std::string& resume_name) {
  ThreadPlan threads = plan_threads(ex.threads, std::size_t(ex.count));
#ifdef _OPENMP
  omp_set_num_threads(threads.threads);
#endif
  SimulationParts parts = build_parts(ex, registry, log, resume, resume_name);
  SimulationSettings settings =
      settings_of(ex, user_time_unit(ex, parts.system->physics()), std::move(threads));
  auto sim = std::make_unique<Simulation>(std::move(parts), std::move(settings), sink, log);
  if (resume) sim->apply(*resume, resume_name);
  return sim;
}

Simulation::Simulation(SimulationParts parts, SimulationSettings settings, ResultSink& sink,
                       std::ostream& log)
    : parts_(std::move(parts)),
      settings_(std::move(settings)),
      sink_(sink),
      log_(log),
      system_(parts_.system.get()) {
  System& sys = *system_;
  bool need_stress = false;
  for (std::size_t i = 0; i < parts_.observers.size(); ++i) {
    if (!parts_.observers[i]->needs().stress) continue;
    need_stress = true;
    // Refused before any work: a hydrodynamic stress of zero would look like a result.
    if (!parts_.hydro->provides_stresslets())
      throw ConfigError(parts_.observer_keys[i] +
                        ": needs the hydrodynamic stresslets, which hydro plugin '" + parts_.hydro_name +
                        "' does not provide (HydroModel::provides_stresslets)");
  }

  range_ = parts_.hydro->pair_range(sys);
  for (const auto& f : parts_.forces) range_ = std::max(range_, f->range(sys));
  // With no pair range nothing acts between bodies (free draining, no force): overlaps are the
  // ideal gas's own dynamics, not an instability, and the list, holding no pairs, would only see
  // an overlap when a rebuild lists it already deep, which no shorter step can undo.
  if (range_ <= 0.0) settings_.guard.max_overlap = std::numeric_limits<double>::infinity();
  // run.gap_step measures the pairs nearer than gap_range: the list must hold them.
  if (settings_.control.adaptive && settings_.control.gap_step > 0.0)
    range_ = std::max(range_, pair_gap_list_range(sys.shape(), settings_.control.gap_range));
  list_.configure(range_, settings_.skin);
  if (settings_.skin_auto) list_.adapt_skin(kMinAutoSkin, kMaxAutoSkin, kAutoSkinUpdates);
  sys.update_nodes();
  list_.update(sys);

  // Skip what the scene does not need: no Brownian work at kT = 0, no strain coupling without
  // shear, no stresslets unless an observer asks.
  HydroRequest request;
  request.brownian = sys.physics().kT > 0.0;
  request.shear = sys.physics().shear_rate != 0.0;
  request.stresslets = need_stress;
  brownian_ = request.brownian;
  skipped_ = parts_.hydro->configure(sys, request);
  if (!need_stress) skipped_.push_back("no interparticle virial (no stress observer)");
  if (need_stress && request.brownian && !parts_.probe_hydro && settings_.drift != "midpoint")
    skipped_.push_back("no Brownian stress (it needs the midpoint stage: run.drift: midpoint)");

  const bool use_rk3 = settings_.integrator == "rk3" || (settings_.integrator == "auto" && !brownian_);
  // Where the averaged noise is unbiased `auto` takes Leimkuhler-Matthews: no thermal drift, so no
  // midpoint stage to pay for, and for spheres an equilibrium exact to O(dt^2) (docs/time_steps.md,
  // "A constant mobility").
  const std::string lm_refusal = leimkuhler_matthews_refusal(*parts_.hydro, sys);
  const bool auto_lm = settings_.auto_may_average_noise && lm_refusal.empty();
  const bool use_lm = settings_.integrator == "leimkuhler_matthews" || auto_lm;
  if (use_lm && !lm_refusal.empty()) throw ConfigError("run.integrator: " + lm_refusal);
  if (use_lm)
    integrator_ = std::make_unique<LeimkuhlerMatthews>(settings_.seed, sys.size());
  else if (use_rk3 && brownian_)
    integrator_ = std::make_unique<RungeKutta3>(settings_.seed, sys.size());
  else if (use_rk3)
    integrator_ = std::make_unique<RungeKutta3>(sys.size());
  else
    integrator_ = std::make_unique<EulerMaruyama>(
        settings_.seed, request.brownian,
        settings_.drift == "none" ? DriftScheme::None : DriftScheme::Midpoint, sys.size());
  evaluator_ = std::make_unique<VelocityEvaluator>(parts_.hydro, parts_.forces, list_, sys.size());

  settings_.control.frame = settings_.dt;
  settings_.control.order = integrator_->error_order();
  settings_.control.displacement_order = brownian_ ? 1.0 : 2.0;
  const StepControlSettings& control = settings_.control;
  log_ << "hydro: " << parts_.hydro_name << "; integrator: " << integrator_->describe() << "; ";
  if (control.adaptive) {
    log_ << "dt: auto (adaptive, ";
    if (control.error_control) log_ << "local error ~ " << control.tolerance << " a, ";
    if (control.displacement > 0.0) log_ << "rms node step <= " << control.displacement << " a, ";
    if (control.gap_step > 0.0)
      log_ << "rms gap step of pairs nearer than " << control.gap_range << " a <= " << control.gap_step
           << " a, ";
    log_ << "steps: " << (control.error_control ? "dyadic" : "equal")
         << " pieces of dt_max = " << settings_.user_dt << " " << settings_.time_unit << "), "
         << settings_.total_steps << " frames of dt_max";
  } else
    log_ << "dt = " << settings_.user_dt << " " << settings_.time_unit << ", " << settings_.total_steps
         << " steps";
  if (control.refine > 0)
    log_ << ", each in " << (1 << control.refine) << " equal steps on its Brownian path (run.refine)";
  if (std::isinf(settings_.guard.max_overlap))
    log_ << "; guard: overlaps allowed (no pair interaction)";
  else
    log_ << "; guard: overlap > " << settings_.guard.max_overlap << " a rejects a step";
  log_ << "; pair range " << range_ << " a + skin " << (settings_.skin_auto ? "auto, from " : "")
       << settings_.skin << " a\n"
       << "threads: " << settings_.threads.threads << " (" << settings_.threads.reason << ")\n";
  for (const auto& w : settings_.threads.warnings) log_ << "warning: " << w << "\n";
  if (auto_lm)
    log_ << "note: integrator auto took Leimkuhler-Matthews: a pair-free mobility without "
            "translation-rotation coupling ("
         << parts_.hydro_name
         << "), so no thermal drift and no midpoint stage; "
            "run.integrator: euler_maruyama for the midpoint scheme (docs/time_steps.md, \"A constant "
            "mobility\")\n";
  if (use_rk3 && brownian_)
    log_ << "note: rk3 with Brownian motion is the paper's scheme; near contact its third stage, at "
            "x - dt k1 + 2 dt k2, can step back to where lubrication is weaker and overlap pairs more "
            "than the default midpoint scheme; with FLD at Pe <= 1 and dt 1e-3 it fails within a strain "
            "(docs/time_steps.md, \"Integrators\")\n";
  for (const auto& s : skipped_) log_ << "skipped: " << s << "\n";

  info_.total_steps = settings_.total_steps;
  info_.dt = settings_.dt;
  info_.time_unit = settings_.time_unit;
  info_.time_scale = settings_.time_scale;
  info_.output_path = settings_.output_path;
  info_.seed = settings_.seed;
  for (auto& o : parts_.observers) o->begin(sys, info_, sink_);
  steps_ = std::make_unique<StepLoop>(sys, *integrator_, *evaluator_, list_, parts_.observers, info_,
                                      brownian_, !use_rk3 && !use_lm && settings_.drift == "midpoint",
                                      settings_.control, settings_.guard, &log_);
  if (parts_.probe_hydro) {
    probe_ = std::make_unique<BrownianStressProbe>(parts_.probe_hydro, sys, range_, settings_.skin,
                                                   settings_.probe_delta, settings_.seed);
    steps_->use_brownian_stress_probe(probe_.get());
    log_ << "Brownian stress: random finite difference, delta " << settings_.probe_delta
         << " a (two extra solves on each stress sample)\n";
  }
  // Components that put lines in the run log (fldsim::RunNotes, API 5.3).
  const auto listen = [this](Component& c, std::string label) {
    if (RunNotes* n = run_notes_of(c)) notes_.push_back({std::move(label), n});
  };
  listen(*parts_.hydro, "hydro " + parts_.hydro_name);
  if (parts_.probe_hydro) listen(*parts_.probe_hydro, "stress probe's hydro " + parts_.hydro_name);
  for (auto& f : parts_.forces) listen(*f, "force " + f->plugin_name());
  for (auto& o : parts_.observers) listen(*o, "observer " + o->plugin_name());
}

void Simulation::log_notes() {
  for (auto& [label, source] : notes_)
    for (const std::string& line : source->take_notes())
      log_ << "note: t = " << log_number(system_->time() / settings_.time_scale) << " " << settings_.time_unit
           << ", " << label << ": " << line << "\n"
           << std::flush;
}

// capture() and apply() are the one place that lists the run state a restart needs: the
// bodies, the clock and strain, the solver's warm starts (the step's and the stress sample's),
// each observer's accumulators, the step control's state (the adaptive proposal and the step
// statistics; a frame's end leaves no bridged noise pending), and the hydro model's own state
// and the stress probe's (the matrices their carried preconditioners were built from).
Checkpoint Simulation::capture() const {
  const System& sys = *system_;
  Checkpoint c;
  c.positions = sys.positions();
  c.orientations = sys.orientations();
  c.displacement = sys.displacement();
  c.nonaffine = sys.nonaffine_displacement();
  c.time = sys.time();
  c.strain = sys.box().strain();
  c.box_edge = sys.box().edge();
  c.step = sys.step();
  c.seed = settings_.seed;
  c.experiment_yaml = settings_.experiment_yaml;
  c.warm_start = evaluator_->warm_start();
  for (std::size_t i = 0; i < parts_.observers.size(); ++i) {
    std::vector<double> state = parts_.observers[i]->save_state();
    if (!state.empty()) c.blobs[parts_.observer_keys[i]] = std::move(state);
  }
  c.blobs[kStepStateKey] = steps_->save_state();
  c.blobs[kStressStartKey] = steps_->stress_start();
  if (std::vector<double> hydro = parts_.hydro->save_state(); !hydro.empty())
    c.blobs[kHydroStateKey] = std::move(hydro);
  if (parts_.probe_hydro)
    if (std::vector<double> probe = parts_.probe_hydro->save_state(); !probe.empty())
      c.blobs[kProbeStateKey] = std::move(probe);
  return c;
}

void Simulation::apply(const Checkpoint& c, const std::string& source) {
  place_checkpoint_bodies(*system_, c, source);
  list_.update(*system_);
  // The warm start only changes the CG iterate, but the last bits of the solution depend on it.
  if (c.warm_start.size() == evaluator_->warm_start().size()) evaluator_->warm_start() = c.warm_start;
  for (std::size_t i = 0; i < parts_.observers.size(); ++i) {
    const auto it = c.blobs.find(parts_.observer_keys[i]);
    if (it != c.blobs.end()) {
      parts_.observers[i]->restore_state(it->second);
    } else if (!parts_.observers[i]->save_state().empty()) {
      log_ << "warning: " << source << " holds no state for " << parts_.observer_keys[i]
           << ": its averages start afresh\n";
    }
  }
  if (const auto start = c.blobs.find(kStressStartKey); start != c.blobs.end())
    steps_->restore_stress_start(start->second);
  // Without it (a checkpoint of an older build) the model starts without a carried preconditioner:
  // the run continues correctly, equal to the uninterrupted one to the CG tolerance, not bit for bit.
  for (const auto& [key, model] :
       {std::pair{kHydroStateKey, parts_.hydro.get()}, std::pair{kProbeStateKey, parts_.probe_hydro.get()}}) {
    const auto state = c.blobs.find(key);
    if (!model || state == c.blobs.end()) continue;
    try {
      model->restore_state(state->second);
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
  }
  const auto it = c.blobs.find(kStepStateKey);
  if (it != c.blobs.end()) {
    try {
      steps_->restore_state(it->second);
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
  }
}

void Simulation::start_stepping() {
  first_step_ = system_->step();
  first_iterations_ = evaluator_->total_iterations();
  first_rebuilds_ = list_.rebuilds();
  const ThreadPlan& plan = settings_.threads;
  trial_.emplace(plan.threads,
                 ThreadTrial::should_run(plan.threads, plan.automatic, settings_.total_steps - first_step_));
  if (trial_->running())
    log_ << "threads: the first " << ThreadTrial::kSteps << " steps compare " << plan.threads
         << " threads with 1 (results do not depend on it)\n";
}

void Simulation::step() {
  if (!trial_) start_stepping();
  if (!trial_->running()) {
    steps_->step(sink_);
    log_notes();
    return;
  }
  // Results do not depend on the thread count, so the trial times real steps.
#ifdef _OPENMP
  omp_set_num_threads(trial_->threads_for_next_step());
#endif
  const auto t0 = std::chrono::steady_clock::now();
  steps_->step(sink_);
  log_notes();
  if (trial_->record(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count())) {
#ifdef _OPENMP
    omp_set_num_threads(trial_->chosen());
#endif
    log_ << "threads: " << trial_->report() << "\n" << std::flush;
  }
}

void Simulation::run() {
  while (!finished()) step();
}

void Simulation::finish() {
  if (finished_observers_) return;
  finished_observers_ = true;
  for (auto& o : parts_.observers) o->finish(info_, sink_);
  steps_->statistics().write(sink_, settings_.time_scale, settings_.time_unit);
}

std::string Simulation::step_report() const {
  return steps_->statistics().text(settings_.time_scale, settings_.time_unit) + "; " +
         std::to_string(steps_->overlap_frames()) + " of " + std::to_string(steps_taken()) +
         " frames ended with an overlap";
}

std::int64_t Simulation::steps_taken() const {
  return trial_ ? system_->step() - first_step_ : 0;
}
std::int64_t Simulation::cg_iterations_taken() const {
  return trial_ ? evaluator_->total_iterations() - first_iterations_ : 0;
}
std::int64_t Simulation::rebuilds_taken() const {
  return trial_ ? list_.rebuilds() - first_rebuilds_ : 0;
}
double Simulation::neighbour_skin() const {
  return list_.skin();
}

}  // namespace fldsim
