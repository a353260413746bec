// Writes YAML snippets to real files so that error locations (file:line:col) are real.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fldsim_test {

class TempYaml {
 public:
  TempYaml() {
    dir_ = std::filesystem::temp_directory_path() /
           ("fldsim-config-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter_++));
    std::filesystem::create_directories(dir_);
  }
  ~TempYaml() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempYaml(const TempYaml&) = delete;
  TempYaml& operator=(const TempYaml&) = delete;

  std::string write(const std::string& name, const std::string& text) const {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  static inline int counter_ = 0;
  std::filesystem::path dir_;
};

}  // namespace fldsim_test
