#include "config/NumberText.hpp"

#include <charconv>
#include <sstream>

namespace fldsim {

std::string format_number(double v) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);  // shortest representation
  return std::string(buf, result.ptr);
}

std::string log_number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace fldsim
