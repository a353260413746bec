// Collects every problem found in an experiment file, then reports them all at once in file
// order, so the user fixes the whole file in one round rather than one error per run.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace fldsim {

// "file:line:col" of a node, 1-based (yaml-cpp marks are 0-based); just "file" when the node
// carries no position (e.g. an undefined node).
std::string location_of(const std::string& file, const YAML::Node& node);

class ConfigErrors {
 public:
  explicit ConfigErrors(std::string file);

  // Nodes put in by a command-line override (the value's whole subtree, and the key it was
  // stored under) are reported as `label`, e.g. "--set run.dt=abc", instead of a place in the
  // file they never were in.
  void add_override(const YAML::Node& key, const YAML::Node& value, const std::string& label);
  // "file:line:col" of a node of the file, the override label of an overridden one.
  std::string location(const YAML::Node& node) const;

  void add(const YAML::Node& where, const std::string& path, const std::string& message);
  // `location` is "file:line:col" (or just "file"); an empty `path` leaves out the key part.
  void add(const std::string& location, const std::string& path, const std::string& message);

  // Lines already formatted as "location: path: message" (a ConfigError's text).
  void add_formatted(const std::string& text);

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  // One "location: path: message" per line, sorted by (line, col); position-less ones first.
  std::string text() const;
  // Throws ConfigError(text()) when anything was added.
  void throw_if_any() const;
  const std::string& file() const { return file_; }

 private:
  struct Entry {
    long line;
    long column;
    std::string text;
  };
  std::string file_;
  std::vector<Entry> entries_;
  std::vector<std::pair<YAML::Node, std::string>> overridden_;
};

}  // namespace fldsim
