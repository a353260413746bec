#include "run/Provenance.hpp"

namespace fldsim {

// /parameters: the resolved experiment, every plugin's version and file, and the run's units.
void write_provenance(Hdf5ResultSink& sink, const Experiment& ex, const PluginRegistry& registry,
                      const Simulation& sim) {
  std::vector<std::array<std::string, 4>> table;
  auto add = [&](const std::string& kind, const std::string& name) {
    const PluginInfo& p = registry.find(kind, name);
    table.push_back({kind, name, p.version, p.file});
  };
  add("shape", ex.shape.name);
  add("hydro", ex.hydro.name);
  for (const auto& f : ex.forces) add("force", f.name);
  for (const auto& o : ex.observers) add("observer", o.plugin.name);
  // Numbers as doubles (exact), not as text.
  std::map<std::string, Hdf5ResultSink::ParameterValue> extra{
      {"time_unit", sim.settings().time_unit},
      {"units", "lengths a (node radius), energies kT; times in time_unit (internally a^2/D0)"},
      {"peclet", ex.peclet},
      {"volume_fraction", sim.system().physics().volume_fraction},
      {"box_edge", sim.system().box().edge()},
      {"dt", ex.dt},
      {"shape", ex.shape.name},
      {"brownian", std::string(ex.brownian ? "true" : "false")},
      {"integrator", sim.integrator().describe()},
      {"experiment_file", ex.file}};
  if (ex.shape.params.has("c")) extra["shape_c"] = ex.shape.params.number("c");
  sink.write_parameters(ex.resolved_yaml, table, std::uint64_t(ex.seed), extra);
  sink.write_experiment_source(ex.source_text, ex.overrides);
}

}  // namespace fldsim
