// ParamSchema: the declaration side of plugin parameters, and the human-readable expectation
// ("a number > 2") that error messages and `fldsim plugins` print.
#include <cmath>

#include "config/NumberText.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

const char* to_string(ParamType t) {
  switch (t) {
    case ParamType::Number:
      return "number";
    case ParamType::Integer:
      return "integer";
    case ParamType::Flag:
      return "flag";
    case ParamType::Text:
      return "text";
    case ParamType::Choice:
      return "choice";
    case ParamType::NumberList:
      return "number list";
    case ParamType::NumberTable:
      return "number table";
  }
  return "unknown";
}

namespace {

// " > 2 and <= 5", or "" when unbounded.
std::string range_text(const ParamSpec& s) {
  std::string out;
  if (std::isfinite(s.min)) out += (s.min_exclusive ? " > " : " >= ") + format_number(s.min);
  if (std::isfinite(s.max)) {
    if (!out.empty()) out += " and";
    out += (s.max_exclusive ? " < " : " <= ") + format_number(s.max);
  }
  return out;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}

ParamSpec make_spec(const std::string& name, ParamType type, const std::string& unit,
                    const std::string& help) {
  ParamSpec s;
  s.name = name;
  s.type = type;
  s.unit = unit;
  s.help = help;
  return s;
}

}  // namespace

std::string ParamSpec::expectation() const {
  const std::string range = range_text(*this);
  const std::string count = list_size ? std::to_string(list_size) + " " : "";
  switch (type) {
    case ParamType::Number:
      return "a number" + range + (choices.empty() ? "" : " or " + join(choices));
    case ParamType::Integer:
      return "an integer" + range;
    case ParamType::Flag:
      return "true or false";
    case ParamType::Text:
      return "a string";
    case ParamType::Choice:
      return "one of: " + join(choices);
    case ParamType::NumberList:
      return "a list of " + count + "numbers" + range;
    case ParamType::NumberTable:
      return "a list of rows of " + count + "numbers" + range;
  }
  return "a value";
}

ParamSpec& ParamSchema::add(ParamSpec s) {
  for (auto& existing : specs_) {
    if (existing.name == s.name) {
      // A plugin declaring a key twice is a programming error in the plugin: keep the last.
      existing = std::move(s);
      return existing;
    }
  }
  specs_.push_back(std::move(s));
  return specs_.back();
}

const ParamSpec* ParamSchema::find(const std::string& name) const {
  for (const auto& s : specs_)
    if (s.name == name) return &s;
  return nullptr;
}

ParamSpec& ParamSchema::number(const std::string& name, std::optional<double> def, const std::string& unit,
                               const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::Number, unit, help);
  if (def) s.default_value = *def;
  return add(std::move(s));
}

ParamSpec& ParamSchema::integer(const std::string& name, std::optional<long> def, const std::string& unit,
                                const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::Integer, unit, help);
  if (def) s.default_value = *def;
  return add(std::move(s));
}

ParamSpec& ParamSchema::flag(const std::string& name, bool def, const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::Flag, "", help);
  s.default_value = def;
  return add(std::move(s));
}

ParamSpec& ParamSchema::text(const std::string& name, std::optional<std::string> def,
                             const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::Text, "", help);
  if (def) s.default_value = *def;
  return add(std::move(s));
}

ParamSpec& ParamSchema::choice(const std::string& name, std::optional<std::string> def,
                               std::vector<std::string> choices, const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::Choice, "", help);
  if (def) s.default_value = *def;
  s.choices = std::move(choices);
  return add(std::move(s));
}

ParamSpec& ParamSchema::numbers(const std::string& name, std::optional<std::vector<double>> def,
                                const std::string& unit, const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::NumberList, unit, help);
  if (def) s.default_value = *def;
  return add(std::move(s));
}

ParamSpec& ParamSchema::table(const std::string& name, std::optional<std::vector<std::vector<double>>> def,
                              const std::string& unit, const std::string& help) {
  ParamSpec s = make_spec(name, ParamType::NumberTable, unit, help);
  if (def) s.default_value = *def;
  return add(std::move(s));
}

}  // namespace fldsim
