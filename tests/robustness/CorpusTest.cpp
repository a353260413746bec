// The robustness corpus (issue 14): broken inputs of every kind, each run through the real
// `fldsim` program in a fresh directory. Every case asserts the exit code, the error lines
// (each names file:line:col and key, or the command-line option), no crash or hang, and that
// nothing was left behind. One TEST per class; each prints its row of the class table:
//
//   | class | cases | clear errors | crashes | leftovers |
//
// The core's keys and every parameter of every plugin found are enumerated from their schemas,
// so a new key or plugin parameter is covered without a new case here.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

#include "CorpusRunner.hpp"
#include "plugins/PluginRegistry.hpp"

namespace {

namespace fs = std::filesystem;
using corpus::Case;

const std::string kBase = R"(system:
  shape: {plugin: sphere}
  count: 27
  volume_fraction: 0.05
  init: {method: monte_carlo, seed: 1}
flow: {peclet: 1}
hydro: {plugin: free_draining}
forces:
  - {plugin: repulsion}
run: {dt: 0.01, duration: 0.1, threads: 1}
observers:
  - {plugin: trajectory, every: 5}
output: out.h5
)";

fs::path work_root() {
  static const fs::path root = fs::temp_directory_path() / ("fldsim-corpus-" + std::to_string(::getpid()));
  return root;
}

// The base experiment with `edit` applied, as block-style YAML (real lines and columns).
std::string edited(const std::function<void(YAML::Node&)>& edit) {
  YAML::Node root = YAML::Load(kBase);
  edit(root);
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

std::string regex_escape(const std::string& s) {
  static const std::string special = R"(\^$.|?*+()[]{})";
  std::string out;
  for (char c : s) {
    if (special.find(c) != std::string::npos) out += '\\';
    out += c;
  }
  return out;
}

// An error line at a place in in.yaml for `path`.
std::string at_key(const std::string& path) {
  return "^in\\.yaml:[0-9]+:[0-9]+: " + regex_escape(path) + "(\\[[0-9]+\\])*: ";
}

Case check_case(const std::string& name, const std::string& yaml, std::vector<std::string> lines,
                std::vector<std::string> extra_args = {}) {
  Case c;
  c.name = name;
  c.files["in.yaml"] = yaml;
  c.args = {"check", "in.yaml"};
  c.args.insert(c.args.end(), extra_args.begin(), extra_args.end());
  c.lines = std::move(lines);
  return c;
}

// `run` rather than `check`: the same refusal must come before any file is created.
Case run_case(Case c) {
  c.name += " (run)";
  c.args[0] = "run";
  return c;
}

// A small real run whose result and checkpoint the HDF5 cases start from (made once).
const fs::path& reference_run() {
  static std::once_flag once;
  static fs::path dir = work_root() / "reference";
  std::call_once(once, [] {
    Case c;
    c.name = "reference";
    c.files["in.yaml"] = edited([](YAML::Node& r) {
      r["observers"].push_back(YAML::Load("{plugin: pair_distribution, every: 5, range: 4, bins: 20}"));
    });
    c.args = {"run", "in.yaml", "-q"};
    const corpus::Outcome o = corpus::run_case(c, dir);
    if (o.exit_code != 0) throw std::runtime_error("reference run failed: " + o.err);
  });
  return dir;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class Corpus : public ::testing::Test {
 protected:
  void run_all(const std::string& klass, const std::vector<Case>& cases) {
    corpus::Tally t;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      const fs::path dir = work_root() / (klass + "-" + std::to_string(i));
      const corpus::Outcome o = corpus::run_case(c, dir);
      const corpus::Verdict v = corpus::judge(c, o);
      ++t.cases;
      t.clear += v.clear ? 1 : 0;
      t.crashes += v.crash ? 1 : 0;
      t.leftovers += v.leftover ? 1 : 0;
      EXPECT_TRUE(v.clear && !v.leftover) << klass << " / " << c.name << "\n" << v.why;
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
    std::cout << corpus::table_row(klass, t) << std::endl;
    EXPECT_EQ(t.crashes, 0);
    EXPECT_EQ(t.leftovers, 0);
  }
};

TEST_F(Corpus, YamlSyntax) {
  std::vector<Case> cases;
  auto file = [&](const std::string& name, const std::string& text, const std::string& line) {
    cases.push_back(check_case(name, text, {line}));
  };
  file("tab in indentation", "system:\n\tcount: 3\n",
       "^in\\.yaml:2:1: syntax error: a tab in the indentation");
  file("unclosed flow map", "system: {count: 3\n", "^in\\.yaml:[0-9]+:[0-9]+: syntax error: ");
  file("unclosed quote", "run: {dt: 'x, duration: 1}\n", "^in\\.yaml:[0-9]+:[0-9]+: syntax error: ");
  file("bad indentation", "system:\n  count: 3\n bad: 1\n", "^in\\.yaml:[0-9]+:[0-9]+: syntax error: ");
  file("duplicate top-level key", kBase + "output: other.h5\n",
       "^in\\.yaml:14:1: output: duplicate key \\(first given at line 13\\)");
  file("duplicate nested key", "system:\n  count: 3\n  count: 4\n",
       "^in\\.yaml:3:3: system\\.count: duplicate key");
  file("second document", kBase + "---\nsystem: {count: 5}\n",
       "^in\\.yaml:[0-9]+:[0-9]+: a second YAML document");
  file("empty file", "", "^in\\.yaml: empty: expected a map");
  file("only a comment", "# nothing here\n", "^in\\.yaml: empty: expected a map");
  file("a scalar document", "hello\n", "^in\\.yaml:1:1: \\(top level\\): expected a map of sections");
  file("a list document", "- 1\n- 2\n", "^in\\.yaml:1:1: \\(top level\\): expected a map of sections");
  file("NUL bytes", std::string("system:\0\0\0", 10), "^in\\.yaml: cannot read: a binary file");
  file("deep nesting", std::string(20000, '[') + std::string(20000, ']') + "\n", "^in\\.yaml.*");
  file("alias bomb",
       "a: &a [x, x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
       "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
       "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]\n"
       "g: [*f, *f, *f, *f, *f, *f, *f, *f, *f, *f]\n",
       "^in\\.yaml:[0-9]+:[0-9]+: the document nests deeper than 64 levels or expands");
  file("unknown alias", "system: *nothing\n", "^in\\.yaml:[0-9]+:[0-9]+: syntax error: ");
  file("non-UTF-8 bytes", "system:\n  count: \xff\xfe\n", "^in\\.yaml:2:10: not UTF-8 text");
  // yaml-cpp 0.7's LoadAll never returned on these (a stray flow entry where a document's node
  // belongs); found by the fuzzer under ASan, 3 December 2026.
  const std::string stray_comma = "syntax error: a ',' outside \\[ \\] or \\{ \\}";
  file("a lone comma", ",\n", "^in\\.yaml:1:1: " + stray_comma);
  file("an indented lone comma", "  ,\n", "^in\\.yaml:1:3: " + stray_comma);
  file("a comma after a top-level scalar", "\"x\",\n", "^in\\.yaml:1:4: " + stray_comma);
  file("a comma after a flow map", "{system: {count: 3}},\n", "^in\\.yaml:1:21: " + stray_comma);
  file("a comma after a document marker", "---\n,\n", "^in\\.yaml:2:1: " + stray_comma);
  file("key that is a list", "[a, b]: 1\n" + kBase,
       "^in\\.yaml:1:1: \\(top level\\): expected a section name");
  {
    Case c;
    c.name = "file is a directory";
    c.setup = [](const fs::path& d) { fs::create_directories(d / "in.yaml"); };
    c.args = {"check", "in.yaml"};
    c.lines = {"^in\\.yaml: cannot read: is a directory"};
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "missing file";
    c.args = {"run", "missing.yaml"};
    c.lines = {"^missing\\.yaml: cannot read: No such file or directory"};
    cases.push_back(c);
  }
  run_all("yaml syntax", cases);
}

TEST_F(Corpus, CoreKeys) {
  std::vector<Case> cases;
  // Every core key with values of the wrong type and out of range.
  const std::vector<std::pair<std::string, std::vector<std::string>>> bad = {
      {"system.count", {"abc", "{a: 1}", "0", "-5", "2.5", "4294967297000", "1e9", "[27]"}},
      {"system.volume_fraction", {"0", "0.8", "abc", "[1]", "-0.1", ".nan"}},
      {"system.box_edge", {"-1", "abc", "{}"}},
      {"system.init.method", {"bogus", "{}", "monte-carlo"}},
      {"system.init.seed", {"-1", "x"}},
      {"system.init.sweeps", {"-1", "1e12"}},
      {"system.init.positions", {"[[1, 2]]", "abc", "[[1, 2, x]]"}},
      {"system.init.orientations", {"abc", "[[1, x, 3]]"}},
      {"system.init.file", {"[1]"}},
      {"flow.peclet", {"-1", "abc", "1e400"}},
      {"flow.brownian", {"maybe", "3"}},
      {"run.dt", {"0", "-1", "abc", ".inf", "{x: 1}"}},
      {"run.duration", {"0", "abc", "-3"}},
      {"run.time_unit", {"hours", "1"}},
      {"run.seed", {"-1", "1.5"}},
      {"run.integrator", {"rk4"}},
      {"run.drift", {"x"}},
      {"run.skin", {"0", "-0.3"}},
      {"run.checkpoint_every", {"-1"}},
      {"run.threads", {"-1", "100000"}},
  };
  for (const auto& [path, values] : bad)
    for (const auto& value : values) {
      const std::string yaml = edited([&](YAML::Node& r) {
        std::vector<std::string> keys;
        std::stringstream ss(path);
        for (std::string k; std::getline(ss, k, '.');) keys.push_back(k);
        YAML::Node cur = r;
        for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
          YAML::Node next = cur[keys[i]];
          cur.reset(next);
        }
        cur[keys.back()] = YAML::Load(value);
      });
      Case c = check_case(path + ": " + value, yaml, {at_key(path)});
      cases.push_back(c);
    }
  // Unknown keys, with a did-you-mean where one is close.
  auto unknown = [&](const std::string& name, const std::function<void(YAML::Node&)>& edit,
                     const std::string& line) { cases.push_back(check_case(name, edited(edit), {line})); };
  unknown(
      "top-level typo", [](YAML::Node& r) { r["observer"] = YAML::Load("[]"); },
      at_key("observer") + "unknown key \\(did you mean 'observers'\\?\\)");
  unknown(
      "system typo", [](YAML::Node& r) { r["system"]["cont"] = 3; },
      at_key("system.cont") + "unknown key \\(did you mean 'count'\\?\\)");
  unknown(
      "run typo", [](YAML::Node& r) { r["run"]["dtt"] = 3; }, at_key("run.dtt") + "unknown key");
  unknown(
      "flow typo", [](YAML::Node& r) { r["flow"]["pecelt"] = 3; },
      at_key("flow.pecelt") + "unknown key \\(did you mean 'peclet'\\?\\)");
  unknown(
      "init typo", [](YAML::Node& r) { r["system"]["init"]["sed"] = 3; },
      at_key("system.init.sed") + "unknown key");
  unknown(
      "plugins typo", [](YAML::Node& r) { r["plugins"] = YAML::Load("{path: [x]}"); },
      at_key("plugins.path") + "unknown key \\(did you mean 'paths'\\?\\)");
  // Missing required sections and keys.
  auto missing = [&](const std::string& name, const std::function<void(YAML::Node&)>& edit,
                     std::vector<std::string> lines) {
    cases.push_back(check_case(name, edited(edit), std::move(lines)));
  };
  missing("no system", [](YAML::Node& r) { r.remove("system"); },
          {"^in\\.yaml:1:1: system: missing required section"});
  missing("no run", [](YAML::Node& r) { r.remove("run"); },
          {"^in\\.yaml:1:1: run: missing required section"});
  missing("no hydro", [](YAML::Node& r) { r.remove("hydro"); },
          {"^in\\.yaml:1:1: hydro: missing required section"});
  missing("no count", [](YAML::Node& r) { r["system"].remove("count"); },
          {at_key("system.count") + "missing required key"});
  missing("no volume_fraction", [](YAML::Node& r) { r["system"].remove("volume_fraction"); },
          {at_key("system.volume_fraction") + "missing required key"});
  missing("no dt", [](YAML::Node& r) { r["run"].remove("dt"); }, {at_key("run.dt") + "missing required key"});
  missing("no duration", [](YAML::Node& r) { r["run"].remove("duration"); },
          {at_key("run.duration") + "missing required key"});
  missing("no shape", [](YAML::Node& r) { r["system"].remove("shape"); },
          {at_key("system.shape") + "missing required key"});
  missing("no hydro plugin", [](YAML::Node& r) { r["hydro"] = YAML::Load("{cutoff: 2}"); },
          {at_key("hydro.plugin") + "missing required key"});
  missing("no output", [](YAML::Node& r) { r.remove("output"); },
          {"^in\\.yaml: output: no result file named"});
  // Sections of the wrong kind.
  auto wrong = [&](const std::string& key, const std::string& value, const std::string& line) {
    cases.push_back(
        check_case(key + " is " + value, edited([&](YAML::Node& r) { r[key] = YAML::Load(value); }), {line}));
  };
  wrong("system", "5", at_key("system") + "expected a map");
  wrong("run", "[1, 2]", at_key("run") + "expected a map");
  wrong("flow", "fast", at_key("flow") + "expected a map");
  wrong("forces", "{a: 1}", at_key("forces") + "expected a list");
  wrong("observers", "3", at_key("observers") + "expected a list");
  wrong("output", "[a]", at_key("output") + "expected a file name");
  wrong("plugins", "3", at_key("plugins.paths") + "expected a list");
  wrong("hydro", "fld", at_key("hydro") + "expected a map with a `plugin` key");
  cases.push_back(check_case("plugins.paths entry is a list",
                             edited([](YAML::Node& r) { r["plugins"] = YAML::Load("{paths: [[1]]}"); }),
                             {at_key("plugins.paths[0]") + "expected a directory name"}));
  cases.push_back(
      check_case("unknown plugin name", edited([](YAML::Node& r) { r["hydro"]["plugin"] = "fdl"; }),
                 {at_key("hydro.plugin") + "no hydro plugin named 'fdl' \\(did you mean 'fld'\\?\\)"}));
  cases.push_back(check_case("plugin of another kind",
                             edited([](YAML::Node& r) { r["hydro"]["plugin"] = "sphere"; }),
                             {at_key("hydro.plugin") + "no hydro plugin named 'sphere'"}));
  cases.push_back(check_case("forces entry not a map",
                             edited([](YAML::Node& r) { r["forces"][0] = "repulsion"; }),
                             {at_key("forces[0]") + "expected a map with a `plugin` key"}));
  cases.push_back(check_case("rk3 with Brownian motion at dt: auto", edited([](YAML::Node& r) {
                               r["run"]["integrator"] = "rk3";
                               r["run"]["dt"] = "auto";
                               r["run"]["dt_max"] = 0.01;
                             }),
                             {at_key("run.integrator") + "rk3 with Brownian motion has no error estimate"}));
  cases.push_back(check_case("run.displacement with a fixed step",
                             edited([](YAML::Node& r) { r["run"]["displacement"] = 0.03; }),
                             {at_key("run.displacement") + "only with dt: auto"}));
  cases.push_back(check_case("run.gap_step with a fixed step",
                             edited([](YAML::Node& r) { r["run"]["gap_step"] = 0.005; }),
                             {at_key("run.gap_step") + "only with dt: auto"}));
  cases.push_back(check_case("run.gap_range without run.gap_step", edited([](YAML::Node& r) {
                               r["run"]["dt"] = "auto";
                               r["run"]["dt_max"] = 0.01;
                               r["run"]["gap_range"] = 0.02;
                             }),
                             {at_key("run.gap_range") + "only with run.gap_step"}));
  cases.push_back(check_case("reject_at with the displacement bound alone", edited([](YAML::Node& r) {
                               r["run"]["dt"] = "auto";
                               r["run"]["dt_max"] = 0.01;
                               r["run"]["displacement"] = 0.03;
                               r["run"]["reject_at"] = 5;
                             }),
                             {at_key("run.reject_at") + "only with run.tolerance"}));
  cases.push_back(
      check_case("rk3 with Brownian motion and drift: none", edited([](YAML::Node& r) {
                   r["run"]["integrator"] = "rk3";
                   r["run"]["drift"] = "none";
                 }),
                 {at_key("run.drift") + "rk3 with Brownian motion always has the thermal drift"}));
  cases.push_back(check_case("rk3 with Brownian motion and the midpoint stress", edited([](YAML::Node& r) {
                               r["run"]["integrator"] = "rk3";
                               r["run"]["brownian_stress"] = "midpoint";
                             }),
                             {at_key("run.brownian_stress") + "brownian_stress: midpoint needs"}));
  cases.push_back(
      check_case("leimkuhler_matthews with a configuration-dependent mobility", edited([](YAML::Node& r) {
                   r["hydro"]["plugin"] = "fld";
                   r["run"]["integrator"] = "leimkuhler_matthews";
                 }),
                 {at_key("run.integrator") + "leimkuhler_matthews needs a hydro model without pair terms"}));
  cases.push_back(
      check_case("leimkuhler_matthews with free-draining heteronuclear dicolloids", edited([](YAML::Node& r) {
                   r["system"]["shape"] = YAML::Load("{plugin: dicolloid, a: 1, b: 0.6, c: 1}");
                   r["run"]["integrator"] = "leimkuhler_matthews";
                 }),
                 {at_key("run.integrator") + "leimkuhler_matthews needs a hydro model without pair terms"}));
  cases.push_back(check_case("leimkuhler_matthews at dt: auto", edited([](YAML::Node& r) {
                               r["run"]["integrator"] = "leimkuhler_matthews";
                               r["run"]["dt"] = "auto";
                               r["run"]["dt_max"] = 0.01;
                             }),
                             {at_key("run.integrator") + "leimkuhler_matthews takes fixed steps"}));
  cases.push_back(check_case("dt longer than duration", edited([](YAML::Node& r) { r["run"]["dt"] = 1; }),
                             {at_key("run.dt") + "expected a time step no longer than run.duration"}));
  cases.push_back(check_case("diffusive time without Brownian motion", edited([](YAML::Node& r) {
                               r["flow"]["brownian"] = false;
                               r["run"]["time_unit"] = "diffusive";
                             }),
                             {at_key("run.time_unit") + "diffusive time"}));
  cases.push_back(check_case("strain time at Pe = 0", edited([](YAML::Node& r) {
                               r["flow"]["peclet"] = 0;
                               r["run"]["time_unit"] = "strain";
                             }),
                             {at_key("run.time_unit") + "times in strain units"}));
  {
    // Several problems at once: all reported, in file order.
    Case c = check_case("three problems at once", edited([](YAML::Node& r) {
                          r["system"]["count"] = "many";
                          r["run"]["dt"] = -1;
                          r["flow"]["peclet"] = "fast";
                        }),
                        {at_key("system.count"), at_key("run.dt"), at_key("flow.peclet")});
    cases.push_back(c);
    cases.push_back(run_case(c));
  }
  // The same refusals from `run`, before anything is created.
  for (std::size_t i = 0; i < 6; ++i) cases.push_back(run_case(cases[i]));
  run_all("core keys", cases);
}

// Every parameter of every plugin found: a value of the wrong type, and values just outside
// its declared range.
TEST_F(Corpus, PluginParameters) {
  fldsim::PluginRegistry registry(fldsim::PluginRegistry::search_path({}, "."));
  std::vector<Case> cases;
  auto place = [](const fldsim::PluginInfo& p, YAML::Node& r, const YAML::Node& block) -> std::string {
    if (p.kind == "shape") {
      r["system"]["shape"] = block;
      return "system.shape";
    }
    if (p.kind == "hydro") {
      r["hydro"] = block;
      return "hydro";
    }
    if (p.kind == "force") {
      r["forces"] = YAML::Node(YAML::NodeType::Sequence);
      r["forces"].push_back(block);
      return "forces[0]";
    }
    r["observers"].push_back(block);
    return "observers[1]";
  };
  // Valid values for required parameters, so that each case has one problem only.
  const std::map<std::string, std::string> required = {{"spheres", "[[0, 0, 0, 1]]"}};
  int plugins = 0;
  for (const auto& p : registry.plugins()) {
    if (p.name.rfind("fixture", 0) == 0) continue;
    ++plugins;
    auto fill_required = [&](YAML::Node& block, const std::string& except) {
      for (const auto& spec : p.schema.specs())
        if (!spec.default_value && spec.name != except) {
          ASSERT_TRUE(required.count(spec.name))
              << "no valid value for the required " << p.name << "." << spec.name;
          block[spec.name] = YAML::Load(required.at(spec.name));
        }
    };
    for (const auto& spec : p.schema.specs()) {
      std::vector<std::pair<std::string, std::string>> values = {{"a map", "{x: 1}"}};
      using fldsim::ParamType;
      if (spec.type == ParamType::Number || spec.type == ParamType::Integer) {
        values.push_back({"text", "abc"});
        if (std::isfinite(spec.min)) values.push_back({"below the range", std::to_string(spec.min - 1.0)});
        if (std::isfinite(spec.max))
          values.push_back({"above the range", std::to_string(spec.max * 10.0 + 1.0)});
        if (spec.type == ParamType::Integer) values.push_back({"a fraction", "2.5"});
      } else if (spec.type == ParamType::Choice) {
        values.push_back({"an unknown choice", "no_such_choice"});
      } else if (spec.type == ParamType::Flag) {
        values.push_back({"not a flag", "maybe"});
      } else if (spec.type == ParamType::NumberList || spec.type == ParamType::NumberTable) {
        values.push_back({"text", "abc"});
      }
      for (const auto& [what, value] : values) {
        std::string path;
        const std::string yaml = edited([&](YAML::Node& r) {
          YAML::Node block(YAML::NodeType::Map);
          block["plugin"] = p.name;
          fill_required(block, spec.name);
          block[spec.name] = YAML::Load(value);
          path = place(p, r, block);
        });
        cases.push_back(check_case(p.kind + " " + p.name + "." + spec.name + ": " + what + " (" + value + ")",
                                   yaml, {at_key(path + "." + spec.name)}));
      }
    }
    // An unknown parameter, for every plugin.
    std::string path;
    const std::string yaml = edited([&](YAML::Node& r) {
      YAML::Node block(YAML::NodeType::Map);
      block["plugin"] = p.name;
      fill_required(block, "");
      block["no_such_parameter"] = 1;
      path = place(p, r, block);
    });
    cases.push_back(check_case(p.kind + " " + p.name + ": unknown parameter", yaml,
                               {at_key(path + ".no_such_parameter") + "unknown key"}));
  }
  ASSERT_GE(plugins, 10) << "the real plugins were not found";
  // Checks the schemas cannot express, made by the plugins themselves.
  auto plugin_check = [&](const std::string& name, const std::function<void(YAML::Node&)>& edit,
                          const std::string& line) {
    cases.push_back(check_case(name, edited(edit), {line}));
  };
  plugin_check(
      "dicolloid c beyond a + b",
      [](YAML::Node& r) { r["system"]["shape"] = YAML::Load("{plugin: dicolloid, c: 5}"); },
      at_key("system.shape.c"));
  plugin_check(
      "cluster without spheres",
      [](YAML::Node& r) { r["system"]["shape"] = YAML::Load("{plugin: cluster, spheres: []}"); },
      at_key("system.shape.spheres"));
  plugin_check(
      "cluster with a zero radius",
      [](YAML::Node& r) { r["system"]["shape"] = YAML::Load("{plugin: cluster, spheres: [[0, 0, 0, 0]]}"); },
      at_key("system.shape.spheres"));
  plugin_check(
      "cluster zero director",
      [](YAML::Node& r) {
        r["system"]["shape"] = YAML::Load("{plugin: cluster, spheres: [[0, 0, 0, 1]], director: [0, 0, 0]}");
      },
      at_key("system.shape.director"));
  plugin_check(
      "projection listed twice",
      [](YAML::Node& r) {
        r["observers"].push_back(YAML::Load("{plugin: pair_distribution, projections: 'xy, xy', range: 4}"));
      },
      at_key("observers[1].projections"));
  plugin_check(
      "repulsion delta_num above delta_min",
      [](YAML::Node& r) {
        r["forces"][0] = YAML::Load("{plugin: repulsion, delta_num: 0.1, delta_min: 0.01}");
      },
      at_key("forces[0].delta_num"));
  run_all("plugin parameters", cases);
}

TEST_F(Corpus, CommandLine) {
  std::vector<Case> cases;
  auto cli = [&](const std::string& name, std::vector<std::string> args, const std::string& line,
                 bool with_file = true) {
    Case c;
    c.name = name;
    if (with_file) c.files["in.yaml"] = kBase;
    c.args = std::move(args);
    c.lines = {line};
    cases.push_back(c);
  };
  cli("no command", {}, "^fldsim <command>|^fldsim —", false);
  cli("unknown command", {"rnu", "in.yaml"}, "^fldsim: unknown command 'rnu'");
  cli("unknown option", {"run", "in.yaml", "--fast"}, "^fldsim: unknown option --fast");
  cli("unknown check option", {"check", "in.yaml", "-x"}, "^fldsim: unknown option -x");
  cli("no experiment file", {"run"}, "^fldsim: no experiment file given");
  cli("two experiment files", {"run", "in.yaml", "in.yaml"}, "^fldsim: more than one experiment file given");
  cli("-o without a value", {"run", "in.yaml", "-o"}, "^-o: expected a file name");
  cli("--set without a value", {"check", "in.yaml", "--set"}, "^--set: expected KEY=VALUE");
  cli("--resume without a value", {"run", "in.yaml", "--resume"}, "^--resume: expected a checkpoint file");
  // An empty value (an unset shell variable) is not "not given": it used to run to the
  // experiment's own output (-o) or start afresh (--resume) without a word.
  cli("-o with an empty value", {"run", "in.yaml", "-o", ""}, "^-o: expected a file name, got ''");
  cli("--resume with an empty value", {"check", "in.yaml", "--resume", ""},
      "^--resume: expected a checkpoint file, got ''");
  cli("--set without =", {"check", "in.yaml", "--set", "run.dt"}, "^--set run\\.dt: expected KEY=VALUE");
  cli("--set empty key", {"check", "in.yaml", "--set", "=3"}, "^--set =3: expected KEY=VALUE");
  cli("--set into a value", {"check", "in.yaml", "--set", "run.dt.x=1"},
      "^--set run\\.dt\\.x=1: run\\.dt: is a value \\(0\\.01\\), not a section");
  cli("--set bad value", {"check", "in.yaml", "--set", "run.dt=abc"},
      "^--set run\\.dt=abc: run\\.dt: expected a number > 0 or auto, got 'abc'");
  cli("--set out of range", {"run", "in.yaml", "--set", "system.count=0"},
      "^--set system\\.count=0: system\\.count: expected an integer >= 1");
  cli("--set unknown key", {"check", "in.yaml", "--set", "run.dtt=1"},
      "^--set run\\.dtt=1: run\\.dtt: unknown key");
  cli("--set unknown section", {"check", "in.yaml", "--set", "sytem.count=1"},
      "^--set sytem\\.count=1: sytem: unknown key \\(did you mean 'system'\\?\\)");
  cli("--set list index out of range", {"check", "in.yaml", "--set", "observers[4].every=2"},
      "^--set observers\\[4\\]\\.every=2: observers: has 1 entry: index 4 is out of range");
  cli("--set list index not a number", {"check", "in.yaml", "--set", "observers.x.every=2"},
      "^--set observers\\.x\\.every=2: observers: is a list");
  cli("--set bracket index, bad value", {"check", "in.yaml", "--set", "observers[0].every=0"},
      "^--set observers\\[0\\]\\.every=0: observers\\[0\\]\\.every: expected an integer >= 1");
  cli("--set bracket index, unknown parameter", {"check", "in.yaml", "--set", "observers[0].bins=5"},
      "^--set observers\\[0\\]\\.bins=5: observers\\[0\\]\\.bins: unknown key");
  cli("--set invalid YAML value", {"check", "in.yaml", "--set", "run.dt=[1,"},
      "^--set run\\.dt=\\[1,: the value is not valid YAML");
  cli("--set a list where a number goes", {"check", "in.yaml", "--set", "run.dt=[1, 2]"},
      "^--set run\\.dt=\\[1, 2\\]: run\\.dt: expected a number");
  cli("--set a whole section wrong", {"check", "in.yaml", "--set", "run=5"},
      "^--set run=5: run: expected a map");
  cli("-o below a file", {"run", "in.yaml", "-o", "in.yaml/out.h5"},
      "^-o in\\.yaml/out\\.h5: .in\\.yaml. is not a directory");
  cli("--resume a missing file", {"run", "in.yaml", "--resume", "missing.checkpoint"},
      "^--resume missing\\.checkpoint: .*missing\\.checkpoint");
  cli("--resume the experiment file", {"run", "in.yaml", "--resume", "in.yaml"},
      "^--resume in\\.yaml: .*in\\.yaml");
  cli("summary of nothing", {"summary"}, "^fldsim: no result file given");
  cli("summary of a missing file", {"summary", "missing.h5"}, "^fldsim: error: missing\\.h5: file not found");
  cases.back().exit_code = 1;
  cli("summary of a YAML file", {"summary", "in.yaml"},
      "^fldsim: error: in\\.yaml: cannot read the result file: not an HDF5 file");
  cases.back().exit_code = 1;
  cli("plugins with an unknown option", {"plugins", "--bogus"}, "^fldsim: unknown argument --bogus");
  {
    Case c;
    c.name = "-o is a directory";
    c.files["in.yaml"] = kBase;
    c.setup = [](const fs::path& d) { fs::create_directories(d / "outdir"); };
    c.args = {"run", "in.yaml", "-o", "outdir"};
    c.lines = {"^-o outdir: 'outdir' is a directory"};
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "existing result without --overwrite";
    c.files["in.yaml"] = kBase;
    c.files["out.h5"] = "precious";
    c.args = {"run", "in.yaml"};
    c.lines = {at_key("output") + "'out\\.h5' exists; give --overwrite"};
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "existing checkpoint without --overwrite";
    c.files["in.yaml"] = kBase;
    c.files["out.h5.checkpoint"] = "the only state left";
    c.args = {"run", "in.yaml"};
    c.lines = {at_key("output") + "'out\\.h5\\.checkpoint' exists \\(the state of an earlier run"};
    cases.push_back(c);
  }
  run_all("command line", cases);
}

// A --path that is not a directory is named in a warning (the listing goes on without it).
TEST(CommandLineWarnings, PluginsPathThatIsNotADirectory) {
  const fs::path dir = fs::temp_directory_path() / "fldsim_corpus_plugins_path";
  fs::remove_all(dir);
  fs::create_directories(dir);
  corpus::Case c;
  c.args = {"plugins", "--path", "missing-dir"};
  const corpus::Outcome o = corpus::run_case(c, dir);
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_NE(o.err.find("warning: --path missing-dir: not a directory (ignored)"), std::string::npos) << o.err;
  fs::remove_all(dir);
}

TEST_F(Corpus, ResourcesAndFeasibility) {
  std::vector<Case> cases;
  auto add = [&](const std::string& name, const std::function<void(YAML::Node&)>& edit,
                 std::vector<std::string> lines) {
    Case c = check_case(name, edited(edit), std::move(lines));
    cases.push_back(c);
    cases.push_back(run_case(c));
  };
  add("duration 1e300", [](YAML::Node& r) { r["run"]["duration"] = 1e300; },
      {at_key("run.duration") + "run\\.duration / run\\.dt = 1e\\+302 steps; at most 1e\\+09"});
  add("dt 1e-300", [](YAML::Node& r) { r["run"]["dt"] = 1e-300; },
      {at_key("run.duration") + "run\\.duration / run\\.dt = 1e\\+299 steps"});
  // Base: duration 0.1 / dt 0.01 = 10 frames; refine 20 takes each in 2^20 steps (1e7), fine;
  // with duration 1e3 the 1e5 frames become 1e11 steps.
  add("refine beyond the step limit",
      [](YAML::Node& r) {
        r["run"]["duration"] = 1000;
        r["run"]["refine"] = 20;
      },
      {at_key("run.refine") +
       "20: run\\.duration / run\\.dt x 2\\^refine = 1\\.049e\\+11 steps; at most 1e\\+09"});
  add("count 1e9", [](YAML::Node& r) { r["system"]["count"] = "1e9"; },
      {at_key("system.count") + "expected an integer >= 1 and <= 1e\\+08, got 1e9"});
  add("count 4294967297", [](YAML::Node& r) { r["system"]["count"] = "4294967297"; },
      {at_key("system.count")});
  add("count beyond memory", [](YAML::Node& r) { r["system"]["count"] = 90000000; },
      {at_key("system.count") + "90000000 bodies of 1 nodes .* need about .*; this machine has"});
  add("pair_distribution bins 1e7",
      [](YAML::Node& r) {
        r["observers"].push_back(YAML::Load("{plugin: pair_distribution, bins: 10000000}"));
      },
      {at_key("observers[1].bins")});
  add("diffusion origins 1e9",
      [](YAML::Node& r) { r["observers"].push_back(YAML::Load("{plugin: diffusion, origins: 1000000000}")); },
      {at_key("observers[1].origins")});
  add("threads 100000", [](YAML::Node& r) { r["run"]["threads"] = 100000; }, {at_key("run.threads")});
  add("box edge 0.001", [](YAML::Node& r) { r["system"]["box_edge"] = 0.001; },
      {at_key("system.box_edge") + ".*phi = .*no packing of hard bodies exceeds 0\\.74",
       at_key("system.box_edge") + ".*touch its own periodic image"});
  add("phi beyond the Monte Carlo start", [](YAML::Node& r) { r["system"]["volume_fraction"] = 0.6; },
      {at_key("system.volume_fraction") + ".*cannot compress beyond phi = 0\\.55"});
  add("cluster 100 a across",
      [](YAML::Node& r) {
        r["system"]["shape"] = YAML::Load("{plugin: cluster, spheres: [[0, 0, 0, 1], [100, 0, 0, 1]]}");
      },
      {at_key("system.volume_fraction") + "a cluster body spans 10[0-9] a, not less than the box edge"});
  add("pair_distribution range over half the box",
      [](YAML::Node& r) { r["observers"].push_back(YAML::Load("{plugin: pair_distribution, range: 40}")); },
      {at_key("observers[1]") + ".*range"});
  add("observer start after the end", [](YAML::Node& r) { r["observers"][0]["start"] = 5; },
      {at_key("observers[0].start") + "5 is after the end of the run"});
  // A trajectory records its start frame whatever `every` is; an observer that only samples after
  // steps records nothing.
  add("observer every longer than the run",
      [](YAML::Node& r) { r["observers"].push_back(YAML::Load("{plugin: stress, every: 1000}")); },
      {at_key("observers[1].every") + "1000 steps: no sample falls in the run's 10 steps"});
  add("trajectory started later, every longer than the run",
      [](YAML::Node& r) {
        r["observers"][0]["every"] = 1000;
        r["observers"][0]["start"] = 0.05;
      },
      {at_key("observers[0].every") + "1000 steps: no sample falls in the run's 10 steps"});
  add("checkpoint more often than a step", [](YAML::Node& r) { r["run"]["checkpoint_every"] = 0.001; },
      {at_key("run.checkpoint_every") + "shorter than one step"});
  add("box too small for the pair range",
      [](YAML::Node& r) {
        r["system"]["count"] = 2;
        r["system"]["volume_fraction"] = 0.3;
      },
      {at_key("system.count") + "the pair range .* must be less than half the box edge",
       at_key("system.volume_fraction") + "a sphere body spans 4 a, not less than the box edge"});
  add("two trajectory observers",
      [](YAML::Node& r) { r["observers"].push_back(YAML::Load("{plugin: trajectory, every: 2}")); },
      {at_key("observers[1]") + "a second 'trajectory' observer"});
  add("explicit start: too few positions",
      [](YAML::Node& r) { r["system"]["init"] = YAML::Load("{method: explicit, positions: [[1, 1, 1]]}"); },
      {at_key("system.init.positions") + "expected 27 positions"});
  add("explicit start: no positions",
      [](YAML::Node& r) { r["system"]["init"] = YAML::Load("{method: explicit}"); },
      {"^in\\.yaml:[0-9]+:[0-9]+: system\\.init\\.positions: method explicit needs"});
  add("explicit start: overlapping bodies",
      [](YAML::Node& r) {
        r["system"]["count"] = 2;
        r["system"]["box_edge"] = 12;
        r["system"]["init"] = YAML::Load("{method: explicit, positions: [[1, 1, 1], [1.5, 1, 1]]}");
      },
      {at_key("system.init.positions") + ".*overlap"});
  add("explicit start: zero director",
      [](YAML::Node& r) {
        r["system"]["count"] = 2;
        r["system"]["box_edge"] = 12;
        r["system"]["init"] = YAML::Load(
            "{method: explicit, positions: [[1, 1, 1], [5, 1, 1]], orientations: [[0, 0, 0], [0, 0, 1]]}");
      },
      {at_key("system.init.orientations") + "orientations\\[0\\]: expected a non-zero director"});
  add("explicit start: wrong orientation count",
      [](YAML::Node& r) {
        r["system"]["count"] = 2;
        r["system"]["box_edge"] = 12;
        r["system"]["init"] =
            YAML::Load("{method: explicit, positions: [[1, 1, 1], [5, 1, 1]], orientations: [[0, 0, 1]]}");
      },
      {at_key("system.init.orientations") + "expected 2 orientations"});
  add("init file missing",
      [](YAML::Node& r) { r["system"]["init"] = YAML::Load("{method: file, file: none.h5}"); },
      {at_key("system.init.file") + ".*none\\.h5"});
  add("init file not named", [](YAML::Node& r) { r["system"]["init"] = YAML::Load("{method: file}"); },
      {"^in\\.yaml:[0-9]+:[0-9]+: system\\.init\\.file: method file needs"});
  run_all("resources, feasibility", cases);
}

// HDF5 inputs: files that are not HDF5, truncated or foreign, and results of another run.
TEST_F(Corpus, Hdf5Files) {
  const fs::path ref = reference_run();
  ASSERT_TRUE(fs::exists(ref / "out.h5"));
  ASSERT_TRUE(fs::exists(ref / "out.h5.checkpoint"));
  std::vector<Case> cases;
  const std::string init_yaml =
      edited([](YAML::Node& r) { r["system"]["init"] = YAML::Load("{method: file, file: start.h5}"); });
  auto init_case = [&](const std::string& name, const std::function<void(const fs::path&)>& make,
                       const std::string& why) {
    Case c = check_case("init file " + name, init_yaml, {at_key("system.init.file") + why});
    c.setup = make;
    cases.push_back(c);
    cases.push_back(run_case(c));
  };
  const std::string result = read_bytes(ref / "out.h5");
  const std::string checkpoint = read_bytes(ref / "out.h5.checkpoint");
  init_case(
      "is text", [](const fs::path& d) { write_bytes(d / "start.h5", "not hdf5 at all\n"); },
      "start\\.h5: .*not an HDF5 file");
  init_case(
      "is empty", [](const fs::path& d) { write_bytes(d / "start.h5", ""); },
      "start\\.h5: .*not an HDF5 file");
  init_case(
      "is truncated",
      [&](const fs::path& d) { write_bytes(d / "start.h5", result.substr(0, result.size() / 3)); },
      "start\\.h5: ");
  init_case(
      "has its header zeroed",
      [&](const fs::path& d) { write_bytes(d / "start.h5", std::string(512, '\0') + result.substr(512)); },
      "start\\.h5: .*not an HDF5 file");
  init_case(
      "is a checkpoint", [&](const fs::path& d) { write_bytes(d / "start.h5", checkpoint); },
      "start\\.h5: .*trajectory");
  init_case(
      "is a directory", [](const fs::path& d) { fs::create_directories(d / "start.h5"); }, "start\\.h5: ");
  init_case(
      "has another body count", [&](const fs::path& d) { write_bytes(d / "start.h5", result); },
      "start\\.h5 holds 27 bodies, the experiment asks for 8");
  // The last one needs 8 bodies in the experiment.
  cases[cases.size() - 2].files["in.yaml"] = cases[cases.size() - 1].files["in.yaml"] =
      edited([](YAML::Node& r) {
        r["system"]["init"] = YAML::Load("{method: file, file: start.h5}");
        r["system"]["count"] = 8;
        r["system"]["volume_fraction"] = 0.01;
      });
  auto summary_case = [&](const std::string& name, const std::function<void(const fs::path&)>& make,
                          const std::string& why) {
    Case c;
    c.name = "summary of " + name;
    c.setup = make;
    c.args = {"summary", "r.h5"};
    c.exit_code = 1;
    c.lines = {"^fldsim: error: r\\.h5: " + why};
    cases.push_back(c);
  };
  summary_case(
      "a text file", [](const fs::path& d) { write_bytes(d / "r.h5", "text"); }, ".*not an HDF5 file");
  summary_case(
      "a truncated result", [&](const fs::path& d) { write_bytes(d / "r.h5", result.substr(0, 2000)); }, "");
  summary_case(
      "a checkpoint", [&](const fs::path& d) { write_bytes(d / "r.h5", checkpoint); }, "");
  summary_case(
      "an empty file", [](const fs::path& d) { write_bytes(d / "r.h5", ""); }, ".*not an HDF5 file");
  run_all("hdf5 files", cases);
}

// --resume with checkpoints that do not belong to the experiment.
TEST_F(Corpus, Resume) {
  const fs::path ref = reference_run();
  const std::string checkpoint = read_bytes(ref / "out.h5.checkpoint");
  const std::string result = read_bytes(ref / "out.h5");
  std::vector<Case> cases;
  const auto ref_yaml = [](const std::function<void(YAML::Node&)>& edit) {
    return edited([&](YAML::Node& r) {
      r["observers"].push_back(YAML::Load("{plugin: pair_distribution, every: 5, range: 4, bins: 20}"));
      r["output"] = "new.h5";
      r["run"]["duration"] = 0.2;
      edit(r);
    });
  };
  auto resume = [&](const std::string& name, const std::string& yaml, const std::string& bytes,
                    std::vector<std::string> lines) {
    Case c = check_case(name, yaml, std::move(lines), {"--resume", "old.checkpoint"});
    c.setup = [bytes](const fs::path& d) { write_bytes(d / "old.checkpoint", bytes); };
    cases.push_back(c);
    cases.push_back(run_case(c));
  };
  const auto same = [](YAML::Node&) {};
  resume("changed pair_distribution range", ref_yaml([](YAML::Node& r) { r["observers"][1]["range"] = 5; }),
         checkpoint,
         {at_key("observers[1].range") + "5 now, 4 when old\\.checkpoint was written; resuming would mix"});
  resume("changed observer every", ref_yaml([](YAML::Node& r) { r["observers"][0]["every"] = 2; }),
         checkpoint, {at_key("observers[0].every") + "2 now, 5 when"});
  resume("changed dt", ref_yaml([](YAML::Node& r) { r["run"]["dt"] = 0.02; }), checkpoint,
         {at_key("run.dt") + "0\\.02 now, 0\\.01 when"});
  resume("changed seed", ref_yaml([](YAML::Node& r) { r["run"]["seed"] = 7; }), checkpoint,
         {at_key("run.seed") + "7 now, 42 when"});
  resume("changed Peclet number", ref_yaml([](YAML::Node& r) { r["flow"]["peclet"] = 2; }), checkpoint,
         {at_key("flow.peclet") + "2 now, 1 when"});
  resume("another observer plugin",
         ref_yaml([](YAML::Node& r) { r["observers"][1] = YAML::Load("{plugin: orientation}"); }), checkpoint,
         {at_key("observers[1].plugin") + "'orientation' now, 'pair_distribution' when"});
  resume("an observer fewer", ref_yaml([](YAML::Node& r) { r["observers"].remove(1); }), checkpoint,
         {"^in\\.yaml: observers: 1 fewer than in the experiment of old\\.checkpoint"});
  resume("checkpoint of another experiment (body count)", ref_yaml([](YAML::Node& r) {
           r["system"]["count"] = 8;
           r["system"]["volume_fraction"] = 0.01;
         }),
         checkpoint,
         {"^--resume old\\.checkpoint: the checkpoint holds 27 bodies, the experiment \\(system\\.count\\) 8",
          at_key("system.count") + "8 now, 27 when",
          at_key("system.volume_fraction") + "0\\.01 now, 0\\.05 when"});
  resume("checkpoint past the end", edited([](YAML::Node& r) {
           r["observers"].push_back(YAML::Load("{plugin: pair_distribution, every: 5, range: 4, bins: 20}"));
           r["output"] = "new.h5";
           r["run"]["duration"] = 0.05;
         }),
         checkpoint,
         {at_key("run.duration") + "the checkpoint is at step 10, past the end of this run \\(5 steps\\)"});
  resume("a result file as checkpoint", ref_yaml(same), result, {"^--resume old\\.checkpoint: "});
  resume("a truncated checkpoint", ref_yaml(same), checkpoint.substr(0, checkpoint.size() / 2),
         {"^--resume old\\.checkpoint: "});
  resume("a text file as checkpoint", ref_yaml(same), "hello",
         {"^--resume old\\.checkpoint: .*not an HDF5 file"});
  run_all("resume", cases);
}

TEST_F(Corpus, HostilePlugins) {
  std::vector<Case> cases;
  auto with_plugin = [&](const std::string& name, const std::string& fixture, const std::string& plugin,
                         std::vector<std::string> lines, int exit_code = 2,
                         const std::string& command = "check") {
    Case c;
    c.name = name;
    c.files["in.yaml"] = edited([&](YAML::Node& r) {
      r["plugins"]["paths"].push_back(std::string(HOSTILE_DIR) + "/" + fixture);
      if (!plugin.empty()) r["observers"].push_back(YAML::Load("{plugin: " + plugin + "}"));
    });
    c.args = {command, "in.yaml", "-q"};
    c.exit_code = exit_code;
    c.lines = std::move(lines);
    cases.push_back(c);
    return &cases.back();
  };
  const std::string hostile = regex_escape(HOSTILE_DIR);
  with_plugin("constructor throws int", "throw_int_ctor", "hostile_throw_int",
              {at_key("observers[1]") + "observer plugin 'hostile_throw_int' \\(" + hostile +
               "/throw_int_ctor/throw_int_ctor\\.so\\): its constructor threw an exception of type int"});
  with_plugin("constructor throws std::string", "throw_string_ctor", "hostile_throw_string",
              {at_key("observers[1]") + "observer plugin 'hostile_throw_string' .*its constructor threw an "
                                        "exception of type std::(__cxx11::)?basic_string"});
  with_plugin("begin() throws a private type", "throw_in_begin", "hostile_throw_begin",
              {at_key("observers[1]") +
               "observer plugin 'hostile_throw_begin' .*begin\\(\\) threw .*PluginOnlyError: begin refuses"});
  with_plugin("begin() throws a private type (run)", "throw_in_begin", "hostile_throw_begin",
              {at_key("observers[1]") + "observer plugin 'hostile_throw_begin'"}, 2, "run");
  {
    Case* c =
        with_plugin("sample() throws during the run", "throw_in_sample", "hostile_throw_sample",
                    {"^fldsim: error: observer plugin 'hostile_throw_sample' \\(.*throw_in_sample\\.so\\): "
                     "sample\\(\\) threw .*PluginOnlyError: sample gives up"},
                    1, "run");
    c->may_leave = {"out.h5.part"};  // a run-time failure keeps what it wrote, never under the real name
  }
  with_plugin("library aborts when loaded, experiment does not name it", "abort_on_load", "", {});
  cases.back().exit_code = 0;
  with_plugin(
      "library aborts when loaded, experiment names it", "abort_on_load", "hostile_abort_on_load",
      {at_key("observers[1].plugin") + "no observer plugin named 'hostile_abort_on_load'.*a candidate "
                                       "failed: .*abort_on_load\\.so: crashed while loading: signal 6"});
  {
    Case* c = with_plugin(
        "describe() crashes", "segv_in_describe", "hostile_segv_describe",
        {at_key("observers[1].plugin") +
         "no observer plugin named 'hostile_segv_describe'.*segv_in_describe\\.so: (crashed|exited) "
         "while loading"});
    // Under `make sanitize`, let the plugin's SIGSEGV be a signal, as in a normal build (ASan would
    // turn it into its own report and exit 1, which the judge counts as fldsim crashing).
    c->env["ASAN_OPTIONS"] =
        "detect_leaks=1:abort_on_error=0:detect_odr_violation=0:allocator_may_return_null=1:handle_segv=0";
  }
  {
    Case* c =
        with_plugin("library hangs when loaded", "hang_on_load", "hostile_hang_on_load",
                    {at_key("observers[1].plugin") +
                     "no observer plugin named 'hostile_hang_on_load'.*did not finish loading within 1"});
    c->env["FLDSIM_PLUGIN_LOAD_TIMEOUT"] = "1";
  }
  {
    // A second `repulsion`, on the experiment's own path: it is used, and the user is told.
    Case c;
    c.name = "shadowed plugin is reported";
    c.files["in.yaml"] = edited([](YAML::Node& r) {
      r["plugins"]["paths"].push_back(std::string(HOSTILE_DIR) + "/shadow_repulsion");
    });
    c.args = {"check", "in.yaml"};
    c.exit_code = 0;
    cases.push_back(c);
  }
  {
    Case c;
    c.name = "plugins lists every bad library and goes on";
    c.args = {"plugins",
              "--path",
              std::string(HOSTILE_DIR) + "/abort_on_load",
              "--path",
              std::string(HOSTILE_DIR) + "/segv_in_describe",
              "--path",
              std::string(HOSTILE_DIR) + "/throw_int_ctor"};
    c.exit_code = 0;
    cases.push_back(c);
  }
  run_all("hostile plugins", cases);
}

// What `check` and `plugins` print about shadowing and failures (not error lines).
TEST(HostilePluginOutput, ShadowAndFailuresAreReported) {
  Case c;
  c.files["in.yaml"] = edited(
      [](YAML::Node& r) { r["plugins"]["paths"].push_back(std::string(HOSTILE_DIR) + "/shadow_repulsion"); });
  c.args = {"check", "in.yaml"};
  corpus::Outcome o = corpus::run_case(c, work_root() / "shadow");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.err.find("warning: forces[0]: "), std::string::npos) << o.err;
  // The experiment's own plugins.paths come first: its `repulsion` is used and the user is told
  // which one it hides.
  EXPECT_NE(o.err.find("fldsim-force-repulsion.so: ignored, force plugin 'repulsion' already provided by " +
                       std::string(HOSTILE_DIR) + "/shadow_repulsion/shadow_repulsion.so"),
            std::string::npos)
      << o.err;

  c.files.clear();
  c.args = {"plugins", "--path", std::string(HOSTILE_DIR) + "/abort_on_load", "--path",
            std::string(HOSTILE_DIR) + "/throw_int_ctor"};
  o = corpus::run_case(c, work_root() / "plugins");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.out.find("not loaded: " + std::string(HOSTILE_DIR) +
                       "/abort_on_load/abort_on_load.so: crashed while loading: signal 6"),
            std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("observer hostile_throw_int 1.0.0"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("hydro fld "), std::string::npos) << o.out;  // the real ones are still listed
  fs::remove_all(work_root());
}

}  // namespace

namespace {

// An observer whose restore_state() throws: the run stops with the plugin named, exit 1, and
// no crash (the exception used to outlive the library that threw it: SIGSEGV).
TEST(HostilePluginOutput, RestoreStateThrowingIsReportedNotACrash) {
  const fs::path dir = work_root() / "restore";
  Case first;
  first.files["in.yaml"] = edited([](YAML::Node& r) {
    r["plugins"]["paths"].push_back(std::string(HOSTILE_DIR) + "/throw_in_restore");
    r["observers"].push_back(YAML::Load("{plugin: hostile_throw_restore}"));
  });
  first.args = {"run", "in.yaml", "-q"};
  corpus::Outcome o = corpus::run_case(first, dir);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  fs::rename(dir / "out.h5.checkpoint", dir / "first.checkpoint");
  fs::remove(dir / "out.h5");

  Case again;
  again.files = first.files;
  again.setup = [&](const fs::path& d) { fs::copy_file(dir / "first.checkpoint", d / "first.checkpoint"); };
  again.args = {"run", "in.yaml", "-q", "--resume", "first.checkpoint"};
  again.exit_code = 1;
  again.lines = {
      "^fldsim: error: observer plugin 'hostile_throw_restore' \\(.*throw_in_restore\\.so\\): checkpoint "
      "state does not fit \\(fixture\\)"};
  again.may_leave = {"out.h5.part"};
  o = corpus::run_case(again, work_root() / "restore-again");
  const corpus::Verdict v = corpus::judge(again, o);
  EXPECT_TRUE(v.clear && !v.crash) << v.why;
  fs::remove_all(work_root());
}

}  // namespace
