// Broken experiment snippets and the exact error each must produce. The messages are the user
// interface of the experiment file, so they are asserted word for word, with real positions.
#include <gtest/gtest.h>

#include "config/TempYaml.hpp"
#include "config/YamlValidation.hpp"

namespace {

using fldsim_test::TempYaml;

// A hydro-like block exercising every parameter type.
fldsim::ParamSchema hydro_schema() {
  fldsim::ParamSchema s;
  s.number("a", std::nullopt, "a", "node radius").greater(0);
  s.number("cutoff", 2.5, "a", "lubrication cut-off").greater(2);
  s.integer("steps", 100, "steps", "rebuild interval").at_least(1);
  s.flag("brownian", true, "thermal forces on");
  s.choice("method", std::string("lammps"), {"jeffrey_onishi", "lammps"}, "resistance functions");
  s.numbers("box", std::vector<double>{10, 10, 10}, "a", "box edges").length(3);
  s.table("spheres", std::vector<std::vector<double>>{}, "a", "x y z r per sphere").length(4);
  s.text("label", std::string(""), "free text");
  return s;
}

// `text` with every occurrence of the temp file's path replaced by "FILE".
std::string anonymise(std::string text, const std::string& file) {
  for (auto at = text.find(file); at != std::string::npos; at = text.find(file, at))
    text.replace(at, file.size(), "FILE");
  return text;
}

// Validates block `hydro` of the snippet; returns the error text with the path as "FILE" ("" if none).
std::string errors_for(const std::string& yaml, fldsim::Params* out = nullptr) {
  TempYaml tmp;
  const std::string file = tmp.write("experiment.yaml", yaml);
  try {
    const YAML::Node root = fldsim::load_yaml_file(file);
    fldsim::ConfigErrors errors(file);
    fldsim::Params p = fldsim::validate_params(root["hydro"], hydro_schema(), "hydro", errors, {"plugin"});
    if (out) *out = p;
    return anonymise(errors.text(), file);
  } catch (const fldsim::ConfigError& e) {  // syntax errors come out of load_yaml_file
    return anonymise(e.what(), file);
  }
}

struct BrokenCase {
  const char* what;
  const char* yaml;
  const char* expected;
};

class BrokenSnippet : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenSnippet, ReportsExactError) {
  const BrokenCase& c = GetParam();
  EXPECT_EQ(errors_for(c.yaml), c.expected) << c.what;
}

const BrokenCase kBroken[] = {
    {"wrong type", "hydro:\n  a: abc\n", "FILE:2:6: hydro.a: expected a number > 0, got 'abc'"},
    {"quoted number is text", "hydro:\n  a: '1.5'\n", "FILE:2:6: hydro.a: expected a number > 0, got '1.5'"},
    {"a map where a number goes", "hydro:\n  a: {x: 1}\n",
     "FILE:2:6: hydro.a: expected a number > 0, got a map"},
    {"empty value", "hydro:\n  a:\n", "FILE:2:3: hydro.a: expected a number > 0, got null"},
    {"out of range", "hydro:\n  a: 1\n  cutoff: 1.5\n",
     "FILE:3:11: hydro.cutoff: expected a number > 2, got 1.5"},
    {"non-integral integer", "hydro:\n  a: 1\n  steps: 2.5\n",
     "FILE:3:10: hydro.steps: expected an integer >= 1, got 2.5"},
    {"integer below range", "hydro:\n  a: 1\n  steps: 0\n",
     "FILE:3:10: hydro.steps: expected an integer >= 1, got 0"},
    {"bad flag", "hydro:\n  a: 1\n  brownian: maybe\n",
     "FILE:3:13: hydro.brownian: expected true or false, got 'maybe'"},
    {"missing required", "hydro:\n  cutoff: 3\n",
     "FILE:2:3: hydro.a: missing required key (a number > 0, in a)"},
    {"unknown key with did-you-mean", "hydro:\n  a: 1\n  cutof: 3\n",
     "FILE:3:3: hydro.cutof: unknown key (did you mean 'cutoff'?)"},
    {"unknown key without a near name", "hydro:\n  a: 1\n  viscosity: 3\n",
     "FILE:3:3: hydro.viscosity: unknown key (known keys: a, cutoff, steps, brownian, method, box, spheres, "
     "label)"},
    {"bad choice", "hydro:\n  a: 1\n  method: lamps\n",
     "FILE:3:11: hydro.method: expected one of: jeffrey_onishi, lammps, got 'lamps' (did you mean "
     "'lammps'?)"},
    {"list of wrong length", "hydro:\n  a: 1\n  box: [1, 2]\n",
     "FILE:3:8: hydro.box: expected a list of 3 numbers, got a list of 2"},
    {"list element not a number", "hydro:\n  a: 1\n  box: [1, x, 3]\n",
     "FILE:3:12: hydro.box[1]: expected a number, got 'x'"},
    {"scalar where a list goes", "hydro:\n  a: 1\n  box: 5\n",
     "FILE:3:8: hydro.box: expected a list of 3 numbers, got 5"},
    {"table row of wrong length", "hydro:\n  a: 1\n  spheres:\n    - [0, 0, 0, 1]\n    - [0, 0, 1]\n",
     "FILE:5:7: hydro.spheres[1]: expected a list of 4 numbers, got a list of 3"},
    {"text given a list", "hydro:\n  a: 1\n  label: [x]\n",
     "FILE:3:10: hydro.label: expected a string, got a list"},
    {"duplicate key", "hydro:\n  a: 1\n  a: 2\n",
     "FILE:3:3: hydro.a: duplicate key (first given at line 2); YAML keeps only one, so this one would be "
     "silently lost"},
    {"block is not a map", "hydro: fld\n",
     "FILE:1:8: hydro: expected a map of parameters, got 'fld'\n"
     "FILE:1:8: hydro.a: missing required key (a number > 0, in a)"},
    // yaml-cpp 0.7 reports the unclosed flow sequence where the parser gives up (the ':' on line 3).
    {"YAML syntax error", "hydro:\n  a: [1, 2\n  cutoff: 3\n",
     "FILE:3:9: syntax error: end of sequence flow not found"},
    {"several errors, reported in line order",
     "hydro:\n  method: lamps\n  a: -1\n  cutof: 3\n  steps: 1e3\n  box: [1, 2, 3, 4]\n",
     "FILE:2:11: hydro.method: expected one of: jeffrey_onishi, lammps, got 'lamps' (did you mean "
     "'lammps'?)\n"
     "FILE:3:6: hydro.a: expected a number > 0, got -1\n"
     "FILE:4:3: hydro.cutof: unknown key (did you mean 'cutoff'?)\n"
     "FILE:6:8: hydro.box: expected a list of 3 numbers, got a list of 4"},
};

INSTANTIATE_TEST_SUITE_P(Config, BrokenSnippet, ::testing::ValuesIn(kBroken));

TEST(ValidateParams, AcceptsValidValuesAndFillsDefaults) {
  fldsim::Params p;
  const std::string yaml =
      "hydro:\n  plugin: fld\n  a: 1\n  steps: 1e3\n  brownian: no\n  box: [4, 5, 6.5]\n"
      "  spheres: [[0, 0, 0, 1], [0, 0, 1.2, 1]]\n  label: 42\n";
  ASSERT_EQ(errors_for(yaml, &p), "");
  EXPECT_EQ(p.number("a"), 1.0);        // an integer literal is a valid number
  EXPECT_EQ(p.integer("steps"), 1000);  // 1e3 is integral
  EXPECT_FALSE(p.flag("brownian"));
  EXPECT_EQ(p.numbers("box"), (std::vector<double>{4, 5, 6.5}));
  ASSERT_EQ(p.table("spheres").size(), 2u);
  EXPECT_EQ(p.table("spheres")[1], (std::vector<double>{0, 0, 1.2, 1}));
  EXPECT_EQ(p.text("label"), "42");
  // Defaults are present but not marked as given.
  EXPECT_EQ(p.number("cutoff"), 2.5);
  EXPECT_EQ(p.text("method"), "lammps");
  EXPECT_TRUE(p.given("a"));
  EXPECT_FALSE(p.given("cutoff"));
  EXPECT_FALSE(p.has("plugin"));  // reserved keys belong to the caller
}

TEST(ValidateParams, LargeIntegersAreExact) {
  fldsim::Params p;
  // 2^53 + 1 is not representable as a double; an integer parameter must still read it exactly.
  ASSERT_EQ(errors_for("hydro:\n  a: 1\n  steps: 9007199254740993\n", &p), "");
  EXPECT_EQ(p.integer("steps"), 9007199254740993L);
}

TEST(ValidateParams, BlockAbsentMeansAllDefaults) {
  TempYaml tmp;
  const std::string file = tmp.write("e.yaml", "other: 1\n");
  const YAML::Node root = fldsim::load_yaml_file(file);
  fldsim::ParamSchema s;
  s.number("x", 1.5, "", "");
  fldsim::ConfigErrors errors(file);
  const fldsim::Params p = fldsim::validate_params(root["absent"], s, "absent", errors);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(p.number("x"), 1.5);
}

TEST(LoadYamlFile, MissingFileIsReported) {
  TempYaml tmp;
  const std::string file = (tmp.dir() / "nope.yaml").string();
  try {
    fldsim::load_yaml_file(file);
    FAIL() << "expected a ConfigError";
  } catch (const fldsim::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), file + ": cannot read: No such file or directory");
  }
}

TEST(DescribeYamlValue, Forms) {
  const YAML::Node n = YAML::Load("{a: 1.5, b: abc, c: 'x', d: [1], e: {f: 1}, g: true, h: ~}");
  EXPECT_EQ(fldsim::describe_yaml_value(n["a"]), "1.5");
  EXPECT_EQ(fldsim::describe_yaml_value(n["b"]), "'abc'");
  EXPECT_EQ(fldsim::describe_yaml_value(n["c"]), "'x'");
  EXPECT_EQ(fldsim::describe_yaml_value(n["d"]), "a list");
  EXPECT_EQ(fldsim::describe_yaml_value(n["e"]), "a map");
  EXPECT_EQ(fldsim::describe_yaml_value(n["g"]), "true");
  EXPECT_EQ(fldsim::describe_yaml_value(n["h"]), "null");
}

TEST(ConfigErrors, SortsByLineThenColumnAndThrowsAll) {
  fldsim::ConfigErrors errors("x.yaml");
  errors.add("x.yaml:10:2", "b", "second");
  errors.add("x.yaml:3:7", "a", "first");
  errors.add("x.yaml:10:1", "", "between");
  EXPECT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors.text(), "x.yaml:3:7: a: first\nx.yaml:10:1: between\nx.yaml:10:2: b: second");
  try {
    errors.throw_if_any();
    FAIL() << "expected a ConfigError";
  } catch (const fldsim::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), errors.text());
  }
  fldsim::ConfigErrors none("y.yaml");
  EXPECT_NO_THROW(none.throw_if_any());
}

}  // namespace
