// fldsim_bench_parts: Google Benchmark of the parts of one time step, on N = 1000 bodies:
// spheres and homonuclear dicolloids (a = b = 1, c = 0.2) at phi = 0.3 and 0.5, Pe = 10, FLD.
// The scene index (the benchmark argument) is listed by kScenes. Each benchmark reports the time
// of one call; counters give the work done (pairs, CG iterations).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "BenchScene.hpp"
#include "dynamics/BodyMotion.hpp"
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"

using namespace fldsim;
using namespace fldsim::bench;

namespace {

struct SceneChoice {
  const char* shape;
  double phi;
};
constexpr SceneChoice kScenes[] = {{"sphere", 0.3}, {"sphere", 0.5}, {"dicolloid", 0.3}, {"dicolloid", 0.5}};

// A scene after a few real steps (so velocities, pairs and the warm start are those of a run),
// built once per scene and shared by all benchmarks. A stress observer that is never due makes
// the model keep what stresslets need, as in a run with a stress observer.
BenchScene& scene(int index) {
  static std::map<int, std::unique_ptr<BenchScene>> scenes;
  auto& s = scenes[index];
  if (!s) {
    SceneSpec spec;
    spec.shape = kScenes[index].shape;
    spec.phi = kScenes[index].phi;
    spec.count = 1000;
    spec.c = 0.2;
    spec.peclet = 10.0;
    spec.mc_sweeps = 50;
    spec.lattice = false;  // the same MC starts as the whole-step table
    spec.cache_dir = FLDSIM_BENCH_CACHE_DIR;
    s = std::make_unique<BenchScene>(spec, std::vector<ObserverSpec>{{"stress", 1000000000}});
    for (int k = 0; k < 3; ++k) s->step();
    s->evaluator().prepare(s->system(), true);
  }
  return *s;
}

void label(benchmark::State& state, int index) {
  state.SetLabel(std::string(kScenes[index].shape) +
                 " phi=" + std::to_string(kScenes[index].phi).substr(0, 3));
}

void BM_NeighbourRefresh(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  // A strain change of 1e-9 each time: an update at an unchanged state recomputes nothing (it
  // remembers the positions and strain of the last), so this times the full refresh of a stage.
  auto& box = s.system().box();
  const double strain = box.strain();
  bool odd = false;
  for (auto _ : state) {
    box.set_strain(strain + (odd ? 1e-9 : 0.0));
    odd = !odd;
    benchmark::DoNotOptimize(s.neighbours().update(s.system()));
  }
  box.set_strain(strain);
  s.neighbours().update(s.system());
  state.counters["node_pairs"] = double(s.neighbours().pairs().pairs().size());
  label(state, int(state.range(0)));
}

void BM_NeighbourRebuild(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  const double range = s.neighbours().pairs().range();
  for (auto _ : state) {
    s.neighbours().configure(range, 0.3);  // forgets the list: the next update rebuilds
    s.neighbours().update(s.system());
  }
  state.counters["node_pairs"] = double(s.neighbours().pairs().pairs().size());
  label(state, int(state.range(0)));
}

void BM_RepulsionForces(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  std::vector<double> wrench(6 * s.system().size());
  for (auto _ : state) {
    std::fill(wrench.begin(), wrench.end(), 0.0);
    for (const auto& f : s.forces()) f->add(s.system(), s.neighbours().pairs(), wrench.data(), nullptr);
    benchmark::DoNotOptimize(wrench.data());
  }
  label(state, int(state.range(0)));
}

// ResistanceModel::assemble through the fld plugin: pair selection and rows, R_0, R_delta into
// the block-sparse matrix, R_FE:E_inf, the preconditioner's factorisation. Each call is the first
// assembly of a new step (the factor is never carried across steps), so each factors.
void BM_LubricationAssemble(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  const std::int64_t step = s.system().step();
  for (auto _ : state) {
    s.system().set_step(s.system().step() + 1);
    s.hydro_plugin()->assemble(s.system(), s.neighbours().pairs());
  }
  s.system().set_step(step);
  state.counters["lub_pairs"] = double(s.hydro_plugin()->last_solve().pairs);
  label(state, int(state.range(0)));
}

// The same without the factorisation: the second assembly of a step (the midpoint stage's, which
// reuses the step's factor: the configuration is the same, so refactor_threshold never trips).
// Time / lub_pairs = the assembly
// cost per lubricated pair block.
void BM_LubricationAssembleNoFactor(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  const std::int64_t step = s.system().step();
  for (auto _ : state) {
    state.PauseTiming();
    s.system().set_step(s.system().step() + 1);
    s.hydro_plugin()->assemble(s.system(), s.neighbours().pairs());
    state.ResumeTiming();
    s.hydro_plugin()->assemble(s.system(), s.neighbours().pairs());
  }
  s.system().set_step(step);
  state.counters["lub_pairs"] = double(s.hydro_plugin()->last_solve().pairs);
  label(state, int(state.range(0)));
}

void BM_BrownianForces(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  s.hydro_plugin()->assemble(s.system(), s.neighbours().pairs());
  std::vector<double> FB(6 * s.system().size());
  std::uint64_t step = 0;
  for (auto _ : state) {
    s.hydro_plugin()->brownian_force(s.system(), s.neighbours().pairs(),
                                     RandomStream(1, RandomPurpose::BodyNoise, ++step), s.dt(), FB.data());
    benchmark::DoNotOptimize(FB.data());
  }
  label(state, int(state.range(0)));
}

// The fld model built directly from the shared hydro code (same settings as the plugin's
// defaults), for the matrix and the preconditioned CG on their own.
struct DirectModel {
  hydro::ResistanceModel model;
  std::vector<double> F, dU;
  explicit DirectModel(BenchScene& s) : model(settings()) {
    HydroRequest req;
    model.configure(s.system(), req);
    model.assemble(s.system(), s.neighbours().pairs());
    F.assign(6 * s.system().size(), 0.0);
    dU.assign(F.size(), 0.0);
    s.hydro_plugin()->brownian_force(s.system(), s.neighbours().pairs(),
                                     RandomStream(7, RandomPurpose::BodyNoise, 0), s.dt(), F.data());
  }
  static hydro::ModelSettings settings() {
    hydro::ModelSettings m = hydro::read_lubrication_params(plugin_params("hydro", "fld", "{}"));
    m.lubrication = true;
    m.fit = hydro::IsotropicFit::Fldsim;
    m.isotropic = hydro::IsotropicForm::Sphere;
    return m;
  }
};

void BM_BlockSparseMatVec(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  DirectModel d(s);
  const BlockSparseMatrix& A = d.model.resistance();
  std::vector<double> y(A.size());
  for (auto _ : state) {
    A.multiply(d.F.data(), y.data());
    benchmark::DoNotOptimize(y.data());
  }
  label(state, int(state.range(0)));
}

// PCG from a zero start (cold) and from the solution of the previous right-hand side (warm; the
// run warm-starts each solve from the last dU).
void pcg_solve(benchmark::State& state, bool warm) {
  BenchScene& s = scene(int(state.range(0)));
  DirectModel d(s);
  std::int64_t iterations = 0, solves = 0;
  std::vector<double> previous(d.dU.size(), 0.0);
  if (warm) d.model.solve(s.system(), d.F.data(), previous.data());
  // Warm: the right-hand side of the next step differs by fresh noise; a second draw stands in.
  std::vector<double> F2(d.F.size());
  s.hydro_plugin()->brownian_force(s.system(), s.neighbours().pairs(),
                                   RandomStream(8, RandomPurpose::BodyNoise, 0), s.dt(), F2.data());
  for (auto _ : state) {
    d.dU = previous;
    d.model.solve(s.system(), F2.data(), d.dU.data());
    iterations += d.model.last_solve().iterations;
    ++solves;
  }
  state.counters["cg_iterations"] = double(iterations) / double(solves);
  label(state, int(state.range(0)));
}
void BM_PCGSolveCold(benchmark::State& state) {
  pcg_solve(state, false);
}
void BM_PCGSolveWarm(benchmark::State& state) {
  pcg_solve(state, true);
}

// The midpoint drift stage: move half a step from the base, refresh pairs and forces, assemble
// and solve again with the same Brownian force (TimeIntegrator.cpp). This is all the extra work
// the thermal drift costs per step.
void BM_MidpointDriftStage(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  System& sys = s.system();
  BodySnapshot base;
  base.save(sys);
  s.evaluator().prepare(sys, false);
  s.evaluator().draw_brownian(sys, RandomStream(3, RandomPurpose::BodyNoise, 0), s.dt());
  s.evaluator().solve(sys, true);
  std::vector<double> U(s.evaluator().velocity(), s.evaluator().velocity() + 6 * sys.size());
  const std::vector<double> first_dU = s.evaluator().warm_start();
  s.hydro().reset_times();
  const std::int64_t step = sys.step();
  for (auto _ : state) {
    // As in a step, the midpoint solve starts from the base solve's dU (not from its own last
    // answer), and its assembly is the step's second (the preconditioner built at the step's
    // base assembly is reused under the default refactor_threshold).
    state.PauseTiming();
    s.evaluator().warm_start() = first_dU;
    base.restore(sys);
    sys.set_step(sys.step() + 1);
    s.evaluator().prepare(sys, false);
    state.ResumeTiming();
    move_from(sys, base, U.data(), 0.5 * s.dt());
    s.evaluator().prepare(sys, false);
    s.evaluator().solve(sys, true);
  }
  state.counters["cg_iterations"] =
      double(s.hydro().times().cg_iterations) / double(s.hydro().times().solves);
  base.restore(sys);
  sys.set_step(step);
  s.neighbours().update(sys);
  label(state, int(state.range(0)));
}

void BM_Stresslets(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  s.evaluator().prepare(s.system(), true);
  s.evaluator().solve(s.system(), false);
  for (auto _ : state)
    benchmark::DoNotOptimize(s.hydro_plugin()->stresslet_sum(s.system(), s.neighbours().pairs(),
                                                             s.evaluator().relative_velocity()));
  label(state, int(state.range(0)));
}

// One observer's sample() on the scene's current step (stress pieces as the core builds them).
void observer_sample(benchmark::State& state, const std::string& plugin, const std::string& yaml) {
  BenchScene& s = scene(int(state.range(0)));
  auto ob = registry().create<Observer>("observer", plugin, plugin_params("observer", plugin, yaml));
  DiscardingSink sink;
  ob->begin(s.system(), s.run_info(), sink);
  StressPieces stress;
  stress.interparticle = -s.evaluator().virial();
  const StepView view{s.system(),
                      s.neighbours().pairs(),
                      s.run_info(),
                      s.evaluator().velocity(),
                      s.evaluator().force(),
                      &stress,
                      s.evaluator().stats(),
                      s.neighbours().min_gap(s.system())};
  // A new step number each call: the trajectory observer writes at most one frame per step.
  const std::int64_t step = s.system().step();
  for (auto _ : state) {
    s.system().set_step(s.system().step() + 1);
    ob->sample(view, sink);
  }
  s.system().set_step(step);
  label(state, int(state.range(0)));
}
void BM_ObserveOrientation(benchmark::State& st) {
  observer_sample(st, "orientation", "{}");
}
void BM_ObservePairDistribution(benchmark::State& st) {
  observer_sample(st, "pair_distribution", "{range: 5, bins: 100}");
}
void BM_ObserveStress(benchmark::State& st) {
  observer_sample(st, "stress", "{}");
}
void BM_ObserveDiffusion(benchmark::State& st) {
  observer_sample(st, "diffusion", "{max_lag: 1}");
}
void BM_ObserveTrajectory(benchmark::State& st) {
  observer_sample(st, "trajectory", "{}");
}

// The whole step (two evaluations: base and midpoint), for the parts to be read against.
void BM_WholeStep(benchmark::State& state) {
  BenchScene& s = scene(int(state.range(0)));
  for (auto _ : state) s.step();
  label(state, int(state.range(0)));
}

// Wall time of one OpenMP barrier with two threads: the price of every parallel loop of a
// multi-threaded step (about ten per CG iteration) and the scale of the cross-thread waits of the
// IC(0) factorisation and sweeps. Where it is large
// (1.5 us measured on a 2-vCPU cloud VM; typically a few tenths of a microsecond on one socket) a second
// thread does not pay at N = 1000, and ThreadTrial keeps one thread.
void BM_OmpBarrier(benchmark::State& state) {
  constexpr int kBarriers = 1000;
  for (auto _ : state) {
#pragma omp parallel num_threads(2)
    for (int i = 0; i < kBarriers; ++i) {
#pragma omp barrier
    }
  }
  state.counters["barriers"] = kBarriers;
}

void scenes(benchmark::internal::Benchmark* b) {
  for (int i = 0; i < int(std::size(kScenes)); ++i) b->Arg(i);
  b->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_NeighbourRefresh)->Apply(scenes);
BENCHMARK(BM_NeighbourRebuild)->Apply(scenes);
BENCHMARK(BM_RepulsionForces)->Apply(scenes);
BENCHMARK(BM_LubricationAssemble)->Apply(scenes);
BENCHMARK(BM_LubricationAssembleNoFactor)->Apply(scenes);
BENCHMARK(BM_BlockSparseMatVec)->Apply(scenes);
BENCHMARK(BM_PCGSolveCold)->Apply(scenes);
BENCHMARK(BM_PCGSolveWarm)->Apply(scenes);
BENCHMARK(BM_BrownianForces)->Apply(scenes);
BENCHMARK(BM_MidpointDriftStage)->Apply(scenes);
BENCHMARK(BM_Stresslets)->Apply(scenes);
BENCHMARK(BM_ObserveOrientation)->Apply(scenes);
BENCHMARK(BM_ObservePairDistribution)->Apply(scenes);
BENCHMARK(BM_ObserveStress)->Apply(scenes);
BENCHMARK(BM_ObserveDiffusion)->Apply(scenes);
BENCHMARK(BM_ObserveTrajectory)->Apply(scenes);
BENCHMARK(BM_WholeStep)->Apply(scenes);
BENCHMARK(BM_OmpBarrier)->UseRealTime()->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
