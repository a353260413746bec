#include "config/ConfigErrors.hpp"

#include <algorithm>
#include <cctype>

#include "fldsim/error.hpp"

namespace fldsim {

namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Reads ":line:col" off the end of a location; (0, 0) when it has none.
std::pair<long, long> line_and_column(const std::string& location) {
  const auto c2 = location.rfind(':');
  if (c2 == std::string::npos || c2 == 0) return {0, 0};
  const auto c1 = location.rfind(':', c2 - 1);
  if (c1 == std::string::npos) return {0, 0};
  const std::string line = location.substr(c1 + 1, c2 - c1 - 1);
  const std::string col = location.substr(c2 + 1);
  if (!all_digits(line) || !all_digits(col)) return {0, 0};
  return {std::stol(line), std::stol(col)};
}

}  // namespace

std::string location_of(const std::string& file, const YAML::Node& node) {
  if (!node.IsDefined()) return file;
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return file;
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

ConfigErrors::ConfigErrors(std::string file) : file_(std::move(file)) {}

void ConfigErrors::add_override(const YAML::Node& key, const YAML::Node& value, const std::string& label) {
  if (key.IsDefined()) overridden_.emplace_back(key, label);
  // Every node of the value, depth first (a value is a few nodes: a scalar, a short list).
  std::vector<YAML::Node> todo{value};
  while (!todo.empty()) {
    YAML::Node n = todo.back();
    todo.pop_back();
    if (!n.IsDefined()) continue;
    overridden_.emplace_back(n, label);
    if (n.IsSequence())
      for (const auto& child : n) todo.push_back(child);
    else if (n.IsMap())
      for (const auto& kv : n) {
        todo.push_back(kv.first);
        todo.push_back(kv.second);
      }
  }
}

std::string ConfigErrors::location(const YAML::Node& node) const {
  if (node.IsDefined())
    for (const auto& [n, label] : overridden_)
      if (n.is(node)) return label;
  return location_of(file_, node);
}

void ConfigErrors::add(const YAML::Node& where, const std::string& path, const std::string& message) {
  add(location(where), path, message);
}

void ConfigErrors::add(const std::string& location, const std::string& path, const std::string& message) {
  const auto [line, column] = line_and_column(location);
  std::string text = location + ": ";
  if (!path.empty()) text += path + ": ";
  text += message;
  entries_.push_back({line, column, std::move(text)});
}

void ConfigErrors::add_formatted(const std::string& text) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    if (line.empty()) continue;
    const std::size_t sep = line.find(": ");
    const auto [l, c] = line_and_column(sep == std::string::npos ? std::string() : line.substr(0, sep));
    entries_.push_back({l, c, std::move(line)});
  }
}

std::string ConfigErrors::text() const {
  std::vector<Entry> sorted = entries_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  });
  std::string out;
  for (std::size_t i = 0; i < sorted.size(); ++i) out += (i ? "\n" : "") + sorted[i].text;
  return out;
}

void ConfigErrors::throw_if_any() const {
  if (!entries_.empty()) throw ConfigError(text());
}

}  // namespace fldsim
