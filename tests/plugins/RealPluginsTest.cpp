// Every plugin actually built into the project's plugin directory must load through the real
// loader, carry a valid descriptor, and declare defaults that pass its own schema.
#include <gtest/gtest.h>

#include <filesystem>

#include "config/YamlValidation.hpp"
#include "plugins/PluginRegistry.hpp"

namespace {

namespace fs = std::filesystem;

std::size_t count_libraries(const std::string& dir) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".so") ++n;
  return n;
}

// A YAML map holding every defaulted key of `schema` at its default value.
YAML::Node defaults_as_yaml(const fldsim::ParamSchema& schema) {
  YAML::Node map(YAML::NodeType::Map);
  for (const auto& spec : schema.specs()) {
    if (!spec.default_value) continue;
    std::visit([&](const auto& v) { map[spec.name] = v; }, *spec.default_value);
  }
  return YAML::Load(YAML::Dump(map));  // reparse so that nodes carry positions and plain tags
}

TEST(RealPlugins, AllBuiltPluginsLoadAndTheirDefaultsAreValid) {
  const std::string dir = FLDSIM_TEST_PLUGIN_DIR;
  const std::size_t files = count_libraries(dir);
  if (files == 0) GTEST_SKIP() << "no plugin built yet in " << dir;

  const fldsim::PluginRegistry registry({dir});
  EXPECT_TRUE(registry.failures().empty()) << ::testing::PrintToString(registry.failures());
  EXPECT_TRUE(registry.shadowed().empty()) << ::testing::PrintToString(registry.shadowed());
  EXPECT_EQ(registry.plugins().size(), files);
  for (const auto& info : registry.plugins()) {
    SCOPED_TRACE(info.file);
    EXPECT_FALSE(info.name.empty());
    EXPECT_FALSE(info.version.empty());
    EXPECT_FALSE(info.summary.empty());
    // The file is named after the plugin by fldsim_add_plugin().
    EXPECT_EQ(fs::path(info.file).filename().string(), "fldsim-" + info.kind + "-" + info.name + ".so");
    fldsim::ConfigErrors errors(info.file + "(defaults)");
    fldsim::validate_params(defaults_as_yaml(info.schema), info.schema, info.kind + "." + info.name, errors);
    // Only required keys may be reported (they have no default to check).
    std::size_t required = 0;
    for (const auto& spec : info.schema.specs()) required += spec.default_value ? 0 : 1;
    EXPECT_EQ(errors.size(), required) << errors.text();
  }
}

}  // namespace
