// Looks inside a plugin library from a forked child process, so that a library whose static
// initialisers abort, crash or hang, or whose describe() throws anything, is reported and
// skipped instead of taking the program down. The parent learns the descriptor and the
// declared parameters without loading the library itself; it loads only the libraries an
// experiment names, and only after their probe succeeded.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "fldsim/params.hpp"

namespace fldsim {

struct ProbeResult {
  bool usable = false;
  // Descriptor fields when it could be read (also for a refused one: kind/name say which
  // plugin the failure belongs to).
  std::string kind, name, version, summary;
  ParamSchema schema;
  std::string problem;  // why not usable, e.g. "cannot load: ...", "crashed while loading: SIGABRT"
  bool died = false;    // the library crashed, hung or exited while probed: it may hold any plugin
};

// Seconds a probe may take (FLDSIM_PLUGIN_LOAD_TIMEOUT overrides the default of 20).
std::chrono::milliseconds probe_timeout();

ProbeResult probe_library(const std::string& file, std::chrono::milliseconds timeout);
// Several at once (a few children at a time), results in the order of `files`.
std::vector<ProbeResult> probe_libraries(const std::vector<std::string>& files,
                                         std::chrono::milliseconds timeout);

// Why a descriptor cannot be used, or "" when it can (shared by the probe and the loader).
std::string descriptor_problem(const struct fldsim_plugin_descriptor_t& d);

}  // namespace fldsim
