// Finds, checks and opens plugin libraries, and makes objects from them.
//
// Each *.so on the search path is probed in a child process (LibraryProbe): loaded with
// RTLD_NOW (a missing symbol fails there, not mid-run), its plain C descriptor read, API version
// and build tag compared, and only then its describe() called. A library that aborts, crashes,
// hangs or throws while probed is reported in failures() and skipped; the program goes on.
// This process loads a library only when an object of one of its plugins is made, so a command
// loads just the plugins its experiment names. A library stays open while the registry or any
// object it made is alive. Objects of the four plugin kinds come wrapped in a guard
// (PluginBoundary.hpp) that turns anything the plugin throws into a core exception naming it.
#pragma once

#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "fldsim/error.hpp"
#include "fldsim/params.hpp"
#include "fldsim/plugin_base.hpp"
#include "plugins/PluginBoundary.hpp"

namespace boost::dll {
class shared_library;
}

namespace fldsim {

struct PluginInfo {
  std::string file, kind, name, version, summary;
  ParamSchema schema;
};

struct ProbeResult;

class PluginRegistry {
 public:
  // Scans each directory (non-recursively, files *.so, in name order) in the given order; the
  // first plugin of a given (kind, name) wins and later ones are listed in shadowed(). A file
  // that cannot be used is recorded in failures() and does not stop the scan. Nothing is
  // loaded into this process yet.
  explicit PluginRegistry(const std::vector<std::string>& directories);
  ~PluginRegistry();
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  // The YAML `plugins.paths` (relative ones taken from the YAML file's directory), then each
  // entry of the colon-separated FLDSIM_PLUGIN_PATH, then the build and install plugin
  // directories. Directories that do not exist are skipped; repeats are dropped.
  static std::vector<std::string> search_path(const std::vector<std::string>& yaml_paths,
                                              const std::string& yaml_dir);

  const std::vector<PluginInfo>& plugins() const { return plugins_; }
  const std::vector<std::string>& failures() const { return failures_; }  // "FILE: reason"
  const std::vector<std::string>& shadowed() const { return shadowed_; }  // "FILE: reason"
  const std::vector<std::string>& directories() const { return directories_; }

  // Throws PluginError "no hydro plugin named 'fdl' (did you mean 'fld'?); available: fld,
  // free_draining, lubrication; searched: dir1, dir2", plus the failure of any file that looks
  // like the wanted plugin.
  const PluginInfo& find(const std::string& kind, const std::string& name) const;

  // "observer plugin 'stress' (FILE)": how messages name a plugin.
  std::string describe_plugin(const std::string& kind, const std::string& name) const;

  // Makes the object, loading its library into this process first if needed. The shared_ptr's
  // deleter owns a reference to the library, so the object is destroyed while its code is
  // still mapped, even after the registry is gone. Throws PluginError if the object is not a T;
  // the plugin's own ConfigError passes through; anything else it throws becomes an Error
  // naming the plugin and its file.
  template <class T>
  std::shared_ptr<T> create(const std::string& kind, const std::string& name, const Params& params) const {
    std::shared_ptr<boost::dll::shared_library> library;
    Component* made = make(kind, name, params, library);
    T* typed = dynamic_cast<T*>(made);
    if (!typed) {
      destroy(kind, name, made);
      throw_wrong_type(kind, name, typeid(T));
    }
    made->set_plugin_name(name);
    const std::string who = describe_plugin(kind, name);
    std::shared_ptr<T> object(typed, [made, library, who](T*) mutable {
      // Runs the plugin's destructor while the library is mapped, then lets go of the library.
      // A destructor must not throw; if one does anyway, it stops here.
      try {
        delete made;
      } catch (...) {
      }
      library.reset();
    });
    std::shared_ptr<T> guarded = guard_plugin_object(std::move(object), who);
    guarded->set_plugin_name(name);
    return guarded;
  }

 private:
  struct Loaded;
  void take_probe(const std::string& file, const ProbeResult& probe);
  // Loads the library of plugins_[index] into this process (once).
  const Loaded& load(std::size_t index) const;
  void destroy(const std::string& kind, const std::string& name, Component* made) const;
  Component* make(const std::string& kind, const std::string& name, const Params& params,
                  std::shared_ptr<boost::dll::shared_library>& library) const;
  [[noreturn]] void throw_wrong_type(const std::string& kind, const std::string& name,
                                     const std::type_info& wanted) const;
  std::vector<std::string> related_failures(const std::string& kind, const std::string& name) const;

  std::vector<std::string> directories_;
  std::vector<PluginInfo> plugins_;
  mutable std::vector<std::unique_ptr<Loaded>> loaded_;  // parallel to plugins_; null until loaded
  std::vector<std::string> failures_;
  std::vector<std::string> shadowed_;
  struct FailedFile {
    std::string file, kind, name;  // kind/name empty when the descriptor could not be read
    bool died = false;             // crashed, hung or exited while probed
  };
  std::vector<FailedFile> failed_files_;
};

}  // namespace fldsim
