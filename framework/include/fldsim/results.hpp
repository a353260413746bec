// Where observers write their results: the run's HDF5 file, behind an interface so plugins do
// not depend on the HDF5 library. Paths are HDF5 paths relative to the file root.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fldsim/api.hpp"

namespace fldsim {

class FLDSIM_VISIBLE ResultSink {
 public:
  virtual ~ResultSink() = default;
  // A steady-state scalar with its standard error, e.g. /results/orientation/delta_theta_m.
  virtual void write_scalar(const std::string& path, double value, double stderr_value, const std::string& unit,
                            const std::string& description) = 0;
  // A fixed array (row-major, `shape` gives its dimensions).
  virtual void write_array(const std::string& path, const std::vector<std::size_t>& shape, const double* data,
                           const std::string& unit, const std::string& description) = 0;
  // Append one sample to an H5MD time-dependent element at `path` (group with step, time,
  // value). `shape` is the shape of one sample; all samples of an element share it.
  virtual void append_sample(const std::string& path, std::int64_t step, double time,
                             const std::vector<std::size_t>& shape, const double* data, const std::string& unit) = 0;
  // A string attribute on a group or dataset (created as a group if absent).
  virtual void write_attribute(const std::string& path, const std::string& key, const std::string& value) = 0;
  // Typed attributes, for conventions that require them (H5MD `dimension` is an integer,
  // `boundary` a string array). The defaults fall back to one comma-separated string attribute
  // for sinks that only store text.
  virtual void write_int_attribute(const std::string& path, const std::string& key,
                                   const std::vector<std::int64_t>& values) {
    std::string joined;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) joined += ',';
      joined += std::to_string(values[i]);
    }
    write_attribute(path, key, joined);
  }
  virtual void write_string_list_attribute(const std::string& path, const std::string& key,
                                           const std::vector<std::string>& values) {
    std::string joined;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) joined += ',';
      joined += values[i];
    }
    write_attribute(path, key, joined);
  }
};

}  // namespace fldsim
