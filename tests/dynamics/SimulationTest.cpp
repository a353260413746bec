// The Simulation that every front end builds: capture() at some step and apply() to a freshly
// assembled Simulation continues bit for bit like the uninterrupted one (exact oracle: the same
// arithmetic on the same state). This is what `fldsim run --resume` relies on; here it is checked
// without files, through the object the Python module and the sweep runner use too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "observers/FakeSink.hpp"
#include "run/Simulation.hpp"

namespace fldsim {
namespace {

namespace fs = std::filesystem;

std::string experiment_file() {
  const fs::path d = fs::temp_directory_path() / ("fldsim-simulation-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path f = d / "e.yaml";
  std::ofstream(f) << "system:\n"
                      "  shape: {plugin: dicolloid, c: 0.2}\n"
                      "  count: 27\n"
                      "  volume_fraction: 0.3\n"
                      "  init: {method: monte_carlo, seed: 3, sweeps: 50}\n"
                      "flow: {peclet: 5}\n"
                      "hydro: {plugin: fld}\n"
                      "forces:\n  - {plugin: repulsion}\n"
                      "run: {dt: 0.001, duration: 0.02, seed: 9, threads: 1}\n"
                      "observers:\n  - {plugin: orientation, every: 2}\n  - {plugin: stress, every: 1}\n"
                      "  - {plugin: diffusion, every: 2, max_lag: 0.01}\n"
                      "output: unused.h5\n";
  return f.string();
}

struct Built {
  std::unique_ptr<PluginRegistry> registry;
  Experiment ex;
  test::FakeSink sink;
  std::ostringstream log;
  std::unique_ptr<Simulation> sim;
};

std::unique_ptr<Built> build(const std::string& file) {
  auto b = std::make_unique<Built>();
  b->ex = read_experiment(file, {}, b->registry);
  b->sim = Simulation::from_experiment(b->ex, *b->registry, b->sink, b->log);
  return b;
}

void expect_same_state(const Checkpoint& a, const Checkpoint& b) {
  ASSERT_EQ(a.step, b.step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.strain, b.strain);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << "body " << i;
    EXPECT_EQ(a.orientations[i].coeffs(), b.orientations[i].coeffs()) << "body " << i;
    EXPECT_EQ(a.displacement[i], b.displacement[i]) << "body " << i;
    EXPECT_EQ(a.nonaffine[i], b.nonaffine[i]) << "body " << i;
  }
  EXPECT_EQ(a.warm_start, b.warm_start);
  EXPECT_EQ(a.blobs, b.blobs);
}

TEST(Simulation, RunsTheExperimentToItsEnd) {
  auto b = build(experiment_file());
  EXPECT_EQ(b->sim->settings().total_steps, 20);
  b->sim->run();
  EXPECT_TRUE(b->sim->finished());
  EXPECT_EQ(b->sim->system().step(), 20);
  EXPECT_EQ(b->sim->steps_taken(), 20);
  b->sim->finish();
  // The observers wrote their steady-state results.
  EXPECT_TRUE(b->sink.scalars.count("results/orientation/S_xx")) << b->log.str();
}

// The stress is sampled every step, so the stress probe's own hydro model carries its
// preconditioner from sample to sample: the test fails if either model's checkpoint state
// (HydroModel::save_state) is not restored (checked for both, 4 December 2026).
TEST(Simulation, CaptureThenApplyContinuesBitForBit) {
  const std::string file = experiment_file();
  auto whole = build(file);
  for (int k = 0; k < 9; ++k) whole->sim->step();
  const Checkpoint middle = whole->sim->capture();
  whole->sim->run();
  const Checkpoint end = whole->sim->capture();

  auto resumed = build(file);  // a fresh Monte Carlo start, then the captured state
  resumed->sim->apply(middle);
  EXPECT_EQ(resumed->sim->system().step(), 9);
  resumed->sim->run();
  expect_same_state(end, resumed->sim->capture());
  EXPECT_EQ(resumed->log.str().find("start afresh"), std::string::npos) << resumed->log.str();
}

// run.skin only decides how often the neighbour list is rebuilt: the listed pairs within the pair
// range are the same, so a run at `skin: auto` (which grows the skin here, where a 0.3 a list lasts a
// step or two) ends bit for bit where the run at a fixed 0.3 a does, stress and hydro state included.
TEST(Simulation, ResultsDoNotDependOnTheNeighbourSkin) {
  const fs::path d = fs::temp_directory_path() / ("fldsim-skin-" + std::to_string(::getpid()));
  fs::create_directories(d);
  auto file = [&](const std::string& skin) {
    const fs::path f = d / ("skin-" + skin + ".yaml");
    std::ofstream(f) << "system:\n"
                        "  shape: {plugin: dicolloid, c: 1}\n"
                        "  count: 64\n"
                        "  volume_fraction: 0.3\n"
                        "  init: {method: monte_carlo, seed: 5}\n"
                        "flow: {peclet: 1}\n"
                        "hydro: {plugin: fld}\n"
                        "forces:\n  - {plugin: repulsion}\n"
                        "run: {dt: 0.002, duration: 0.2, seed: 9, threads: 1, skin: "
                     << skin
                     << "}\n"
                        "observers:\n  - {plugin: stress, every: 1}\n"
                        "output: unused.h5\n";
    return f.string();
  };
  auto fixed = build(file("0.3"));
  auto adaptive = build(file("auto"));
  fixed->sim->run();
  adaptive->sim->run();
  expect_same_state(fixed->sim->capture(), adaptive->sim->capture());
  EXPECT_GT(adaptive->sim->neighbour_skin(), 0.5) << adaptive->log.str();
  EXPECT_LT(adaptive->sim->rebuilds_taken(), fixed->sim->rebuilds_taken() / 2);
  EXPECT_EQ(fixed->sim->neighbour_skin(), 0.3);
}

// A third-party hydro model that leaves the stresslets out: it says so, and asking anyway throws.
class NoStressletHydro : public HydroModel {
 public:
  double pair_range(const System&) const override { return 0.0; }
  std::vector<std::string> configure(const System&, const HydroRequest&) override { return {}; }
  void assemble(const System&, const NodePairList&) override {}
  void brownian_force(const System& s, const NodePairList&, const RandomStream&, double,
                      double* FB) override {
    std::fill(FB, FB + 6 * s.size(), 0.0);
  }
  void solve(const System& s, const double* F, double* dU) override { std::copy(F, F + 6 * s.size(), dU); }
  bool provides_stresslets() const override { return false; }
};

// The parts of the test experiment with its hydro model replaced by NoStressletHydro; the
// observers listed by index (0 orientation, 1 stress).
SimulationParts parts_without_stresslets(const Built& b, const std::vector<std::size_t>& observers) {
  SimulationParts parts;
  auto shape = b.registry->create<Shape>("shape", b.ex.shape.name, b.ex.shape.params);
  parts.system = std::make_unique<System>(shape, 8, 10.0, b.sim->system().physics());
  for (std::size_t i = 0; i < 8; ++i)
    parts.system->positions()[i] = Vec3(2.5 + 5.0 * (i % 2), 2.5 + 5.0 * (i / 2 % 2), 2.5 + 5.0 * (i / 4));
  parts.system->update_nodes();
  parts.hydro_name = "no_stresslets";
  parts.hydro = std::make_shared<NoStressletHydro>();
  for (std::size_t i : observers) {
    const auto& o = b.ex.observers[i];
    parts.observers.push_back(b.registry->create<Observer>("observer", o.plugin.name, o.plugin.params));
    parts.observer_keys.push_back("observers[" + std::to_string(i) + "]." + o.plugin.name);
  }
  return parts;
}

TEST(Simulation, RefusesAStressObserverWhenTheHydroModelHasNoStresslets) {
  auto b = build(experiment_file());
  SimulationSettings settings;
  settings.dt = 1e-3;
  settings.total_steps = 1;
  test::FakeSink sink;
  std::ostringstream log;
  try {
    Simulation sim(parts_without_stresslets(*b, {0, 1}), settings, sink, log);
    FAIL() << "a stress observer ran with a model that provides no stresslets";
  } catch (const ConfigError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "observers[1].stress: needs the hydrodynamic stresslets, which hydro plugin 'no_stresslets' does "
        "not provide (HydroModel::provides_stresslets)");
  }
  // Without the stress observer the same model runs.
  Simulation sim(parts_without_stresslets(*b, {0}), settings, sink, log);
  sim.step();
  EXPECT_EQ(sim.system().step(), 1);
  // From an experiment the refusal names the observer block's file:line:col (line 13: the stress
  // observer of experiment_file()), as `fldsim check` prints it.
  std::vector<std::shared_ptr<Observer>> observers;
  for (const auto& o : b->ex.observers)
    observers.push_back(b->registry->create<Observer>("observer", o.plugin.name, o.plugin.params));
  NoStressletHydro no_stresslets;
  try {
    check_observer_needs(b->ex, no_stresslets, observers);
    FAIL() << "check_observer_needs accepted a stress observer without stresslets";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              b->ex.file +
                  ":13:5: observers[1].plugin: observer 'stress' needs the hydrodynamic "
                  "stresslets, which hydro plugin 'fld' does not provide "
                  "(HydroModel::provides_stresslets)");
  }
  observers.erase(observers.begin() + 1);
  Experiment without_stress = b->ex;
  without_stress.observers.erase(without_stress.observers.begin() + 1);
  EXPECT_NO_THROW(check_observer_needs(without_stress, no_stresslets, observers));
  // And nobody gets a silent zero: asking the model anyway throws.
  NoStressletHydro model;
  EXPECT_THROW(model.stresslet_sum(sim.system(), NodePairList{}, nullptr), Error);
}

// A component's RunNotes lines reach the run log once each, after the step in which they were
// noted, with the time and the component (API 5.3); components without RunNotes are not asked.
class NotingHydro : public NoStressletHydro, public RunNotes {
 public:
  void assemble(const System& s, const NodePairList&) override {
    if (s.step() == 2 && !noted_) {  // during the third step
      notes_.push_back("switched to plan B");
      noted_ = true;
    }
  }
  std::vector<std::string> take_notes() override {
    std::vector<std::string> out;
    out.swap(notes_);
    return out;
  }

 private:
  std::vector<std::string> notes_;
  bool noted_ = false;
};

TEST(Simulation, WritesTheComponentsRunNotesToTheLog) {
  auto b = build(experiment_file());
  SimulationSettings settings;
  settings.dt = 1e-3;
  settings.total_steps = 5;
  test::FakeSink sink;
  std::ostringstream log;
  SimulationParts parts = parts_without_stresslets(*b, {0});
  parts.hydro_name = "noting";
  parts.hydro = std::make_shared<NotingHydro>();
  Simulation sim(std::move(parts), settings, sink, log);
  sim.run();
  const std::string text = log.str(), line = "note: t = 0.003 a^2/D0, hydro noting: switched to plan B\n";
  const std::size_t at = text.find(line);
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_EQ(text.find("note:", at + 1), std::string::npos) << text;
}

// Free draining: `integrator: auto` takes Leimkuhler-Matthews at fixed steps for spheres and
// homonuclear dicolloids (docs/time_steps.md, "A constant mobility") and keeps Euler-Maruyama where
// run.drift is given or unequal nodes couple translation and rotation; the averaged noise resumes
// bit for bit like any other.
std::string free_draining_file(const std::string& name, const std::string& shape,
                               const std::string& run_extra) {
  const fs::path d = fs::temp_directory_path() / ("fldsim-simulation-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path f = d / (name + ".yaml");
  std::ofstream(f)
      << "system:\n  shape: " << shape
      << "\n  count: 27\n  volume_fraction: 0.3\n  init: {method: monte_carlo, seed: 3, sweeps: 50}\n"
         "flow: {peclet: 0}\nhydro: {plugin: free_draining}\nforces:\n  - {plugin: repulsion}\n"
         "run: {dt: 2.5e-5, duration: 5.0e-4, time_unit: diffusive, seed: 9, threads: 1"
      << run_extra << "}\noutput: unused.h5\n";
  return f.string();
}

TEST(Simulation, AutoTakesLeimkuhlerMatthewsWhereTheAveragedNoiseIsUnbiased) {
  const std::string lm = "integrator: Leimkuhler-Matthews";
  auto spheres = build(free_draining_file("fd-auto", "{plugin: sphere}", ""));
  EXPECT_NE(spheres->log.str().find(lm), std::string::npos) << spheres->log.str();
  EXPECT_NE(spheres->log.str().find("note: integrator auto took Leimkuhler-Matthews"), std::string::npos);
  auto drift = build(free_draining_file("fd-drift", "{plugin: sphere}", ", drift: none"));
  EXPECT_NE(drift->log.str().find("integrator: Euler-Maruyama without thermal drift"), std::string::npos)
      << drift->log.str();
  auto homonuclear = build(free_draining_file("fd-dicolloid", "{plugin: dicolloid, c: 0.2}", ""));
  EXPECT_NE(homonuclear->log.str().find(lm), std::string::npos) << homonuclear->log.str();
  // Unequal nodes couple translation and rotation: the averaged noise would drift.
  auto heteronuclear = build(free_draining_file("fd-hetero", "{plugin: dicolloid, a: 1, b: 0.6, c: 1}", ""));
  EXPECT_NE(heteronuclear->log.str().find("integrator: Euler-Maruyama with midpoint thermal drift"),
            std::string::npos)
      << heteronuclear->log.str();
}

TEST(Simulation, LeimkuhlerMatthewsCaptureThenApplyContinuesBitForBit) {
  const std::string file = free_draining_file("fd-resume", "{plugin: sphere}", "");
  auto whole = build(file);
  for (int k = 0; k < 9; ++k) whole->sim->step();
  const Checkpoint middle = whole->sim->capture();
  whole->sim->run();
  const Checkpoint end = whole->sim->capture();
  auto resumed = build(file);
  resumed->sim->apply(middle);
  resumed->sim->run();
  expect_same_state(end, resumed->sim->capture());
}

}  // namespace
}  // namespace fldsim
