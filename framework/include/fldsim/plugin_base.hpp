// Base of every object a plugin makes. The core keeps the library that made an object loaded
// for as long as the object lives (the shared_ptr deleter holds the library).
#pragma once

#include <string>
#include <vector>

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

// API 5.3: a component (hydro model, force law, observer) that changes how it works during a run
// may also derive from RunNotes, so that the user sees it in the run log. The core drains every
// component that does after each step and writes each line as
//   note: t = <time> <unit>, <hydro|force|observer> <plugin>: <line>
// Note changes of behaviour (a preconditioner that broke down and fell back, and when it works
// again), not per-step events: a line per step would flood the log of a million-step run.
class FLDSIM_VISIBLE RunNotes {
 public:
  virtual ~RunNotes() = default;
  // The lines noted since the last call, oldest first; the component keeps none of them.
  virtual std::vector<std::string> take_notes() = 0;
};

// The component's RunNotes side, or null when it has none (a plugin of API 5.2 or older).
inline RunNotes* run_notes_of(Component& c) {
  return dynamic_cast<RunNotes*>(&c);
}

}  // namespace fldsim
