// In-memory ResultSink for observer tests: keeps every scalar, array and time series written.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "fldsim/results.hpp"

namespace fldsim::test {

class FakeSink : public ResultSink {
 public:
  struct Scalar {
    double value, stderr_value;
    std::string unit, description;
  };
  struct Array {
    std::vector<std::size_t> shape;
    std::vector<double> data;
    std::string unit;
  };
  struct Series {
    std::vector<std::int64_t> steps;
    std::vector<double> times;
    std::vector<std::size_t> shape;
    std::vector<double> data;  // samples concatenated
  };

  void write_scalar(const std::string& path, double value, double stderr_value, const std::string& unit,
                    const std::string& description) override {
    scalars[path] = {value, stderr_value, unit, description};
  }
  void write_array(const std::string& path, const std::vector<std::size_t>& shape, const double* data,
                   const std::string& unit, const std::string&) override {
    std::size_t n = 1;
    for (auto s : shape) n *= s;
    arrays[path] = {shape, std::vector<double>(data, data + n), unit};
  }
  void append_sample(const std::string& path, std::int64_t step, double time,
                     const std::vector<std::size_t>& shape, const double* data, const std::string&) override {
    auto& s = series[path];
    if (!s.steps.empty() && s.shape != shape)
      throw std::logic_error(std::string("shape changed in ").append(path));
    std::size_t n = 1;
    for (auto d : shape) n *= d;
    s.shape = shape;
    s.steps.push_back(step);
    s.times.push_back(time);
    s.data.insert(s.data.end(), data, data + n);
  }
  void write_attribute(const std::string& path, const std::string& key, const std::string& value) override {
    attributes[path + "@" + key] = value;
  }

  const Scalar& scalar(const std::string& path) const {
    auto it = scalars.find(path);
    if (it == scalars.end()) throw std::out_of_range(std::string("no scalar ").append(path));
    return it->second;
  }

  std::map<std::string, Scalar> scalars;
  std::map<std::string, Array> arrays;
  std::map<std::string, Series> series;
  std::map<std::string, std::string> attributes;
};

}  // namespace fldsim::test
