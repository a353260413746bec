// Errors thrown by the core and by plugins. Marked visible so that a type thrown in a plugin
// (built with hidden visibility) is caught by type in the core.
#pragma once

#include <stdexcept>
#include <string>

#include "fldsim/api.hpp"

namespace fldsim {

// Any failure the user can act on: bad input, a diverging run, a missing plugin.
class FLDSIM_VISIBLE Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A problem with the experiment file; exit code 2. The message is already formatted as
// `file:line:col: key.path: expected ..., got ...` (possibly several lines).
class FLDSIM_VISIBLE ConfigError : public Error {
 public:
  using Error::Error;
};

// A plugin library that cannot be used (not a plugin, API mismatch, missing symbol).
class FLDSIM_VISIBLE PluginError : public Error {
 public:
  using Error::Error;
};

}  // namespace fldsim
