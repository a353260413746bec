#include "io/MemoryResultSink.hpp"

#include "fldsim/error.hpp"

namespace fldsim {
namespace {

std::string key(const std::string& path) {
  return !path.empty() && path.front() == '/' ? path.substr(1) : path;
}

std::size_t count(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (std::size_t d : shape) n *= d;
  return n;
}

}  // namespace

void MemoryResultSink::write_scalar(const std::string& path, double value, double stderr_value,
                                    const std::string& unit, const std::string& description) {
  scalars_[key(path)] = {value, stderr_value, unit, description};
}

void MemoryResultSink::write_array(const std::string& path, const std::vector<std::size_t>& shape,
                                   const double* data, const std::string& unit,
                                   const std::string& description) {
  arrays_[key(path)] = {shape, std::vector<double>(data, data + count(shape)), unit, description};
}

void MemoryResultSink::append_sample(const std::string& path, std::int64_t step, double time,
                                     const std::vector<std::size_t>& shape, const double* data,
                                     const std::string& unit) {
  Series& s = series_[key(path)];
  if (!s.steps.empty() && s.shape != shape)
    throw Error(path + ": a sample's shape differs from the earlier samples' shape");
  s.shape = shape;
  s.unit = unit;
  s.steps.push_back(step);
  s.times.push_back(time);
  s.data.insert(s.data.end(), data, data + count(shape));
}

void MemoryResultSink::write_attribute(const std::string& path, const std::string& k,
                                       const std::string& value) {
  attributes_[key(path)][k] = value;
}

}  // namespace fldsim
