#include "sweep/SweepPlan.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <set>

#include "config/ConfigErrors.hpp"
#include "config/DidYouMean.hpp"
#include "config/YamlValidation.hpp"

namespace fldsim {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kSweepKeys = {"base", "output_dir", "threads", "axes", "repeats", "overrides"};

std::string suggestion(const std::string& key, const std::vector<std::string>& known) {
  const std::string guess = did_you_mean(key, known);
  return guess.empty() ? "" : " (did you mean '" + guess + "'?)";
}

std::string flow_yaml(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetSeqFormat(YAML::Flow);
  e.SetMapFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

// A dotted key as `--set` takes it: words of letters, digits and '_' joined by '.', list
// indices as `[i]` or `.i`.
bool valid_key(const std::string& k) {
  if (k.empty() || k.front() == '.' || k.back() == '.' || k.find("..") != std::string::npos) return false;
  for (char c : k)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '[' || c == ']'))
      return false;
  return true;
}

// A label piece: the value's text with anything but [A-Za-z0-9.+-] replaced by '_'.
std::string label_text(const std::string& s) {
  std::string out;
  for (char c : s)
    out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-') ? c : '_';
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "_" : out;
}

std::string last_segment(const std::string& key) {
  const auto dot = key.find_last_of(".]");
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// One entry of `axes`: its keys (one, or several zipped) and their values.
struct Axis {
  std::vector<std::string> keys;
  std::vector<std::vector<SweepValue>> values;  // [value index][key index]
};

void read_axis(const YAML::Node& entry, std::size_t index, ConfigErrors& errors, std::vector<Axis>& axes) {
  const std::string path = "axes[" + std::to_string(index) + "]";
  if (!entry.IsMap() || entry.size() != 1) {
    errors.add(entry, path,
               "expected one `KEY: [values]` or a `zip:` map of keys with equally long lists, got " +
                   describe_yaml_value(entry));
    return;
  }
  const auto kv = *entry.begin();
  const std::string head = kv.first.as<std::string>();
  std::vector<std::pair<YAML::Node, YAML::Node>> columns;  // (key node, list)
  if (head == "zip") {
    if (!kv.second.IsMap() || kv.second.size() == 0) {
      errors.add(kv.second, path + ".zip",
                 "expected a map of KEY: [values], got " + describe_yaml_value(kv.second));
      return;
    }
    for (const auto& z : kv.second) columns.emplace_back(z.first, z.second);
  } else {
    columns.emplace_back(kv.first, kv.second);
  }
  Axis axis;
  std::size_t length = 0;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::string key = columns[c].first.as<std::string>();
    const YAML::Node& list = columns[c].second;
    if (!valid_key(key)) {
      errors.add(columns[c].first, path,
                 "'" + key + "' is not a dotted key such as flow.peclet or observers[0].every");
      return;
    }
    if (!list.IsSequence() || list.size() == 0) {
      errors.add(list, path + "." + key,
                 "expected a non-empty list of values, got " + describe_yaml_value(list));
      return;
    }
    if (c == 0)
      length = list.size();
    else if (list.size() != length) {
      errors.add(list, path + ".zip." + key,
                 "zipped lists must be equally long: " + std::to_string(list.size()) + " values here, " +
                     std::to_string(length) + " for " + axis.keys.front());
      return;
    }
    axis.keys.push_back(key);
  }
  axis.values.assign(length, {});
  for (std::size_t c = 0; c < columns.size(); ++c)
    for (std::size_t v = 0; v < length; ++v) {
      const YAML::Node value = columns[c].second[v];
      axis.values[v].push_back(
          SweepValue{axis.keys[c], flow_yaml(value), errors.location(value), "axis " + axis.keys[c]});
    }
  axes.push_back(std::move(axis));
}

struct Override {
  std::vector<std::pair<std::string, std::vector<std::string>>> when;  // key, accepted values (YAML text)
  std::vector<SweepValue> set;
};

void read_override(const YAML::Node& entry, std::size_t index, const std::set<std::string>& axis_keys,
                   ConfigErrors& errors, std::vector<Override>& out) {
  const std::string path = "overrides[" + std::to_string(index) + "]";
  if (!entry.IsMap() || !entry["set"] || !entry["set"].IsMap()) {
    errors.add(entry, path, "expected {when: {AXIS_KEY: value or [values]}, set: {KEY: value}}");
    return;
  }
  for (const auto& kv : entry) {
    const std::string k = kv.first.as<std::string>();
    if (k != "when" && k != "set") errors.add(kv.first, path, "unknown key '" + k + "' (expected when, set)");
  }
  Override o;
  if (const YAML::Node when = entry["when"]) {
    if (!when.IsMap()) {
      errors.add(when, path + ".when", "expected a map of axis keys, got " + describe_yaml_value(when));
      return;
    }
    for (const auto& kv : when) {
      const std::string key = kv.first.as<std::string>();
      if (!axis_keys.count(key)) {
        errors.add(
            kv.first, path + ".when",
            "'" + key + "' is not an axis key" + suggestion(key, {axis_keys.begin(), axis_keys.end()}));
        continue;
      }
      std::vector<std::string> accepted;
      if (kv.second.IsSequence())
        for (const auto& v : kv.second) accepted.push_back(flow_yaml(v));
      else
        accepted.push_back(flow_yaml(kv.second));
      o.when.emplace_back(key, accepted);
    }
  }
  for (const auto& kv : entry["set"]) {
    const std::string key = kv.first.as<std::string>();
    if (!valid_key(key)) {
      errors.add(kv.first, path + ".set", "'" + key + "' is not a dotted key such as run.dt");
      continue;
    }
    o.set.push_back(SweepValue{key, flow_yaml(kv.second), errors.location(kv.second), path + ".set"});
  }
  out.push_back(std::move(o));
}

// A path written in the sweep file is relative to the sweep file, as a path in an experiment file
// is relative to that file (docs/sweep.md): made absolute here, before it becomes a `--set`, which
// `fldsim run` would otherwise resolve against the current directory.
const std::set<std::string> kPathKeys = {"system.init.file", "plugins.paths"};

std::string anchored_path_value(const std::string& yaml, const fs::path& dir) {
  YAML::Node value = YAML::Load(yaml);
  auto anchor = [&](YAML::Node n) {
    if (n.IsScalar() && !n.Scalar().empty() && fs::path(n.Scalar()).is_relative())
      n = (dir / n.Scalar()).lexically_normal().string();
  };
  if (value.IsSequence())
    for (std::size_t i = 0; i < value.size(); ++i) anchor(value[i]);
  else
    anchor(value);
  return flow_yaml(value);
}

// YAML texts of two scalars name the same value when they parse to the same number, or are equal.
bool same_value(const std::string& a, const std::string& b) {
  if (a == b) return true;
  try {
    std::size_t ia = 0, ib = 0;
    const double x = std::stod(a, &ia), y = std::stod(b, &ib);
    return ia == a.size() && ib == b.size() && x == y;
  } catch (...) {
    return false;
  }
}

}  // namespace

std::vector<std::string> SweepPoint::overrides() const {
  std::vector<std::string> out;
  for (const auto& s : settings) out.push_back(s.key + "=" + s.yaml);
  return out;
}

std::string SweepPoint::describe() const {
  std::string out;
  for (const auto& v : axis) out += (out.empty() ? "" : ", ") + v.key + " = " + v.yaml;
  return out.empty() ? "the base experiment" : out;
}

std::string SweepPlan::output_of(const SweepPoint& p) const {
  return (fs::path(output_dir) / (p.label + ".h5")).string();
}

SweepPlan read_sweep_plan(const std::string& file,
                          const std::function<BaseSeeds(const std::string& base)>& base_seeds) {
  const YAML::Node root = load_yaml_file(file);
  ConfigErrors errors(file);
  SweepPlan plan;
  plan.file = file;
  if (!root.IsMap()) {
    errors.add(root, "", "expected a sweep: a map with base, axes, ... (docs/sweep.md)");
    errors.throw_if_any();
  }
  for (const auto& kv : root) {
    const std::string k = kv.first.as<std::string>();
    if (std::find(kSweepKeys.begin(), kSweepKeys.end(), k) == kSweepKeys.end())
      errors.add(kv.first, "", "unknown key '" + k + "'" + suggestion(k, kSweepKeys));
  }
  const fs::path dir = fs::path(file).parent_path();
  auto resolve = [&](const std::string& p) {
    return fs::path(p).is_absolute() ? p : (dir / p).lexically_normal().string();
  };
  if (!root["base"] || !root["base"].IsScalar())
    errors.add(root["base"] ? root["base"] : root, "base",
               "expected the base experiment file (relative to this file)");
  else {
    plan.base = resolve(root["base"].Scalar());
    std::error_code ec;
    if (!fs::is_regular_file(plan.base, ec))
      errors.add(root["base"], "base",
                 "'" + plan.base + "' is not a readable file (the path is relative to this file)");
  }
  plan.output_dir =
      resolve(root["output_dir"] && root["output_dir"].IsScalar() ? root["output_dir"].Scalar()
                                                                  : fs::path(file).stem().string());
  SweepValue threads_value;
  if (const YAML::Node t = root["threads"]) {
    try {
      plan.threads = t.as<int>();
    } catch (const YAML::Exception&) {
      plan.threads = 0;
    }
    if (plan.threads < 1 || plan.threads > 1024)
      errors.add(
          t, "threads",
          "expected an integer from 1 to 1024 (run.threads of each point), got " + describe_yaml_value(t));
    threads_value = SweepValue{"run.threads", flow_yaml(t), errors.location(t), "threads"};
  } else {
    threads_value = SweepValue{"run.threads", "1", file, "threads"};
  }
  if (const YAML::Node r = root["repeats"]) {
    try {
      plan.repeats = r.as<int>();
    } catch (const YAML::Exception&) {
      plan.repeats = 0;
    }
    if (plan.repeats < 1 || plan.repeats > 10000)
      errors.add(r, "repeats",
                 "expected an integer from 1 to 10000 (runs of every point with seeds + 0, 1, ...), got " +
                     describe_yaml_value(r));
  }
  std::vector<Axis> axes;
  if (const YAML::Node a = root["axes"]) {
    if (!a.IsSequence())
      errors.add(a, "axes",
                 "expected a list of axes (- KEY: [values], or - zip: {...}), got " + describe_yaml_value(a));
    else
      for (std::size_t i = 0; i < a.size(); ++i) read_axis(a[i], i, errors, axes);
  }
  std::set<std::string> axis_keys;
  for (const auto& ax : axes)
    for (const auto& k : ax.keys) {
      if (!axis_keys.insert(k).second) errors.add(root["axes"], "axes", "'" + k + "' is an axis twice");
      plan.axis_keys.push_back(k);
    }
  std::vector<Override> overrides;
  if (const YAML::Node o = root["overrides"]) {
    if (!o.IsSequence())
      errors.add(o, "overrides", "expected a list of {when: ..., set: ...}, got " + describe_yaml_value(o));
    else
      for (std::size_t i = 0; i < o.size(); ++i) read_override(o[i], i, axis_keys, errors, overrides);
  }
  errors.throw_if_any();

  BaseSeeds seeds;
  if (plan.repeats > 1) seeds = base_seeds(plan.base);

  // Labels: the last segment of each axis key, or the whole key where two axes share it.
  std::map<std::string, int> tail_count;
  for (const auto& k : plan.axis_keys) ++tail_count[last_segment(k)];
  auto label_key = [&](const std::string& k) {
    return tail_count[last_segment(k)] > 1 ? k : last_segment(k);
  };

  std::size_t total = static_cast<std::size_t>(plan.repeats);
  for (const auto& ax : axes) total *= ax.values.size();
  if (total > 100000) {
    errors.add(root["axes"], "axes", std::to_string(total) + " points; at most 100000 in one sweep");
    errors.throw_if_any();
  }
  for (std::size_t n = 0; n < total; ++n) {
    SweepPoint p;
    // Mixed-radix digits of n: the first axis varies slowest, the repeat fastest.
    std::size_t rest = n;
    p.repeat = int(rest % std::size_t(plan.repeats));
    rest /= std::size_t(plan.repeats);
    std::vector<std::size_t> digit(axes.size());
    for (std::size_t a = axes.size(); a-- > 0;) {
      digit[a] = rest % axes[a].values.size();
      rest /= axes[a].values.size();
    }
    for (std::size_t a = 0; a < axes.size(); ++a)
      for (const auto& v : axes[a].values[digit[a]]) {
        p.axis.push_back(v);
        // Appended piece by piece: `"_" + std::string` here trips GCC 12's -Wrestrict false positive.
        if (!p.label.empty()) p.label += '_';
        p.label += label_text(label_key(v.key));
        p.label += '-';
        p.label += label_text(v.yaml);
      }
    p.settings = p.axis;
    p.settings.push_back(threads_value);
    if (plan.repeats > 1) {
      const std::string where = errors.location(root["repeats"]);
      p.settings.push_back(SweepValue{"run.seed", std::to_string(seeds.run + p.repeat), where, "repeats"});
      p.settings.push_back(
          SweepValue{"system.init.seed", std::to_string(seeds.init + p.repeat), where, "repeats"});
      p.label += (p.label.empty() ? "" : "_") + std::string("rep") + std::to_string(p.repeat);
    }
    for (const auto& o : overrides) {
      bool match = true;
      for (const auto& [key, accepted] : o.when) {
        bool any = false;
        for (const auto& v : p.axis)
          if (v.key == key)
            for (const auto& a : accepted) any = any || same_value(v.yaml, a);
        match = match && any;
      }
      if (match) p.settings.insert(p.settings.end(), o.set.begin(), o.set.end());
    }
    for (auto& setting : p.settings)
      if (kPathKeys.count(setting.key)) setting.yaml = anchored_path_value(setting.yaml, dir);
    if (p.label.empty()) p.label = "base";
    plan.points.push_back(std::move(p));
  }
  return plan;
}

}  // namespace fldsim
