// Shortest round-trip text of a number ("2", "0.5", "1e-06") for messages and docs.
#pragma once

#include <string>

namespace fldsim {
std::string format_number(double v);
}  // namespace fldsim
