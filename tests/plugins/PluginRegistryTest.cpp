// The loader against fixture libraries: one good plugin and one library per documented failure.
// Each failure text is asserted exactly: it is what a user sees when a plugin cannot be used.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "config/YamlValidation.hpp"
#include "fixtures/FixtureInterfaces.hpp"
#include "plugins/PluginRegistry.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kDir = PLUGIN_FIXTURE_DIR;
const std::string kShadowDir = PLUGIN_FIXTURE_SHADOW_DIR;
std::string fixture(const std::string& name) {
  return kDir + "/" + name + ".so";
}

fldsim::Params params_for(const fldsim::PluginInfo& info, const std::string& yaml) {
  fldsim::ConfigErrors errors("inline.yaml");
  fldsim::Params p = fldsim::validate_params(YAML::Load(yaml), info.schema, "forces[0]", errors, {"plugin"});
  errors.throw_if_any();
  return p;
}

std::string plugin_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const fldsim::PluginError& e) {
    return e.what();
  }
  return "(no PluginError)";
}

TEST(PluginRegistry, LoadsTheGoodFixtureAndRecordsEachFailure) {
  const fldsim::PluginRegistry registry({kDir});
  ASSERT_EQ(registry.plugins().size(), 1u);
  const fldsim::PluginInfo& info = registry.plugins()[0];
  EXPECT_EQ(info.file, fixture("fixture_scaler"));
  EXPECT_EQ(info.kind, "force");
  EXPECT_EQ(info.name, "fixture_scaler");
  EXPECT_EQ(info.version, "1.0.0");
  EXPECT_EQ(info.summary, "test fixture: multiplies by a factor");
  ASSERT_EQ(info.schema.specs().size(), 1u);
  EXPECT_EQ(info.schema.specs()[0].expectation(), "a number > 0");

  // Files are scanned in name order, so failures come in that order.
  const std::vector<std::string> expected = {
      fixture("fixture_api99") +
          ": plugin API 99.0 does not match this fldsim (API " FLDSIM_STR(FLDSIM_API_MAJOR) "." FLDSIM_STR(
              FLDSIM_API_MINOR) "); rebuild the plugin against this fldsim",
      fixture("fixture_badkind") +
          ": unknown plugin kind 'widget' (expected shape, hydro, force or observer)",
      fixture("fixture_badtag") +
          ": plugin build tag 'gcc-abi0/cxx11abi0/api1' does not match this fldsim's '" + FLDSIM_BUILD_TAG +
          "'; rebuild the plugin against this fldsim with the same compiler",
      fixture("fixture_notplugin") + ": not an fldsim plugin (no fldsim_plugin_descriptor)",
      // glibc's dlerror() text for an unresolved symbol under RTLD_NOW.
      fixture("fixture_undefined") + ": cannot load: " + fixture("fixture_undefined") +
          ": undefined symbol: _Z14missing_helperv",
  };
  EXPECT_EQ(registry.failures(), expected);
  EXPECT_EQ(registry.directories(), std::vector<std::string>{kDir});
}

TEST(PluginRegistry, ANonLibraryFileDoesNotStopTheScan) {
  const fs::path dir = fs::temp_directory_path() / ("fldsim-plugin-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "junk.so") << std::string(256, 'x');  // long enough to have an ELF header slot
  fs::copy_file(fixture("fixture_scaler"), dir / "zz_scaler.so", fs::copy_options::overwrite_existing);
  {
    const fldsim::PluginRegistry registry({dir.string()});
    ASSERT_EQ(registry.failures().size(), 1u);
    const std::string junk = (dir / "junk.so").string();
    EXPECT_EQ(registry.failures()[0], junk + ": cannot load: " + junk + ": invalid ELF header");
    ASSERT_EQ(registry.plugins().size(), 1u);
    EXPECT_EQ(registry.plugins()[0].name, "fixture_scaler");
  }
  fs::remove_all(dir);
}

TEST(PluginRegistry, FirstDirectoryWinsForTheSameName) {
  {
    const fldsim::PluginRegistry registry({kDir, kShadowDir});
    EXPECT_EQ(registry.find("force", "fixture_scaler").version, "1.0.0");
    ASSERT_EQ(registry.shadowed().size(), 1u);
    EXPECT_EQ(registry.shadowed()[0], kShadowDir +
                                          "/fixture_scaler.so: ignored, force plugin 'fixture_scaler' "
                                          "already provided by " +
                                          fixture("fixture_scaler"));
  }
  const fldsim::PluginRegistry reversed({kShadowDir, kDir});
  EXPECT_EQ(reversed.find("force", "fixture_scaler").version, "2.0.0");
}

TEST(PluginRegistry, RepeatedDirectoryIsScannedOnce) {
  const fldsim::PluginRegistry registry({kDir, kDir + "/.", kDir});
  EXPECT_EQ(registry.directories(), std::vector<std::string>{kDir});
  EXPECT_TRUE(registry.shadowed().empty());
}

TEST(PluginRegistry, CreatesObjectsWithValidatedParams) {
  const fldsim::PluginRegistry registry({kDir});
  const auto& info = registry.find("force", "fixture_scaler");
  auto scaler = registry.create<fixture::Scaler>("force", "fixture_scaler",
                                                 params_for(info, "{plugin: fixture_scaler, factor: 3}"));
  ASSERT_TRUE(scaler);
  EXPECT_EQ(scaler->scaled(2.0), 6.0);
  EXPECT_EQ(scaler->plugin_name(), "fixture_scaler");
  // Default from the plugin's schema.
  EXPECT_EQ(registry.create<fixture::Scaler>("force", "fixture_scaler", params_for(info, "{}"))->scaled(1.0),
            2.0);
}

TEST(PluginRegistry, ConfigErrorFromAPluginConstructorReachesTheCaller) {
  const fldsim::PluginRegistry registry({kDir});
  const auto& info = registry.find("force", "fixture_scaler");
  const fldsim::Params p = params_for(info, "{plugin: fixture_scaler, factor: 500}");
  try {
    registry.create<fixture::Scaler>("force", "fixture_scaler", p);
    FAIL() << "expected a ConfigError";
  } catch (const fldsim::ConfigError& e) {  // thrown in the plugin, caught here by type
    EXPECT_EQ(std::string(e.what()), "inline.yaml:1:34: forces[0].factor: must be <= 100 for this fixture");
  }
}

TEST(PluginRegistry, RefusesAnObjectOfTheWrongInterface) {
  const fldsim::PluginRegistry registry({kDir});
  const fldsim::Params p = params_for(registry.find("force", "fixture_scaler"), "{}");
  EXPECT_EQ(plugin_error([&] { registry.create<fixture::Unrelated>("force", "fixture_scaler", p); }),
            fixture("fixture_scaler") +
                ": force plugin 'fixture_scaler' made an object that is not a fixture::Unrelated");
}

TEST(PluginRegistry, UnknownNameListsAvailableAndSuggests) {
  const fldsim::PluginRegistry registry({kDir});
  EXPECT_EQ(
      plugin_error([&] { registry.find("force", "fixture_scalr"); }),
      "no force plugin named 'fixture_scalr' (did you mean 'fixture_scaler'?); available: fixture_scaler; "
      "searched: " +
          kDir);
  EXPECT_EQ(plugin_error([&] { registry.find("hydro", "fld"); }),
            "no hydro plugin named 'fld'; available: none; searched: " + kDir);
}

TEST(PluginRegistry, FindingAFailedPluginMentionsTheFailure) {
  const fldsim::PluginRegistry registry({kDir});
  // Descriptor unreadable (load failed): matched by file name.
  EXPECT_EQ(plugin_error([&] { registry.find("force", "fixture_undefined"); }),
            "no force plugin named 'fixture_undefined'; available: fixture_scaler; searched: " + kDir +
                "; a candidate failed: " + fixture("fixture_undefined") +
                ": cannot load: " + fixture("fixture_undefined") + ": undefined symbol: _Z14missing_helperv");
  // Descriptor read but refused: matched by its kind and name.
  EXPECT_EQ(
      plugin_error([&] { registry.find("force", "fixture_api99"); }),
      "no force plugin named 'fixture_api99'; available: fixture_scaler; searched: " + kDir +
          "; a candidate failed: " + fixture("fixture_api99") +
          ": plugin API 99.0 does not match this fldsim (API " FLDSIM_STR(FLDSIM_API_MAJOR) "." FLDSIM_STR(
              FLDSIM_API_MINOR) "); rebuild the plugin against this fldsim");
}

// Whether the dynamic loader still has `file` mapped (RTLD_NOLOAD opens nothing new).
bool is_mapped(const std::string& file) {
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (handle) dlclose(handle);
  return handle != nullptr;
}

TEST(PluginRegistry, ObjectOutlivesTheRegistryAndThenReleasesTheLibrary) {
  const std::string file = fixture("fixture_scaler");
  ASSERT_FALSE(is_mapped(file));
  auto registry = std::make_unique<fldsim::PluginRegistry>(std::vector<std::string>{kDir});
  const fldsim::Params p = params_for(registry->find("force", "fixture_scaler"), "{factor: 4}");
  std::shared_ptr<fixture::Scaler> scaler = registry->create<fixture::Scaler>("force", "fixture_scaler", p);
  registry.reset();
  // The object's deleter holds the library: still mapped, and its virtual functions still run.
  ASSERT_TRUE(is_mapped(file));
  EXPECT_EQ(scaler->scaled(0.5), 2.0);
  scaler.reset();
  // Nothing holds it any more: the fixture is built with -fno-gnu-unique, so dlclose unmaps it.
  EXPECT_FALSE(is_mapped(file));
}

}  // namespace
