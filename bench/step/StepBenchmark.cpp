// fldsim_bench_step: one whole-step benchmark case per invocation (so that the peak memory is
// the case's own), printed as one CSV row. bench/run.sh runs the table of cases.
//
//   fldsim_bench_step [key=value ...]        e.g. shape=dicolloid c=0.2 n=1000 phi=0.5 pe=10
//   fldsim_bench_step --header               the CSV header
//
// Keys: label, hydro_params (the hydro plugin's parameters as a YAML map, e.g.
// "{preconditioner: block_jacobi}"), repeats (blocks of `steps` steps; the fastest is reported), shape
// (sphere|dicolloid), c, n, phi, pe, kT (1|0), hydro, skin (a number or auto), dt (internal, 0 = 1e-3 in the
// paper's unit), threads, steps, warmup, sweeps (MC sweeps of the quick start), observers
// (none|standard|stress1|all1|all100), start (lattice: spheres on a simple cubic lattice when N is a cube,
// else MC compression | mc: always MC compression), order (bodies renumbered: shuffle | cells), cache
// (configuration cache directory). Columns: wall and
// process-CPU ms/step of the timed steps, CG iterations per step (all solves of the step), the time of each
// part of the step in ms/step (neighbours+forces+moves are the rest), lubricated pairs, neighbour rebuilds
// and the process's peak resident memory (VmHWM) in MB.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "BenchScene.hpp"

using namespace fldsim;
using namespace fldsim::bench;

namespace {

const char* kHeader =
    "label,shape,c,n,phi,pe,kT,hydro,observers,skin,threads,steps,ms_per_step,cpu_ms_per_step,cg_per_step,"
    "solves_per_step,"
    "assemble_ms,brownian_ms,solve_ms,observers_ms,rest_ms,pairs,rebuilds,rss_mb,start";

// CPU time of the whole process (all threads): on a shared, loaded machine a one-thread case's
// CPU time is a far steadier figure than its wall time.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return 0.0;
}

std::vector<ObserverSpec> observer_preset(const std::string& name) {
  const std::string pd = "{range: 5, bins: 100}";
  if (name == "none") return {};
  // The quickstart's observers (examples/quickstart.yaml) without file output.
  if (name == "standard") return {{"orientation", 100}, {"pair_distribution", 200, pd}, {"stress", 20}};
  if (name == "stress1") return {{"stress", 1}};
  if (name == "all1")
    return {
        {"orientation", 1}, {"pair_distribution", 1, pd}, {"stress", 1}, {"diffusion", 1, "{max_lag: 1}"}};
  if (name == "all100")
    return {{"orientation", 100},
            {"pair_distribution", 100, pd},
            {"stress", 100},
            {"diffusion", 100, "{max_lag: 1}"}};
  throw Error("observers=" + name + ": expected none, standard, stress1, all1 or all100");
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> kv{{"label", "step"}, {"shape", "sphere"},  {"c", "0.2"},
                                        {"n", "1000"},     {"phi", "0.3"},       {"pe", "10"},
                                        {"kT", "1"},       {"hydro", "fld"},     {"hydro_params", "{}"},
                                        {"skin", "0.3"},   {"dt", "0"},          {"threads", "1"},
                                        {"steps", "20"},   {"repeats", "1"},     {"warmup", "2"},
                                        {"sweeps", "50"},  {"start", "lattice"}, {"observers", "standard"},
                                        {"cache", ""},     {"order", ""}};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--header") {
      std::cout << kHeader << "\n";
      return 0;
    }
    const auto eq = a.find('=');
    if (eq == std::string::npos || !kv.count(a.substr(0, eq))) {
      std::cerr << "fldsim_bench_step: " << a << ": expected key=value with a key from the list in "
                << "bench/step/StepBenchmark.cpp (label, shape, c, n, phi, pe, kT, hydro, ...)\n";
      return 2;
    }
    kv[a.substr(0, eq)] = a.substr(eq + 1);
  }
  try {
    SceneSpec spec;
    spec.shape = kv["shape"];
    spec.c = std::stod(kv["c"]);
    spec.count = std::stoul(kv["n"]);
    spec.phi = std::stod(kv["phi"]);
    spec.peclet = std::stod(kv["pe"]);
    spec.brownian = kv["kT"] != "0";
    spec.hydro = kv["hydro"];
    spec.hydro_yaml = kv["hydro_params"];
    spec.skin_auto = kv["skin"] == "auto";
    if (!spec.skin_auto) spec.skin = std::stod(kv["skin"]);
    spec.dt = std::stod(kv["dt"]);
    spec.mc_sweeps = std::stoi(kv["sweeps"]);
    spec.cache_dir = kv["cache"];
    if (kv["start"] != "lattice" && kv["start"] != "mc")
      throw Error("start=" + kv["start"] + ": expected lattice or mc");
    spec.lattice = kv["start"] == "lattice";
    spec.order = kv["order"];
    const int threads = std::stoi(kv["threads"]);
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    BenchScene scene(spec, observer_preset(kv["observers"]));
    for (int k = 0; k < std::stoi(kv["warmup"]); ++k) scene.step();
    // `repeats` blocks of `steps` steps; the fastest block (wall time) is reported, the usual
    // noise-robust estimate on a shared machine.
    const int steps = std::stoi(kv["steps"]);
    const int repeats = std::max(1, std::stoi(kv["repeats"]));
    double wall = 1e300, cpu = 0.0, observer_s = 0.0;
    std::int64_t rebuilds = 0;
    HydroTimes h;
    for (int r = 0; r < repeats; ++r) {
      scene.hydro().reset_times();
      const double obs0 = scene.observer_seconds();
      const std::int64_t rebuilds0 = scene.neighbours().rebuilds();
      const double cpu0 = process_cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = 0; k < steps; ++k) scene.step();
      const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (w < wall) {
        wall = w;
        cpu = process_cpu_seconds() - cpu0;
        h = scene.hydro().times();
        observer_s = scene.observer_seconds() - obs0;
        rebuilds = scene.neighbours().rebuilds() - rebuilds0;
      }
    }
    const double per = 1000.0 / steps;  // seconds in total -> ms per step
    // The observers' share: their sample calls plus the stresslet sums of the stress pieces
    // (computed inside the step; the extra deterministic solve counts as solve time).
    const double observers_ms = (observer_s + h.stresslets) * per;
    const double parts = (h.assemble + h.brownian + h.solve) * per + observers_ms;
    std::printf(
        "%s,%s,%s,%zu,%g,%g,%s,%s,%s,%s,%d,%d,%.3f,%.3f,%.2f,%.2f,%.3f,%.3f,%.3f,%.3f,%.3f,%lld,%lld,%.1f,%"
        "s\n",
        kv["label"].c_str(), spec.shape.c_str(), spec.shape == "dicolloid" ? kv["c"].c_str() : "-",
        spec.count, spec.phi, spec.peclet, spec.brownian ? "1" : "0", spec.hydro.c_str(),
        kv["observers"].c_str(), kv["skin"].c_str(), threads, steps, wall * per, cpu * per,
        double(h.cg_iterations) / steps, double(h.solves) / steps, h.assemble * per, h.brownian * per,
        h.solve * per, observers_ms, wall * per - parts,
        static_cast<long long>(scene.evaluator().stats().pairs), static_cast<long long>(rebuilds),
        peak_rss_mb(), scene.start_note().c_str());
    for (const auto& s : scene.skipped()) std::cerr << "skipped: " << s << "\n";
    for (const auto& n : scene.notes()) std::cerr << n << "\n";
  } catch (const std::exception& e) {
    std::cerr << "fldsim_bench_step: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
