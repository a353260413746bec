// Base of every object a plugin makes. The core keeps the library that made an object loaded
// for as long as the object lives (the shared_ptr deleter holds the library).
#pragma once

#include <string>

#include "fldsim/api.hpp"

namespace fldsim {

class FLDSIM_VISIBLE Component {
 public:
  virtual ~Component() = default;
  // The plugin name that made this object, set by the loader.
  const std::string& plugin_name() const { return plugin_name_; }
  void set_plugin_name(std::string n) { plugin_name_ = std::move(n); }

 private:
  std::string plugin_name_;
};

}  // namespace fldsim
