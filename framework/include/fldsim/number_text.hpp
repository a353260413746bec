// The shortest text that reads back as the same double ("2.5e-07", "0.1", "3"): for messages,
// logs and text attributes, where std::to_string's fixed six decimals would lose a value
// (2.5e-7 -> "0.000000"). Header-only.
#pragma once

#include <charconv>
#include <string>

namespace fldsim {

inline std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round trip (C++17)
  return std::string(buf, r.ptr);
}

}  // namespace fldsim
