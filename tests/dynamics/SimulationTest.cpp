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
                      "observers:\n  - {plugin: orientation, every: 2}\n  - {plugin: stress, every: 3}\n"
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

}  // namespace
}  // namespace fldsim
