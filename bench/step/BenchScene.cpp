#include "BenchScene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>

#include "config/YamlValidation.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"

namespace fldsim::bench {
namespace {

std::string cache_name(const SceneSpec& s) {
  std::ostringstream name;
  name << "config-" << s.shape;
  if (s.shape == "dicolloid") name << "-c" << s.c;
  name << (s.lattice ? "-lattice" : "-mc") << "-n" << s.count << "-phi" << s.phi << "-sweeps" << s.mc_sweeps
       << ".bin";
  return name.str();
}

// Cache format: body count, then x y z qw qx qy qz per body, as raw doubles.
bool read_cache(const std::string& path, System& sys) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof n);
  if (n != sys.size()) return false;
  for (std::size_t i = 0; i < sys.size(); ++i) {
    double v[7];
    in.read(reinterpret_cast<char*>(v), sizeof v);
    sys.positions()[i] = Vec3(v[0], v[1], v[2]);
    sys.orientations()[i] = Quat(v[3], v[4], v[5], v[6]);
  }
  if (!in) return false;
  sys.update_nodes();
  return true;
}

void write_cache(const std::string& path, const System& sys) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary);
    const std::uint64_t n = sys.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    for (std::size_t i = 0; i < sys.size(); ++i) {
      const Vec3& x = sys.positions()[i];
      const Quat& q = sys.orientations()[i];
      const double v[7] = {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()};
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  std::filesystem::rename(part, path);  // atomic: parallel benchmarks never read half a file
}

// Simple cubic lattice at the target density, if N is a cube and the spacing leaves a gap
// (spheres only: any orientation fits).
bool place_on_lattice(System& sys) {
  const std::size_t n = sys.size();
  const auto side = std::size_t(std::llround(std::cbrt(double(n))));
  const double spacing = sys.box().edge() / double(side);
  if (side * side * side != n || sys.nodes_per_body() != 1 || spacing < 2.0 * sys.node_radius(0) + 0.02)
    return false;
  std::size_t i = 0;
  for (std::size_t a = 0; a < side; ++a)
    for (std::size_t b = 0; b < side; ++b)
      for (std::size_t c = 0; c < side; ++c, ++i) {
        sys.positions()[i] = spacing * Vec3(double(a) + 0.5, double(b) + 0.5, double(c) + 0.5);
        sys.orientations()[i] = Quat::Identity();
      }
  sys.update_nodes();
  return true;
}

}  // namespace

const PluginRegistry& registry() {
  static PluginRegistry r({FLDSIM_BENCH_PLUGIN_DIR});
  return r;
}

Params plugin_params(const std::string& kind, const std::string& name, const std::string& yaml) {
  ConfigErrors errors("bench");
  Params p = validate_params(YAML::Load(yaml), registry().find(kind, name).schema, kind, errors, {"plugin"});
  errors.throw_if_any();
  return p;
}

void BenchScene::start_configuration(const SceneSpec& spec, System& sys) {
  const std::string path = spec.cache_dir.empty() ? "" : spec.cache_dir + "/" + cache_name(spec);
  if (!path.empty() && read_cache(path, sys)) {
    start_note_ = "cached " + path;
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (spec.lattice && place_on_lattice(sys)) {
    geometry::HardBodyMonteCarlo mc(sys, spec.seed);
    for (int k = 0; k < spec.mc_sweeps; ++k) {
      mc.sweep();
      mc.adapt_steps(0.35);
    }
    if (mc.count_overlaps() != 0) throw Error("bench: lattice start has overlaps");
    start_note_ = "simple cubic lattice + " + std::to_string(spec.mc_sweeps) + " MC sweeps";
  } else {
    geometry::MonteCarloOptions opt;
    opt.seed = spec.seed;
    opt.sweeps = spec.mc_sweeps;
    const auto r = geometry::initialise_monte_carlo(sys, opt);
    if (r.overlaps != 0) throw Error("bench: Monte Carlo start has overlaps");
    start_note_ = "MC compression + " + std::to_string(r.sweeps) + " sweeps";
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  start_note_ += " (" + std::to_string(int(s + 0.5)) + " s)";
  if (!path.empty()) write_cache(path, sys);
}

BenchScene::BenchScene(const SceneSpec& spec, const std::vector<ObserverSpec>& observers) {
  const std::string shape_yaml =
      spec.shape == "dicolloid" ? "{a: 1, b: 1, c: " + std::to_string(spec.c) + "}" : std::string("{a: 1}");
  auto shape = registry().create<Shape>("shape", spec.shape, plugin_params("shape", spec.shape, shape_yaml));
  Physics ph;
  ph.kT = spec.brownian ? 1.0 : 0.0;
  ph.shear_rate = spec.peclet;
  ph.volume_fraction = spec.phi;
  const double edge = std::cbrt(double(spec.count) * shape->volume() / spec.phi);
  SimulationParts parts;
  parts.system = std::make_unique<System>(shape, spec.count, edge, ph);
  start_configuration(spec, *parts.system);
  if (!spec.order.empty()) {
    System& sys = *parts.system;
    std::vector<std::size_t> order(sys.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    if (spec.order == "shuffle") {
      std::shuffle(order.begin(), order.end(), std::mt19937_64(spec.seed));
    } else {
      const double L = sys.box().edge();
      const int cells = std::max(1, int(L / (2.0 * sys.shape().bounding_radius())));
      auto morton = [&](const Vec3& x) {
        std::uint64_t key = 0;
        for (int d = 0; d < 3; ++d) {
          double u = x[d] / L;
          u -= std::floor(u);
          const std::uint64_t c = std::min<std::uint64_t>(std::uint64_t(u * cells), std::uint64_t(cells - 1));
          for (int b = 0; b < 21; ++b) key |= ((c >> b) & 1u) << (3 * b + d);
        }
        return key;
      };
      std::vector<std::uint64_t> key(sys.size());
      for (std::size_t i = 0; i < sys.size(); ++i) key[i] = morton(sys.positions()[i]);
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    }
    const std::vector<Vec3> x = sys.positions();
    const auto q = sys.orientations();
    for (std::size_t i = 0; i < order.size(); ++i) {
      sys.positions()[i] = x[order[i]];
      sys.orientations()[i] = q[order[i]];
    }
    sys.update_nodes();
    start_note_ += ", bodies ordered: " + spec.order;
  }

  hydro_ =
      registry().create<HydroModel>("hydro", spec.hydro, plugin_params("hydro", spec.hydro, spec.hydro_yaml));
  timed_ = std::make_shared<TimedHydro>(hydro_);
  parts.hydro_name = spec.hydro;
  parts.hydro = timed_;
  const std::string rep = "{prefactor: " + std::to_string(spec.repulsion) + "}";
  parts.forces.push_back(
      registry().create<ForceLaw>("force", "repulsion", plugin_params("force", "repulsion", rep)));
  for (std::size_t i = 0; i < observers.size(); ++i) {
    const ObserverSpec& o = observers[i];
    auto ob = registry().create<Observer>("observer", o.plugin, plugin_params("observer", o.plugin, o.yaml));
    ob->set_schedule(o.every, 0.0);
    parts.observers.push_back(ob);
    parts.observer_keys.push_back("observers[" + std::to_string(i) + "]." + o.plugin);
  }

  SimulationSettings settings;
  // The paper's time unit: 1/gammadot for Pe >= 1, a^2/D0 below (run/RunUnits.cpp).
  settings.dt = spec.dt > 0.0 ? spec.dt : spec.peclet >= 1.0 ? spec.dt_paper / spec.peclet : spec.dt_paper;
  settings.total_steps = 1000000;
  settings.integrator = "euler_maruyama";  // with the midpoint drift stage, also at kT = 0
  settings.drift = "midpoint";
  settings.skin = spec.skin;
  settings.skin_auto = spec.skin_auto;
  settings.seed = spec.seed;
  settings.time_unit = spec.peclet >= 1.0 ? "1/gammadot" : "a^2/D0";
  settings.time_scale = spec.peclet >= 1.0 ? 1.0 / spec.peclet : 1.0;
  settings.user_dt = settings.dt / settings.time_scale;
  settings.output_path = "bench";
  // The benchmark sets the threads itself (OMP_NUM_THREADS, omp_set_num_threads).
  settings.threads.reason = "set by the benchmark";
  simulation_ = std::make_unique<Simulation>(std::move(parts), std::move(settings), sink_, log_);
}

}  // namespace fldsim::bench
