#include "config/YamlValidation.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "config/YamlDocumentScan.hpp"
#include "fldsim/error.hpp"

namespace fldsim {

namespace {

// A quoted scalar ('1.5', "yes") is text by the user's choice: never read it as a number or flag.
bool is_plain_scalar(const YAML::Node& n) {
  return n.IsScalar() && n.Tag() != "!";
}

// YAML 1.2 core-schema decimal float/int: [+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)?
// (".inf"/".nan" are refused: no parameter has a use for them).
std::optional<double> parse_number(const std::string& s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t mantissa_start = i;
  std::size_t digits = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i, ++digits;
  }
  if (digits == 0) return std::nullopt;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i, ++exponent_digits;
    if (exponent_digits == 0) return std::nullopt;
  }
  if (i != s.size()) return std::nullopt;
  double v = 0;
  const char* begin = s.data() + mantissa_start;
  const auto r = std::from_chars(begin, s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return (mantissa_start == 1 && s[0] == '-') ? -v : v;
}

std::optional<double> as_number(const YAML::Node& n) {
  if (!is_plain_scalar(n)) return std::nullopt;
  return parse_number(n.Scalar());
}

// Integers accept "100" and "1e3" but not "2.5"; exact for the whole long range.
std::optional<long> as_integer(const YAML::Node& n) {
  if (!is_plain_scalar(n)) return std::nullopt;
  const std::string& s = n.Scalar();
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  long exact = 0;
  const auto r = std::from_chars(begin, s.data() + s.size(), exact);
  if (r.ec == std::errc() && r.ptr == s.data() + s.size()) return exact;
  const auto v = parse_number(s);
  // 2^63 is exactly representable; every double below it in magnitude that is integral fits a long.
  if (!v || std::floor(*v) != *v || std::fabs(*v) >= 9223372036854775808.0) return std::nullopt;
  return static_cast<long>(*v);
}

std::optional<bool> as_flag(const YAML::Node& n) {
  if (!is_plain_scalar(n)) return std::nullopt;
  std::string s = n.Scalar();
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "true" || s == "yes") return true;
  if (s == "false" || s == "no") return false;
  return std::nullopt;
}

bool in_range(const ParamSpec& spec, double v) {
  if (std::isnan(v)) return false;
  if (spec.min_exclusive ? !(v > spec.min) : !(v >= spec.min)) return false;
  if (spec.max_exclusive ? !(v < spec.max) : !(v <= spec.max)) return false;
  return true;
}

std::string dotted(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// Checks one value against its spec; returns the converted value, or nothing after reporting.
class ValueReader {
 public:
  ValueReader(ConfigErrors& errors, const std::string& path) : errors_(errors), path_(path) {}

  std::optional<ParamValue> read(const ParamSpec& spec, const YAML::Node& n) {
    switch (spec.type) {
      case ParamType::Number:
        return number(spec, n, path_);
      case ParamType::Integer:
        return integer(spec, n);
      case ParamType::Flag:
        return flag(spec, n);
      case ParamType::Text:
        return text(spec, n);
      case ParamType::Choice:
        return choice(spec, n);
      case ParamType::NumberList:
        return list(spec, n, path_);
      case ParamType::NumberTable:
        return table(spec, n);
    }
    return std::nullopt;
  }

 private:
  void wrong(const YAML::Node& n, const std::string& path, const std::string& expected,
             const std::string& suffix = "") {
    errors_.add(n, path, "expected " + expected + ", got " + describe_yaml_value(n) + suffix);
  }

  std::optional<ParamValue> number(const ParamSpec& spec, const YAML::Node& n, const std::string& path) {
    if (n.IsScalar() && std::find(spec.choices.begin(), spec.choices.end(), n.Scalar()) != spec.choices.end())
      return n.Scalar();  // a word the spec accepts instead of a number (`dt: auto`)
    const auto v = as_number(n);
    if (v && in_range(spec, *v)) return *v;
    ParamSpec element = spec;
    element.type = ParamType::Number;
    wrong(n, path, element.expectation());
    return std::nullopt;
  }

  std::optional<ParamValue> integer(const ParamSpec& spec, const YAML::Node& n) {
    const auto v = as_integer(n);
    if (v && in_range(spec, static_cast<double>(*v))) return *v;
    wrong(n, path_, spec.expectation());
    return std::nullopt;
  }

  std::optional<ParamValue> flag(const ParamSpec& spec, const YAML::Node& n) {
    if (const auto v = as_flag(n)) return *v;
    wrong(n, path_, spec.expectation());
    return std::nullopt;
  }

  std::optional<ParamValue> text(const ParamSpec& spec, const YAML::Node& n) {
    if (n.IsScalar()) return n.Scalar();
    wrong(n, path_, spec.expectation());
    return std::nullopt;
  }

  std::optional<ParamValue> choice(const ParamSpec& spec, const YAML::Node& n) {
    if (n.IsScalar()) {
      const std::string& s = n.Scalar();
      if (std::find(spec.choices.begin(), spec.choices.end(), s) != spec.choices.end()) return s;
      const std::string guess = did_you_mean(s, spec.choices);
      wrong(n, path_, spec.expectation(), guess.empty() ? "" : " (did you mean '" + guess + "'?)");
      return std::nullopt;
    }
    wrong(n, path_, spec.expectation());
    return std::nullopt;
  }

  // A sequence of numbers; `path` names the list (a table passes "key[i]" for its rows).
  std::optional<ParamValue> list(const ParamSpec& spec, const YAML::Node& n, const std::string& path) {
    ParamSpec as_list = spec;
    as_list.type = ParamType::NumberList;
    if (!n.IsSequence()) {
      wrong(n, path, as_list.expectation());
      return std::nullopt;
    }
    if (spec.list_size != 0 && n.size() != spec.list_size) {
      errors_.add(n, path,
                  "expected " + as_list.expectation() + ", got a list of " + std::to_string(n.size()));
      return std::nullopt;
    }
    std::vector<double> out;
    bool ok = true;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto v = number(spec, n[i], path + "[" + std::to_string(i) + "]");
      if (v) out.push_back(std::get<double>(*v));
      ok = ok && v.has_value();
    }
    if (!ok) return std::nullopt;
    return out;
  }

  std::optional<ParamValue> table(const ParamSpec& spec, const YAML::Node& n) {
    if (!n.IsSequence()) {
      wrong(n, path_, spec.expectation());
      return std::nullopt;
    }
    std::vector<std::vector<double>> out;
    bool ok = true;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto row = list(spec, n[i], path_ + "[" + std::to_string(i) + "]");
      if (row) out.push_back(std::get<std::vector<double>>(*row));
      ok = ok && row.has_value();
    }
    if (!ok) return std::nullopt;
    return out;
  }

  ConfigErrors& errors_;
  const std::string& path_;
};

std::vector<std::string> schema_names(const ParamSchema& schema) {
  std::vector<std::string> names;
  for (const auto& s : schema.specs()) names.push_back(s.name);
  return names;
}

std::string missing_message(const ParamSpec& spec) {
  std::string what = spec.expectation();
  if (!spec.unit.empty()) what += ", in " + spec.unit;
  return "missing required key (" + what + ")";
}

std::string unknown_key_message(const std::string& key, const ParamSchema& schema) {
  const auto names = schema_names(schema);
  const std::string guess = did_you_mean(key, names);
  if (!guess.empty()) return "unknown key (did you mean '" + guess + "'?)";
  if (names.empty()) return "unknown key (this block takes no parameters)";
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) list += (i ? ", " : "") + names[i];
  return "unknown key (known keys: " + list + ")";
}

}  // namespace

std::string describe_yaml_value(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "null";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  if (is_plain_scalar(n) && (parse_number(n.Scalar()) || as_flag(n))) return n.Scalar();
  return "'" + n.Scalar() + "'";
}

namespace {

constexpr std::uintmax_t kMaxFileBytes = 16u << 20;  // an experiment is a few KiB; tables of positions more
constexpr std::size_t kMaxNodes = 1000000;           // after aliases are expanded ("billion laughs")
constexpr std::size_t kMaxDepth = 64;

std::string at(const std::string& path, const YAML::Mark& m) {
  if (m.is_null()) return path;
  return path + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

// A tab among a line's leading spaces: YAML indents with spaces only, and yaml-cpp's own
// message for it ("end of map not found") does not say so.
std::optional<std::pair<int, int>> tab_in_indentation(const std::string& text) {
  int line = 1, column = 1;
  bool leading = true;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      column = 1;
      leading = true;
      continue;
    }
    if (leading && c == '\t') return std::make_pair(line, column);
    if (c != ' ') leading = false;
    ++column;
  }
  return std::nullopt;
}

// The first byte that is not part of valid UTF-8 (YAML files are Unicode text; yaml-cpp
// passes other bytes through into keys and values and then into messages and the result file).
std::optional<std::pair<int, int>> invalid_utf8(const std::string& text) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool ok = len != 0 && i + len <= text.size();
    for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
    if (!ok) return std::make_pair(line, column);
    if (c == '\n') {
      ++line;
      column = 0;
    }
    ++column;
    i += len;
  }
  return std::nullopt;
}

// Every map of the document: duplicate keys (yaml-cpp keeps both; a lookup would see only the
// first), and a size bound so that aliases cannot expand into an enormous tree.
void check_tree(const std::string& path, const YAML::Node& node, std::size_t depth, std::size_t& count,
                ConfigErrors& errors, const std::string& key_path = "") {
  if (++count > kMaxNodes || depth > kMaxDepth) {
    if (count == kMaxNodes + 1 || depth == kMaxDepth + 1)
      errors.add(node, "",
                 "the document nests deeper than " + std::to_string(kMaxDepth) +
                     " levels or expands (through aliases) to more than " + std::to_string(kMaxNodes) +
                     " values");
    throw std::length_error("too large");
  }
  if (node.IsSequence()) {
    std::size_t i = 0;
    for (const auto& child : node)
      check_tree(path, child, depth + 1, count, errors, key_path + "[" + std::to_string(i++) + "]");
  } else if (node.IsMap()) {
    std::vector<std::pair<std::string, YAML::Mark>> seen;
    for (const auto& kv : node) {
      if (kv.first.IsScalar()) {
        const std::string& key = kv.first.Scalar();
        const auto it = std::find_if(seen.begin(), seen.end(), [&](const auto& p) { return p.first == key; });
        if (it != seen.end())
          errors.add(kv.first, dotted(key_path, key),
                     "duplicate key (first given at line " + std::to_string(it->second.line + 1) +
                         "); YAML keeps only one, so this one would be silently lost");
        else
          seen.emplace_back(key, kv.first.Mark());
      }
      const std::string child = kv.first.IsScalar() ? dotted(key_path, kv.first.Scalar()) : key_path;
      check_tree(path, kv.first, depth + 1, count, errors, child);
      check_tree(path, kv.second, depth + 1, count, errors, child);
    }
  }
}

// What yaml-cpp stalled on, for the message: in practice a `,` where a document's node belongs.
std::string stray_token(const std::string& text, const YAML::Mark& m) {
  const char c = m.pos >= 0 && static_cast<std::size_t>(m.pos) < text.size() ? text[m.pos] : '\0';
  if (c == ',') return "a ',' outside [ ] or { } (a comma separates items only inside a flow list or map)";
  if (c == '\0') return "the text ends where a value was expected";
  return std::string("unexpected '") + c + "' where a value was expected";
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw ConfigError(path + ": cannot read: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxFileBytes)
    throw ConfigError(path + ": cannot read: " + std::to_string(size) +
                      " bytes is not an experiment file (limit " + std::to_string(kMaxFileBytes) + ")");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  if (text.find('\0') != std::string::npos)
    throw ConfigError(path + ": cannot read: a binary file (it holds NUL bytes), not a YAML experiment");
  if (const auto bad = invalid_utf8(text))
    throw ConfigError(path + ":" + std::to_string(bad->first) + ":" + std::to_string(bad->second) +
                      ": not UTF-8 text (an experiment file is YAML, which is Unicode)");
  // Scanned first, not YAML::LoadAll: see YamlDocumentScan.hpp for the text LoadAll never returns on.
  YamlDocumentScan scan;
  YAML::Node root;
  try {
    scan = scan_yaml_documents(text);
    if (!scan.stalled_at) root = YAML::Load(text);  // the first document only
  } catch (const YAML::Exception& e) {
    if (const auto tab = tab_in_indentation(text); tab && tab->first <= e.mark.line + 1)
      throw ConfigError(path + ":" + std::to_string(tab->first) + ":" + std::to_string(tab->second) +
                        ": syntax error: a tab in the indentation (YAML indents with spaces only)");
    throw ConfigError(at(path, e.mark) + ": syntax error: " + e.msg);
  }
  if (scan.stalled_at)
    throw ConfigError(at(path, *scan.stalled_at) + ": syntax error: " + stray_token(text, *scan.stalled_at));
  if (root.IsNull())
    throw ConfigError(path + ": empty: expected a map of sections (system, flow, hydro, run, ...)");
  if (scan.documents > 1)
    throw ConfigError(at(path, scan.second_document.value_or(YAML::Mark::null_mark())) +
                      ": a second YAML document: one file holds one experiment (remove the `---` line and "
                      "what follows, or split the file)");
  ConfigErrors errors(path);
  std::size_t count = 0;
  try {
    check_tree(path, root, 0, count, errors);
  } catch (const std::length_error&) {
  }
  errors.throw_if_any();
  return root;
}

Params validate_params(const YAML::Node& node, const ParamSchema& schema, const std::string& path,
                       ConfigErrors& errors, const std::set<std::string>& reserved) {
  Params params(path, errors.location(node));
  // A missing block (an invalid node: its type may not even be asked) validates as an empty map.
  const bool is_map = node.IsDefined() && node.IsMap();
  if (node.IsDefined() && !node.IsNull() && !is_map)
    errors.add(node, path, "expected a map of parameters, got " + describe_yaml_value(node));

  std::set<std::string> seen;
  if (is_map) {
    for (const auto& kv : node) {
      if (!kv.first.IsScalar()) {
        errors.add(kv.first, path, "expected a key name, got " + describe_yaml_value(kv.first));
        continue;
      }
      const std::string key = kv.first.Scalar();
      const std::string key_path = dotted(path, key);
      if (!seen.insert(key).second) {
        errors.add(kv.first, key_path, "duplicate key");
        continue;
      }
      if (reserved.count(key)) continue;
      const ParamSpec* spec = schema.find(key);
      if (!spec) {
        errors.add(kv.first, key_path, unknown_key_message(key, schema));
        continue;
      }
      if (kv.second.IsNull()) {
        // yaml-cpp places an empty value at the next token; the key is where the user looks.
        errors.add(kv.first, key_path, "expected " + spec->expectation() + ", got null");
        continue;
      }
      ValueReader reader(errors, key_path);
      if (auto v = reader.read(*spec, kv.second))
        params.set(key, std::move(*v), {errors.location(kv.second), key_path}, true);
    }
  }

  const std::string block_location = errors.location(node);
  for (const auto& spec : schema.specs()) {
    if (params.has(spec.name)) continue;
    const std::string key_path = dotted(path, spec.name);
    if (spec.default_value) {
      // Also fills a given-but-invalid key, so the returned Params is always complete.
      params.set(spec.name, *spec.default_value, {block_location, key_path}, false);
    } else if (!seen.count(spec.name)) {
      errors.add(block_location, key_path, missing_message(spec));
    }
  }
  return params;
}

}  // namespace fldsim
