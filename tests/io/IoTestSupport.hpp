// Shared helpers of the io tests: a scratch directory per test and HDF5 read-back helpers.
#pragma once

#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fldsim::test {

// A fresh directory for the running test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("fldsim-io-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::vector<hsize_t> dims_of(const H5::DataSet& d) {
  const H5::DataSpace s = d.getSpace();
  std::vector<hsize_t> dims(s.getSimpleExtentNdims());
  s.getSimpleExtentDims(dims.data());
  return dims;
}

inline std::vector<double> read_all(const H5::DataSet& d) {
  std::vector<double> v(d.getSpace().getSimpleExtentNpoints());
  if (!v.empty()) d.read(v.data(), H5::PredType::NATIVE_DOUBLE);
  return v;
}

inline std::string string_attr(const H5::H5Object& o, const std::string& key) {
  H5::Attribute a = o.openAttribute(key);
  std::string s;
  a.read(a.getStrType(), s);
  return s.substr(0, s.find('\0'));
}

inline double double_attr(const H5::H5Object& o, const std::string& key) {
  double v = 0;
  o.openAttribute(key).read(H5::PredType::NATIVE_DOUBLE, &v);
  return v;
}

inline std::vector<long long> int_attr(const H5::H5Object& o, const std::string& key) {
  H5::Attribute a = o.openAttribute(key);
  std::vector<long long> v(a.getSpace().getSimpleExtentNpoints());
  a.read(H5::PredType::NATIVE_LLONG, v.data());
  return v;
}

// Fixed-length string array attribute (H5MD `boundary`).
inline std::vector<std::string> string_list_attr(const H5::H5Object& o, const std::string& key) {
  H5::Attribute a = o.openAttribute(key);
  H5::StrType t = a.getStrType();
  const std::size_t width = t.getSize();
  const std::size_t n = a.getSpace().getSimpleExtentNpoints();
  std::vector<char> buffer(n * width);
  a.read(t, buffer.data());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n; ++i) {
    std::string s(&buffer[i * width], width);
    out.push_back(s.substr(0, s.find('\0')));
  }
  return out;
}

}  // namespace fldsim::test
