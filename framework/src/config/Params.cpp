// Params: the validated values a plugin reads. Every failure names where the value came from,
// as "file:line:col: dotted.path: message", so a plugin's own checks read like the core's.
#include "fldsim/params.hpp"

#include <variant>

namespace fldsim {

namespace {

// What a stored ParamValue holds, for "x is a list, not a number" messages (plugin bugs).
const char* held_kind(const ParamValue& v) {
  switch (v.index()) {
    case 0:
      return "a number";
    case 1:
      return "an integer";
    case 2:
      return "a flag";
    case 3:
      return "a string";
    case 4:
      return "a number list";
    default:
      return "a number table";
  }
}

std::string dotted(const std::string& block, const std::string& name) {
  return block.empty() ? name : block + "." + name;
}

}  // namespace

void Params::set(const std::string& name, ParamValue v, ParamOrigin origin, bool given) {
  values_[name] = std::move(v);
  origins_[name] = std::move(origin);
  given_[name] = given;
}

void Params::fail(const std::string& name, const std::string& message) const {
  const auto it = origins_.find(name);
  const std::string location =
      (it != origins_.end() && !it->second.location.empty()) ? it->second.location : block_location_;
  const std::string path =
      (it != origins_.end() && !it->second.path.empty()) ? it->second.path : dotted(block_path_, name);
  std::string text;
  if (!location.empty()) text += location + ": ";
  text += path + ": " + message;
  throw ConfigError(text);
}

const ParamValue& Params::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    fail(name, "no such parameter (the plugin reads a key its schema does not declare)");
  return it->second;
}

bool Params::given(const std::string& name) const {
  const auto it = given_.find(name);
  return it != given_.end() && it->second;
}

double Params::number(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* l = std::get_if<long>(&v)) return static_cast<double>(*l);  // an integer is a number
  fail(name, std::string("is ") + held_kind(v) + ", not a number");
}

long Params::integer(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* l = std::get_if<long>(&v)) return *l;
  fail(name, std::string("is ") + held_kind(v) + ", not an integer");
}

bool Params::flag(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  fail(name, std::string("is ") + held_kind(v) + ", not a flag");
}

const std::string& Params::text(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  fail(name, std::string("is ") + held_kind(v) + ", not a string");
}

const std::vector<double>& Params::numbers(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* l = std::get_if<std::vector<double>>(&v)) return *l;
  fail(name, std::string("is ") + held_kind(v) + ", not a number list");
}

const std::vector<std::vector<double>>& Params::table(const std::string& name) const {
  const ParamValue& v = get(name);
  if (const auto* t = std::get_if<std::vector<std::vector<double>>>(&v)) return *t;
  fail(name, std::string("is ") + held_kind(v) + ", not a number table");
}

}  // namespace fldsim
