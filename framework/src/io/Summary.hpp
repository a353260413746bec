// `fldsim summary <file.h5>`: the steady-state scalars of a result file as a table.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace fldsim {

// One scalar dataset under /results, as observers write it.
struct ResultScalar {
  std::string name;                        // relative to /results, e.g. orientation/delta_theta_m
  double value = 0.0, stderr_value = 0.0;  // stderr NaN when the dataset has none
  std::string unit;
  bool no_plateau = false;  // the blocking analysis found no plateau: the SE is a lower bound
};

// Every scalar dataset under /results, in file order. Throws fldsim::Error if the file cannot be
// read or has no /results group.
std::vector<ResultScalar> read_result_scalars(const std::string& path);

// Prints every scalar dataset under /results (name relative to /results, value, standard
// error, unit) in aligned columns, each value rounded to the precision of its error. Returns 0;
// throws fldsim::Error if the file cannot be read or has no /results group.
int print_summary(const std::string& path, std::ostream& out);

// "value" and "stderr" as printed: two significant digits of the error and the value to the
// same decimal place (scientific notation for very large or small values). An error of zero
// prints the value with 6 significant digits; a non-finite error prints as "n/a".
void format_with_error(double value, double stderr_value, std::string& value_text, std::string& stderr_text);

}  // namespace fldsim
