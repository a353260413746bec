// What a result file records about how it was made (/parameters): the resolved experiment,
// every plugin's version and file, the seed and the run's units.
#pragma once

#include "io/Hdf5ResultSink.hpp"
#include "run/Experiment.hpp"
#include "run/Simulation.hpp"

namespace fldsim {

void write_provenance(Hdf5ResultSink& sink, const Experiment& ex, const PluginRegistry& registry,
                      const Simulation& sim);

}  // namespace fldsim
