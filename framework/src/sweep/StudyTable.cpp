#include "sweep/StudyTable.hpp"

#include <H5Cpp.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "fldsim/error.hpp"
#include "io/H5Helpers.hpp"
#include "io/Summary.hpp"
#include "sweep/StoredRun.hpp"

namespace fldsim {
namespace {

namespace fs = std::filesystem;

struct Row {
  std::string label, status;
  int repeat = 0;
  std::map<std::string, std::string> axis;      // key -> YAML text
  std::map<std::string, ResultScalar> results;  // name -> scalar
};

std::string number(double x) {
  if (std::isnan(x)) return "";
  char b[40];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

// A CSV field: quoted when it holds a comma, quote or newline.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

bool parse_number(const std::string& s, double& x) {
  try {
    std::size_t used = 0;
    x = std::stod(s, &used);
    return used == s.size();
  } catch (...) {
    return false;
  }
}

void write_strings(H5::Group& g, const std::string& name, const std::vector<std::string>& values) {
  const H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  const hsize_t n = values.size();
  H5::DataSet d = g.createDataSet(name, type, H5::DataSpace(1, &n));
  std::vector<const char*> p;
  for (const auto& v : values) p.push_back(v.c_str());
  if (n) d.write(p.data(), type);
}

void write_doubles(H5::Group& g, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  H5::DataSet d = g.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &n));
  if (n) d.write(values.data(), H5::PredType::NATIVE_DOUBLE);
}

}  // namespace

StudyFiles write_study_table(const SweepPlan& plan) {
  std::vector<Row> rows;
  std::vector<std::string> names;  // result names, in first-seen order
  std::map<std::string, std::string> units;
  StudyFiles files;
  for (const SweepPoint& p : plan.points) {
    Row r;
    r.label = p.label;
    r.repeat = p.repeat;
    for (const auto& v : p.axis) r.axis[v.key] = v.yaml;
    const std::string out = plan.output_of(p);
    std::error_code ec;
    r.status = "missing";
    if (fs::exists(out, ec)) {
      try {
        for (const ResultScalar& s : read_result_scalars(out)) {
          if (!units.count(s.name)) {
            names.push_back(s.name);
            units[s.name] = s.unit;
          }
          r.results[s.name] = s;
        }
        bool interrupted = false;
        try {
          interrupted = read_stored_run(out).interrupted;
        } catch (const H5::Exception&) {
          interrupted = false;  // its scalars were readable; the run status is only a flag
        }
        r.status = interrupted ? "interrupted" : "done";
        ++(r.status == "done" ? files.with_results : files.partial);
      } catch (const Error& e) {
        r.status = "unreadable";
      }
    } else if (fs::exists(out + ".checkpoint", ec)) {
      r.status = "unfinished";
    }
    rows.push_back(std::move(r));
  }
  files.rows = rows.size();

  std::error_code ec;
  fs::create_directories(plan.output_dir, ec);
  files.csv = (fs::path(plan.output_dir) / "study.csv").string();
  files.h5 = (fs::path(plan.output_dir) / "study.h5").string();

  {
    const std::string tmp = files.csv + ".part";
    std::ofstream csv(tmp);
    csv << "point,status,repeat";
    for (const auto& k : plan.axis_keys) csv << "," << field(k);
    for (const auto& n : names)
      csv << "," << field(n) << "," << field(n + "_se") << "," << field(n + "_no_plateau");
    csv << "\n";
    for (const Row& r : rows) {
      csv << field(r.label) << "," << r.status << "," << r.repeat;
      for (const auto& k : plan.axis_keys) csv << "," << field(r.axis.count(k) ? r.axis.at(k) : "");
      for (const auto& n : names) {
        const auto it = r.results.find(n);
        if (it == r.results.end())
          csv << ",,,";
        else
          csv << "," << number(it->second.value) << "," << number(it->second.stderr_value) << ","
              << (it->second.no_plateau ? 1 : 0);
      }
      csv << "\n";
    }
    csv.close();
    if (!csv) throw Error(tmp + ": cannot write the study table");
    fs::rename(tmp, files.csv, ec);
    if (ec) throw Error(files.csv + ": cannot write the study table: " + ec.message());
  }

  io::quiet_hdf5();
  const std::string tmp = files.h5 + ".part";
  try {
    H5::H5File f(tmp, H5F_ACC_TRUNC);
    H5::Group root = f.openGroup("/");
    io::set_string_attribute(root, "sweep", plan.file);
    io::set_string_attribute(root, "base", plan.base);
    H5::Group points = f.createGroup("points");
    std::vector<std::string> labels, status;
    std::vector<double> repeats;
    for (const Row& r : rows) {
      labels.push_back(r.label);
      status.push_back(r.status);
      repeats.push_back(r.repeat);
    }
    write_strings(points, "label", labels);
    write_strings(points, "status", status);
    write_doubles(points, "repeat", repeats);
    // Axis values: numbers where every value is one, the YAML text otherwise.
    H5::Group axes = f.createGroup("axes");
    for (const auto& k : plan.axis_keys) {
      std::vector<std::string> text;
      std::vector<double> x;
      bool numeric = true;
      for (const Row& r : rows) {
        text.push_back(r.axis.count(k) ? r.axis.at(k) : "");
        double v = 0.0;
        numeric = numeric && parse_number(text.back(), v);
        x.push_back(v);
      }
      if (numeric)
        write_doubles(axes, k, x);
      else
        write_strings(axes, k, text);
    }
    H5::Group results = f.createGroup("results");
    for (const auto& n : names) {
      H5::Group g = io::ensure_group(results, n);
      std::vector<double> value, se, flag;
      for (const Row& r : rows) {
        const auto it = r.results.find(n);
        value.push_back(it == r.results.end() ? NAN : it->second.value);
        se.push_back(it == r.results.end() ? NAN : it->second.stderr_value);
        flag.push_back(it == r.results.end() ? NAN : double(it->second.no_plateau));
      }
      write_doubles(g, "value", value);
      write_doubles(g, "stderr", se);
      write_doubles(g, "no_plateau", flag);
      io::set_string_attribute(g, "unit", units[n]);
    }
  } catch (const H5::Exception& e) {
    io::fail(tmp, "cannot write the study table", e);
  }
  fs::rename(tmp, files.h5, ec);
  if (ec) throw Error(files.h5 + ": cannot write the study table: " + ec.message());
  return files;
}

}  // namespace fldsim
