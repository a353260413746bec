// Finds, checks and opens plugin libraries, and makes objects from them.
//
// Each *.so is checked in an order that never lets an incompatible C++ type cross the library
// boundary: load with RTLD_NOW (a missing symbol fails here, not mid-run), read the plain C
// descriptor, compare API version and build tag, and only then touch the C++ entry points.
// A library stays open while the registry or any object it made is alive.
#pragma once

#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "fldsim/error.hpp"
#include "fldsim/params.hpp"
#include "fldsim/plugin_base.hpp"

namespace boost::dll {
class shared_library;
}

namespace fldsim {

struct PluginInfo {
  std::string file, kind, name, version, summary;
  ParamSchema schema;
};

class PluginRegistry {
 public:
  // Scans each directory (non-recursively, files *.so, in name order) in the given order; the
  // first plugin of a given (kind, name) wins and later ones are listed in shadowed(). A file
  // that cannot be used is recorded in failures() and does not stop the scan.
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

  // Makes the object. The shared_ptr's deleter owns a reference to the library, so the object
  // is destroyed while its code is still mapped, even after the registry is gone. Throws
  // PluginError if the object is not a T; the plugin's own ConfigError passes through.
  template <class T>
  std::shared_ptr<T> create(const std::string& kind, const std::string& name, const Params& params) const {
    std::shared_ptr<boost::dll::shared_library> library;
    Component* made = make(kind, name, params, library);
    T* typed = dynamic_cast<T*>(made);
    if (!typed) {
      delete made;
      throw_wrong_type(kind, name, typeid(T));
    }
    made->set_plugin_name(name);
    return std::shared_ptr<T>(typed, [made, library](T*) mutable {
      delete made;      // runs the plugin's destructor while the library is mapped
      library.reset();  // then lets go of the library
    });
  }

 private:
  struct Loaded;
  void scan_file(const std::string& file);
  Component* make(const std::string& kind, const std::string& name, const Params& params,
                  std::shared_ptr<boost::dll::shared_library>& library) const;
  [[noreturn]] void throw_wrong_type(const std::string& kind, const std::string& name,
                                     const std::type_info& wanted) const;
  std::vector<std::string> related_failures(const std::string& kind, const std::string& name) const;

  std::vector<std::string> directories_;
  std::vector<PluginInfo> plugins_;
  std::vector<Loaded> loaded_;  // parallel to plugins_
  std::vector<std::string> failures_;
  std::vector<std::string> shadowed_;
  struct FailedFile {
    std::string file, kind, name;  // kind/name empty when the descriptor could not be read
  };
  std::vector<FailedFile> failed_files_;
};

}  // namespace fldsim
