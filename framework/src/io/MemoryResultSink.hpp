// A ResultSink that keeps everything in memory: the Python module hands results to numpy from
// it, and a front end that wants no file (a quick look, a sweep point kept in memory) uses it.
// Time series keep their samples concatenated; shapes are checked like the HDF5 sink does.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fldsim/api.hpp"
#include "fldsim/results.hpp"

namespace fldsim {

class FLDSIM_VISIBLE MemoryResultSink : public ResultSink {
 public:
  struct Scalar {
    double value = 0, stderr_value = 0;
    std::string unit, description;
  };
  struct Array {
    std::vector<std::size_t> shape;
    std::vector<double> data;
    std::string unit, description;
  };
  struct Series {
    std::vector<std::int64_t> steps;
    std::vector<double> times;       // internal time units (a^2/D0), as observers pass them
    std::vector<std::size_t> shape;  // of one sample
    std::vector<double> data;        // samples concatenated
    std::string unit;
  };

  void write_scalar(const std::string& path, double value, double stderr_value, const std::string& unit,
                    const std::string& description) override;
  void write_array(const std::string& path, const std::vector<std::size_t>& shape, const double* data,
                   const std::string& unit, const std::string& description) override;
  // Throws fldsim::Error if a sample's shape differs from the element's earlier samples.
  void append_sample(const std::string& path, std::int64_t step, double time,
                     const std::vector<std::size_t>& shape, const double* data,
                     const std::string& unit) override;
  void write_attribute(const std::string& path, const std::string& key, const std::string& value) override;

  // Keys are paths as the observers wrote them, without a leading '/'.
  const std::map<std::string, Scalar>& scalars() const { return scalars_; }
  const std::map<std::string, Array>& arrays() const { return arrays_; }
  const std::map<std::string, Series>& series() const { return series_; }
  const std::map<std::string, std::map<std::string, std::string>>& attributes() const { return attributes_; }

 private:
  std::map<std::string, Scalar> scalars_;
  std::map<std::string, Array> arrays_;
  std::map<std::string, Series> series_;
  std::map<std::string, std::map<std::string, std::string>> attributes_;
};

}  // namespace fldsim
