#include "io/Summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "fldsim/error.hpp"
#include "io/H5Helpers.hpp"
#include "io/IsolatedRead.hpp"

namespace fldsim {

namespace {

std::string printf_string(const char* format, int precision, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, precision, x);
  return buffer;
}

struct Row {
  std::string name, value, stderr_text, unit;
  bool no_plateau = false;  // the observer's blocking found no plateau: the SE is a lower bound
};

// Observers write blocked averages with write_blocked(), which says so in the description.
constexpr const char* kNoPlateau = "no plateau reached";

void collect(const H5::Group& group, const std::string& prefix, std::vector<ResultScalar>& rows) {
  for (hsize_t i = 0; i < group.getNumObjs(); ++i) {
    const std::string name = group.getObjnameByIdx(i);
    const std::string full = prefix.empty() ? name : prefix + "/" + name;
    const H5O_type_t type = group.childObjType(name);
    if (type == H5O_TYPE_GROUP) {
      collect(group.openGroup(name), full, rows);
      continue;
    }
    if (type != H5O_TYPE_DATASET) continue;
    H5::DataSet d = group.openDataSet(name);
    const H5T_class_t cls = d.getTypeClass();
    if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || d.getSpace().getSimpleExtentNpoints() != 1) continue;
    ResultScalar row;
    row.name = full;
    d.read(&row.value, H5::PredType::NATIVE_DOUBLE);
    row.stderr_value = d.attrExists("stderr") ? io::read_double_attribute(d, "stderr") : std::nan("");
    row.unit = d.attrExists("unit") ? io::read_string_attribute(d, "unit") : "";
    row.no_plateau = d.attrExists("description") &&
                     io::read_string_attribute(d, "description").find(kNoPlateau) != std::string::npos;
    rows.push_back(std::move(row));
  }
}

}  // namespace

void format_with_error(double value, double stderr_value, std::string& value_text, std::string& stderr_text) {
  if (!std::isfinite(stderr_value) || stderr_value <= 0.0 || !std::isfinite(value)) {
    value_text = printf_string("%.*g", 6, value);
    stderr_text = stderr_value == 0.0 ? "0" : "n/a";
    return;
  }
  // An error below double round-off (12 significant digits) is no guide: the value is exact as
  // far as the run can tell (0.5000000000000011 +- 6.7e-17 prints as 0.5).
  if (std::isfinite(value) && stderr_value <= 1e-12 * std::fabs(value)) {
    value_text = printf_string("%.*g", 12, value);
    stderr_text = printf_string("%.*e", 1, stderr_value);
    return;
  }
  // Position (power of ten) of the last printed digit: the second significant digit of the error.
  const int last = static_cast<int>(std::floor(std::log10(stderr_value))) - 1;
  const double magnitude = std::fabs(value);
  const bool fixed = (magnitude == 0.0 || (magnitude >= 1e-3 && magnitude < 1e6)) && last >= -12;
  if (fixed) {
    const int decimals = std::max(0, -last);
    value_text = printf_string("%.*f", decimals, value);
    stderr_text = printf_string("%.*f", decimals, stderr_value);
  } else {
    const int exponent = magnitude > 0.0 ? static_cast<int>(std::floor(std::log10(magnitude))) : last;
    const int digits = std::clamp(exponent - last + 1, 1, 17);
    value_text = printf_string("%.*e", digits - 1, value);
    stderr_text = printf_string("%.*e", 1, stderr_value);
  }
}

namespace {

std::vector<ResultScalar> read_result_scalars_in_process(const std::string& path) {
  io::quiet_hdf5();
  if (!std::filesystem::exists(path)) throw Error(path + ": file not found");
  std::vector<ResultScalar> scalars;
  try {
    H5::H5File file(path, H5F_ACC_RDONLY);
    H5::Group root = file.openGroup("/");
    if (!io::path_exists(root, "results") || root.childObjType("results") != H5O_TYPE_GROUP)
      throw Error(path + ": no /results group (did the run finish and have observers that write results?)");
    collect(root.openGroup("results"), "", scalars);
  } catch (const H5::Exception& e) {
    io::fail(path, "cannot read the result file", e);
  }
  return scalars;
}

}  // namespace

std::vector<ResultScalar> read_result_scalars(const std::string& path) {
  return io::read_isolated(path, "result file", [&] { return read_result_scalars_in_process(path); });
}

int print_summary(const std::string& path, std::ostream& out) {
  std::vector<Row> rows;
  for (const ResultScalar& r : read_result_scalars(path)) {
    Row row;
    row.name = r.name;
    format_with_error(r.value, r.stderr_value, row.value, row.stderr_text);
    row.unit = r.unit;
    row.no_plateau = r.no_plateau;
    rows.push_back(std::move(row));
  }

  Row header{"name", "value", "stderr", "unit"};
  std::size_t w[4] = {header.name.size(), header.value.size(), header.stderr_text.size(), header.unit.size()};
  for (const auto& r : rows) {
    w[0] = std::max(w[0], r.name.size());
    w[1] = std::max(w[1], r.value.size());
    w[2] = std::max(w[2], r.stderr_text.size());
    w[3] = std::max(w[3], r.unit.size());
  }
  auto print = [&](const Row& r) {
    std::string line = r.name + std::string(w[0] - r.name.size() + 2, ' ');
    line += std::string(w[1] - r.value.size(), ' ') + r.value + "  ";
    line += std::string(w[2] - r.stderr_text.size(), ' ') + r.stderr_text + "  " + r.unit;
    if (r.no_plateau) line += std::string(w[3] - r.unit.size(), ' ') + "  *";
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << '\n';
  };
  out << path << ": " << rows.size() << " scalar result" << (rows.size() == 1 ? "" : "s")
      << " under /results\n";
  print(header);
  out << std::string(w[0] + w[1] + w[2] + w[3] + 6, '-') << '\n';
  std::size_t flagged = 0;
  for (const auto& r : rows) {
    print(r);
    flagged += r.no_plateau;
  }
  if (flagged)
    out << "* " << flagged << " of " << rows.size()
        << ": no plateau reached in the blocking analysis, so the SE is a lower bound: the run is "
           "too short for it\n";
  return 0;
}

}  // namespace fldsim
