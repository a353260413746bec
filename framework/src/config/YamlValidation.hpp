// Checking a YAML map against a plugin's ParamSchema. yaml-cpp stays inside the core: the
// plugin only ever sees the Params returned here.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "config/ConfigErrors.hpp"
#include "config/DidYouMean.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

// Parses the file; throws ConfigError "FILE: cannot read: <reason>" when it cannot be opened and
// "FILE:LINE:COL: syntax error: <yaml-cpp message>" when it is not valid YAML.
YAML::Node load_yaml_file(const std::string& path);

// Validates `node` (a map) against `schema`. Keys in `reserved` (e.g. "plugin", "every") belong
// to the caller and are skipped. Each wrong type, out-of-range value, bad choice, missing required
// key, duplicate key and unknown key (with a did-you-mean) goes to `errors`. Returns Params with
// every schema key set: the given value, or the default.
Params validate_params(const YAML::Node& node, const ParamSchema& schema, const std::string& path,
                       ConfigErrors& errors, const std::set<std::string>& reserved = {});

// How a value is shown after "got": `1.5`, `true`, `'abc'`, `null`, `a list`, `a map`.
std::string describe_yaml_value(const YAML::Node& n);

}  // namespace fldsim
