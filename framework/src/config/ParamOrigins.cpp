#include "config/ParamOrigins.hpp"

namespace fldsim {

ParamOrigin origin_of(const Params& params, const std::string& name) {
  std::string text;
  try {
    params.fail(name, "");
  } catch (const ConfigError& e) {
    text = e.what();
  }
  // "location: path: " (the message is empty); the path holds no ": ".
  if (text.size() >= 2 && text.compare(text.size() - 2, 2, ": ") == 0) text.resize(text.size() - 2);
  const auto split = text.rfind(": ");
  if (split == std::string::npos) return {"", text};
  return {text.substr(0, split), text.substr(split + 2)};
}

}  // namespace fldsim
