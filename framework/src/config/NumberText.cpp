#include "config/NumberText.hpp"

#include <charconv>

namespace fldsim {

std::string format_number(double v) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);  // shortest representation
  return std::string(buf, result.ptr);
}

}  // namespace fldsim
