// Search order: YAML plugins.paths (relative to the YAML file), FLDSIM_PLUGIN_PATH, build dir,
// install dir; missing directories skipped, repeats dropped.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "plugins/PluginRegistry.hpp"

namespace {

namespace fs = std::filesystem;

TEST(PluginSearchPath, OrderSkipsMissingAndDropsRepeats) {
  const fs::path root = fs::temp_directory_path() / ("fldsim-search-test-" + std::to_string(::getpid()));
  const fs::path yaml_dir = root / "exp", rel = yaml_dir / "myplugins", abs = root / "abs",
                 env = root / "env";
  for (const auto& d : {rel, abs, env}) fs::create_directories(d);

  const std::string env_value = env.string() + "::" + (root / "missing").string() + ":" + abs.string();
  ASSERT_EQ(::setenv("FLDSIM_PLUGIN_PATH", env_value.c_str(), 1), 0);
  const auto path =
      fldsim::PluginRegistry::search_path({"myplugins", abs.string(), "nothere"}, yaml_dir.string());

  ASSERT_GE(path.size(), 3u);
  EXPECT_EQ(path[0], rel.string());
  EXPECT_EQ(path[1], abs.string());
  EXPECT_EQ(path[2], env.string());  // abs again in the env var: dropped; missing: skipped
  // Then the build plugin directory (the same one the tests get), when it exists.
  std::size_t next = 3;
  if (fs::is_directory(FLDSIM_TEST_PLUGIN_DIR)) {
    ASSERT_GE(path.size(), 4u);
    EXPECT_EQ(path[3], FLDSIM_TEST_PLUGIN_DIR);
    next = 4;
  }
  EXPECT_LE(path.size(), next + 1);  // at most the install directory after that
  for (const auto& p : path) EXPECT_TRUE(fs::is_directory(p)) << p;
  fs::remove_all(root);
}

}  // namespace
