#include "plugins/PluginRegistry.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <boost/core/demangle.hpp>
#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "config/DidYouMean.hpp"
#include "fldsim/api.hpp"
#include "fldsim/plugin.hpp"
#include "plugins/LibraryProbe.hpp"

namespace fldsim {

namespace fs = std::filesystem;

struct PluginRegistry::Loaded {
  std::shared_ptr<boost::dll::shared_library> library;
  PluginCreateFn* create = nullptr;
};

namespace {

std::string join(const std::vector<std::string>& items, const char* separator = ", ") {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

// Identity of a directory for de-duplication (the same place named two ways).
std::string canonical_or_same(const std::string& dir) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(dir, ec);
  return ec ? dir : p.string();
}

}  // namespace

PluginRegistry::PluginRegistry(const std::vector<std::string>& directories) {
  std::vector<std::string> seen, files;
  for (const auto& dir : directories) {
    const std::string id = canonical_or_same(dir);
    if (std::find(seen.begin(), seen.end(), id) != seen.end()) continue;
    seen.push_back(id);
    directories_.push_back(dir);

    std::error_code ec;
    std::vector<std::string> here;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      std::error_code type_ec;
      if (entry.path().extension() == ".so" && !entry.is_directory(type_ec))
        here.push_back(entry.path().string());
    }
    if (ec) {
      failures_.push_back(dir + ": cannot list directory: " + ec.message());
      continue;
    }
    std::sort(here.begin(), here.end());  // directory order is arbitrary; results must not be
    files.insert(files.end(), here.begin(), here.end());
  }
  // Probed side by side, then taken in search order (which decides what shadows what).
  const std::vector<ProbeResult> probes = probe_libraries(files, probe_timeout());
  for (std::size_t i = 0; i < files.size(); ++i) take_probe(files[i], probes[i]);
}

PluginRegistry::~PluginRegistry() = default;

void PluginRegistry::take_probe(const std::string& file, const ProbeResult& probe) {
  if (!probe.usable) {
    failures_.push_back(file + ": " + probe.problem);
    failed_files_.push_back({file, probe.kind, probe.name, probe.died});
    return;
  }
  for (const auto& p : plugins_) {
    if (p.kind == probe.kind && p.name == probe.name) {
      shadowed_.push_back(file + ": ignored, " + probe.kind + " plugin '" + probe.name +
                          "' already provided by " + p.file);
      return;
    }
  }
  plugins_.push_back(PluginInfo{file, probe.kind, probe.name, probe.version, probe.summary, probe.schema});
  loaded_.push_back(nullptr);
}

const PluginRegistry::Loaded& PluginRegistry::load(std::size_t index) const {
  if (loaded_[index]) return *loaded_[index];
  const PluginInfo& info = plugins_[index];
  auto library = std::make_shared<boost::dll::shared_library>();
  std::error_code ec;
  library->load(info.file, boost::dll::load_mode::rtld_now, ec);
  if (ec) {
    const char* why = dlerror();
    throw PluginError(info.file + ": cannot load: " + (why ? why : ec.message()));
  }
  // The probe checked this file; check again in case it was replaced since.
  if (!library->has("fldsim_plugin_descriptor") || !library->has("fldsim_create"))
    throw PluginError(info.file + ": no longer an fldsim plugin (replaced while fldsim ran?)");
  const auto& d = library->get<const fldsim_plugin_descriptor_t>("fldsim_plugin_descriptor");
  if (const std::string problem = descriptor_problem(d); !problem.empty())
    throw PluginError(info.file + ": " + problem);
  auto loaded = std::make_unique<Loaded>();
  loaded->create = &library->get_alias<PluginCreateFn>("fldsim_create");
  loaded->library = std::move(library);
  loaded_[index] = std::move(loaded);
  return *loaded_[index];
}

std::string PluginRegistry::describe_plugin(const std::string& kind, const std::string& name) const {
  for (const auto& p : plugins_)
    if (p.kind == kind && p.name == name) return kind + " plugin '" + name + "' (" + p.file + ")";
  return kind + " plugin '" + name + "'";
}

void PluginRegistry::destroy(const std::string& kind, const std::string& name, Component* made) const {
  try {
    delete made;
  } catch (...) {
    rethrow_from_plugin(describe_plugin(kind, name), "its destructor");
  }
}

std::vector<std::string> PluginRegistry::search_path(const std::vector<std::string>& yaml_paths,
                                                     const std::string& yaml_dir) {
  std::vector<std::string> candidates;
  for (const auto& p : yaml_paths) {
    const fs::path path(p);
    candidates.push_back((path.is_absolute() ? path : fs::path(yaml_dir) / path).lexically_normal().string());
  }
  if (const char* env = std::getenv("FLDSIM_PLUGIN_PATH")) {
    const std::string value = env;
    std::size_t start = 0;
    while (start <= value.size()) {
      const std::size_t end = std::min(value.find(':', start), value.size());
      if (end > start) candidates.push_back(value.substr(start, end - start));
      start = end + 1;
    }
  }
  // Relative to where this core library was loaded from: the build tree's core searches the build
  // tree's plugins; an installed core searches <libdir>/fldsim/plugins next to itself, under
  // whatever prefix it was installed to (cmake --install --prefix P). The configured install
  // directory stays as a fallback.
  std::error_code ec;
  const fs::path core_dir = boost::dll::this_line_location(ec).parent_path();
  if (!ec && canonical_or_same(core_dir.string()) == canonical_or_same(FLDSIM_CORE_BUILD_DIR))
    candidates.push_back(FLDSIM_PLUGIN_BUILD_DIR);
  else if (!ec)
    candidates.push_back((core_dir / FLDSIM_PLUGIN_DIR_FROM_CORE).lexically_normal().string());
  candidates.push_back(FLDSIM_PLUGIN_INSTALL_DIR);

  std::vector<std::string> result, ids;
  for (const auto& dir : candidates) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    const std::string id = canonical_or_same(dir);
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) continue;
    ids.push_back(id);
    result.push_back(dir);
  }
  return result;
}

std::vector<std::string> PluginRegistry::related_failures(const std::string& kind,
                                                          const std::string& name) const {
  // A failed file is related when its descriptor names this plugin or, if it could not be read,
  // when its file name ends in the plugin name (fldsim-hydro-fld.so, libfld.so, fld.so).
  std::vector<std::string> out;
  for (std::size_t i = 0; i < failed_files_.size(); ++i) {
    const auto& f = failed_files_[i];
    bool related = false;
    if (f.died) {
      related = true;  // it never said which plugin it holds
    } else if (!f.name.empty()) {
      related = f.kind == kind && f.name == name;
    } else {
      const std::string stem = fs::path(f.file).stem().string();
      related =
          stem == name || stem == "lib" + name ||
          (stem.size() > name.size() && stem.compare(stem.size() - name.size(), name.size(), name) == 0 &&
           stem[stem.size() - name.size() - 1] == '-');
    }
    if (related) out.push_back(failures_[i]);
  }
  return out;
}

const PluginInfo& PluginRegistry::find(const std::string& kind, const std::string& name) const {
  std::vector<std::string> available;
  for (const auto& p : plugins_) {
    if (p.kind != kind) continue;
    if (p.name == name) return p;
    available.push_back(p.name);
  }
  std::sort(available.begin(), available.end());
  std::string message = "no " + kind + " plugin named '" + name + "'";
  if (const std::string guess = did_you_mean(name, available); !guess.empty())
    message += " (did you mean '" + guess + "'?)";
  message += "; available: " + (available.empty() ? std::string("none") : join(available));
  message += "; searched: " + (directories_.empty() ? std::string("no directories") : join(directories_));
  for (const auto& failure : related_failures(kind, name)) message += "; a candidate failed: " + failure;
  throw PluginError(message);
}

Component* PluginRegistry::make(const std::string& kind, const std::string& name, const Params& params,
                                std::shared_ptr<boost::dll::shared_library>& library) const {
  const PluginInfo& info = find(kind, name);
  const auto index = static_cast<std::size_t>(&info - plugins_.data());
  const Loaded& loaded = load(index);
  library = loaded.library;
  Component* made =
      plugin_call(describe_plugin(kind, name), "its constructor", [&] { return loaded.create(params); });
  if (!made) throw PluginError(info.file + ": " + kind + " plugin '" + name + "' returned no object");
  return made;
}

void PluginRegistry::throw_wrong_type(const std::string& kind, const std::string& name,
                                      const std::type_info& wanted) const {
  const PluginInfo& info = find(kind, name);
  throw PluginError(info.file + ": " + kind + " plugin '" + name + "' made an object that is not a " +
                    boost::core::demangle(wanted.name()));
}

}  // namespace fldsim
