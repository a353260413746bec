// Test scaffolding: plugins are made through the real loader from the build's plugin
// directory, with parameters written as YAML, and stepped with the core's integrators.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <memory>
#include <string>

#include "config/YamlValidation.hpp"
#include "dynamics/TimeIntegrator.hpp"
#include "dynamics/VelocityEvaluator.hpp"
#include "geometry/CellNeighbourList.hpp"
#include "plugins/PluginRegistry.hpp"

namespace fldsim::testing {
using geometry::CellNeighbourList;

inline const PluginRegistry& registry() {
  static PluginRegistry r({FLDSIM_TEST_PLUGIN_DIR});
  return r;
}

inline Params params(const std::string& kind, const std::string& name, const std::string& yaml = "{}") {
  ConfigErrors errors("test");
  Params p = validate_params(YAML::Load(yaml), registry().find(kind, name).schema, kind, errors, {"plugin"});
  errors.throw_if_any();
  return p;
}

template <class T>
std::shared_ptr<T> make(const std::string& kind, const std::string& name, const std::string& yaml = "{}") {
  return registry().create<T>(kind, name, params(kind, name, yaml));
}

// Mean of independent samples (or batch means) and its standard error.
struct MeanWithError {
  double mean = 0, se = 0;
};
inline MeanWithError mean_with_error(const std::vector<double>& v) {
  double m = 0, var = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  for (double x : v) var += (x - m) * (x - m);
  return {m, std::sqrt(var / double(v.size() - 1) / double(v.size()))};
}

// A system plus what it takes to step it.
struct Scene {
  std::shared_ptr<Shape> shape;
  std::unique_ptr<System> system;
  std::shared_ptr<HydroModel> hydro;
  std::vector<std::shared_ptr<ForceLaw>> forces;
  CellNeighbourList list;
  std::unique_ptr<VelocityEvaluator> evaluator;

  Scene(std::shared_ptr<Shape> s, std::size_t n, double edge, Physics ph) : shape(std::move(s)) {
    system = std::make_unique<System>(shape, n, edge, ph);
  }
  // Call after placing the bodies.
  void finish(std::shared_ptr<HydroModel> h, std::vector<std::shared_ptr<ForceLaw>> f, HydroRequest req,
              double skin = 0.3) {
    hydro = std::move(h);
    forces = std::move(f);
    double range = hydro->pair_range(*system);
    for (const auto& law : forces) range = std::max(range, law->range(*system));
    list.configure(range, skin);
    system->update_nodes();
    list.update(*system);
    hydro->configure(*system, req);
    evaluator = std::make_unique<VelocityEvaluator>(hydro, forces, list, system->size());
  }
};

}  // namespace fldsim::testing
