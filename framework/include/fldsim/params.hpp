// Declared, validated plugin parameters. A plugin describes its parameters in a ParamSchema;
// the core checks the YAML node against it (type, range, choices, required, unknown keys with
// a did-you-mean) and hands the plugin a Params holding only validated values. Plugins never
// see yaml-cpp, so they do not depend on its ABI.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fldsim/api.hpp"
#include "fldsim/error.hpp"

namespace fldsim {

enum class ParamType { Number, Integer, Flag, Text, Choice, NumberList, NumberTable };

const char* to_string(ParamType t);

using ParamValue =
    std::variant<double, long, bool, std::string, std::vector<double>, std::vector<std::vector<double>>>;

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Number;
  std::string unit;  // e.g. "a", "kT", "steps"; empty for dimensionless
  std::string help;
  std::optional<ParamValue> default_value;  // absent = required
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::vector<std::string> choices;  // for Choice; for Number: words accepted instead of a number
  std::size_t list_size = 0;         // for NumberList / rows of NumberTable: 0 = any length

  // Range builders, chainable: s.number(...).greater(2.0).at_most(5.0)
  ParamSpec& greater(double v) { min = v; min_exclusive = true; return *this; }
  ParamSpec& at_least(double v) { min = v; min_exclusive = false; return *this; }
  ParamSpec& less(double v) { max = v; max_exclusive = true; return *this; }
  ParamSpec& at_most(double v) { max = v; max_exclusive = false; return *this; }
  ParamSpec& length(std::size_t n) { list_size = n; return *this; }
  // A Number that may also be this word (e.g. `dt: auto`); Params::text then returns the word.
  ParamSpec& or_word(std::string word) { choices.push_back(std::move(word)); return *this; }

  // "a number > 2", "an integer >= 1", "one of: a, b" — used in error messages and docs.
  std::string expectation() const;
};

class FLDSIM_VISIBLE ParamSchema {
 public:
  ParamSpec& number(const std::string& name, std::optional<double> def, const std::string& unit,
                    const std::string& help);
  ParamSpec& integer(const std::string& name, std::optional<long> def, const std::string& unit,
                     const std::string& help);
  ParamSpec& flag(const std::string& name, bool def, const std::string& help);
  ParamSpec& text(const std::string& name, std::optional<std::string> def, const std::string& help);
  ParamSpec& choice(const std::string& name, std::optional<std::string> def,
                    std::vector<std::string> choices, const std::string& help);
  ParamSpec& numbers(const std::string& name, std::optional<std::vector<double>> def,
                     const std::string& unit, const std::string& help);
  ParamSpec& table(const std::string& name, std::optional<std::vector<std::vector<double>>> def,
                   const std::string& unit, const std::string& help);

  const std::vector<ParamSpec>& specs() const { return specs_; }
  const ParamSpec* find(const std::string& name) const;
  // Append a complete spec (used by the core to merge its own keys into a plugin's schema).
  ParamSpec& add(ParamSpec s);

 private:
  std::vector<ParamSpec> specs_;
};

// Where a value came from, for error messages: "exp.yaml:12:5" and "hydro.cutoff".
struct ParamOrigin {
  std::string location;  // file:line:col of the value (or of the parent map when defaulted)
  std::string path;      // dotted key path
};

class FLDSIM_VISIBLE Params {
 public:
  Params() = default;
  Params(std::string block_path, std::string block_location)
      : block_path_(std::move(block_path)), block_location_(std::move(block_location)) {}

  // `given` = false marks a value filled in from the schema default.
  void set(const std::string& name, ParamValue v, ParamOrigin origin, bool given = true);

  double number(const std::string& name) const;
  long integer(const std::string& name) const;
  bool flag(const std::string& name) const;
  const std::string& text(const std::string& name) const;  // Text and Choice
  const std::vector<double>& numbers(const std::string& name) const;
  const std::vector<std::vector<double>>& table(const std::string& name) const;
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  // True when the user wrote the key, false when the default was used.
  bool given(const std::string& name) const;

  // Throws a ConfigError "file:line:col: path.name: message" for a check that spans several
  // parameters or needs the plugin's knowledge (e.g. "c must be < a + b").
  [[noreturn]] void fail(const std::string& name, const std::string& message) const;

  const std::string& block_path() const { return block_path_; }
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& get(const std::string& name) const;
  std::string block_path_;
  std::string block_location_;
  std::map<std::string, ParamValue> values_;
  std::map<std::string, ParamOrigin> origins_;
  std::map<std::string, bool> given_;
};

}  // namespace fldsim
