// Shortest round-trip text of a number ("2", "0.5", "1e-06") for messages and docs.
#pragma once

#include <string>

namespace fldsim {
std::string format_number(double v);
// Four significant digits ("372.3", "0.0001234"): times, gaps and sizes in run-log lines and
// pre-run checks, where the shortest round-trip text shows the sum of a million steps' rounding
// (t = 27.540000000001505).
std::string log_number(double v);
}  // namespace fldsim
