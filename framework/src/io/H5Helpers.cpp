#include "io/H5Helpers.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "fldsim/error.hpp"

namespace fldsim::io {

namespace {

// The innermost entry of HDF5's error stack says why, e.g. the sec2 driver's "file write failed:
// ..., errno = 28, error message = 'No space left on device', ..." or "file signature not
// found" for a file that is not HDF5; the C++ exception only names the failing call.
herr_t innermost(unsigned n, const H5E_error2_t* entry, void* data) {
  if (n == 0 && entry && entry->desc) *static_cast<std::string*>(data) = entry->desc;
  return 0;
}

// The reason of the first failure since the last fail(): HDF5 calls this (its "auto" error
// handler) when an API call fails, while the error stack is still intact; the C++ wrappers'
// destructors clear the stack before a catch block could read it. Per thread.
thread_local std::string first_reason;

herr_t record_reason(hid_t stack, void*) {
  std::string desc;
  H5Ewalk2(stack, H5E_WALK_UPWARD, innermost, &desc);
  // A later failure (a close during unwinding) is less telling, unless it carries an errno.
  if (first_reason.empty() || (desc.find("error message = '") != std::string::npos &&
                               first_reason.find("error message = '") == std::string::npos))
    first_reason = desc;
  return 0;
}

std::string explain(const std::string& desc) {
  // Before the errno text: HDF5 says "unable to lock file, errno = 11, error message = 'Resource
  // temporarily unavailable'" for a file a running fldsim is writing.
  if (desc.find("unable to lock file") != std::string::npos)
    return "locked by another process (another fldsim run writing it?)";
  const std::string marker = "error message = '";
  if (const auto at = desc.find(marker); at != std::string::npos) {
    const auto end = desc.find('\'', at + marker.size());
    return desc.substr(at + marker.size(),
                       end == std::string::npos ? std::string::npos : end - at - marker.size());
  }
  if (desc.find("file signature not found") != std::string::npos) return "not an HDF5 file";
  if (desc.find("truncated file") != std::string::npos)
    return "truncated file (an interrupted copy or write?)";
  return desc;
}

}  // namespace

namespace {
std::atomic<bool> any_write_failed{false};
}

void note_write_failure() {
  any_write_failed = true;
}

bool write_failed() {
  return any_write_failed;
}

QuietCerr::QuietCerr() : saved_(std::cerr.rdbuf(nullptr)) {}

QuietCerr::~QuietCerr() {
  std::cerr.rdbuf(saved_);
  std::cerr.clear();
}

void quiet_hdf5() {
  static std::once_flag once;
  std::call_once(once, [] {
    H5::Exception::dontPrint();
    H5Eset_auto2(H5E_DEFAULT, record_reason, nullptr);
  });
}

void fail(const std::string& file, const std::string& what, const H5::Exception& e) {
  std::string detail = explain(first_reason);
  first_reason.clear();
  if (detail.empty()) detail = e.getDetailMsg();
  if (detail.empty()) detail = e.getFuncName();
  throw Error(file + ": " + what + (detail.empty() ? "" : ": " + detail));
}

namespace {
std::vector<std::string> components(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::size_t end = slash == std::string::npos ? path.size() : slash;
    if (end > start) parts.push_back(path.substr(start, end - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return parts;
}

H5::StrType fixed_string_type(std::size_t length) {
  H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(length, 1));
  type.setStrpad(H5T_STR_NULLTERM);
  type.setCset(H5T_CSET_UTF8);
  return type;
}

void remove_attribute(H5::H5Object& obj, const std::string& key) {
  if (obj.attrExists(key)) obj.removeAttr(key);
}
}  // namespace

H5::Group ensure_group(H5::Group root, const std::string& path) {
  H5::Group g = root;
  for (const auto& part : components(path)) {
    if (H5Lexists(g.getId(), part.c_str(), H5P_DEFAULT) > 0)
      g = g.openGroup(part);
    else
      g = g.createGroup(part);
  }
  return g;
}

bool path_exists(const H5::Group& root, const std::string& path) {
  // H5Lexists needs each intermediate link to exist, so test level by level.
  std::string prefix;
  for (const auto& part : components(path)) {
    prefix += (prefix.empty() ? "" : "/") + part;
    if (H5Lexists(root.getId(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

void split_path(const std::string& path, std::string& parent, std::string& leaf) {
  std::string p = path;
  while (p.size() > 1 && p.back() == '/') p.pop_back();
  const std::size_t slash = p.rfind('/');
  if (slash == std::string::npos) {
    parent.clear();
    leaf = p;
  } else {
    parent = p.substr(0, slash);
    leaf = p.substr(slash + 1);
  }
}

void set_string_attribute(H5::H5Object& obj, const std::string& key, const std::string& value) {
  remove_attribute(obj, key);
  const H5::StrType type = fixed_string_type(value.size() + 1);
  H5::Attribute a = obj.createAttribute(key, type, H5::DataSpace(H5S_SCALAR));
  a.write(type, value.c_str());
}

void set_string_list_attribute(H5::H5Object& obj, const std::string& key,
                               const std::vector<std::string>& values) {
  remove_attribute(obj, key);
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size() + 1);
  std::vector<char> buffer(values.size() * width, '\0');
  for (std::size_t i = 0; i < values.size(); ++i)
    std::copy(values[i].begin(), values[i].end(), &buffer[i * width]);
  const hsize_t n = values.size();
  const H5::StrType type = fixed_string_type(width);
  H5::Attribute a = obj.createAttribute(key, type, H5::DataSpace(1, &n));
  if (n > 0) a.write(type, buffer.data());
}

void set_double_attribute(H5::H5Object& obj, const std::string& key, double value) {
  remove_attribute(obj, key);
  H5::Attribute a = obj.createAttribute(key, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
  a.write(H5::PredType::NATIVE_DOUBLE, &value);
}

void set_int_attribute(H5::H5Object& obj, const std::string& key, const std::vector<std::int64_t>& values) {
  remove_attribute(obj, key);
  const hsize_t n = values.size();
  // One value is stored as a scalar (H5MD `dimension` is a plain integer), more as a vector.
  const H5::DataSpace space = n == 1 ? H5::DataSpace(H5S_SCALAR) : H5::DataSpace(1, &n);
  H5::Attribute a = obj.createAttribute(key, H5::PredType::NATIVE_INT64, space);
  if (n > 0) a.write(H5::PredType::NATIVE_INT64, values.data());
}

std::string read_string_attribute(const H5::H5Object& obj, const std::string& key) {
  H5::Attribute a = obj.openAttribute(key);
  std::string value;
  // Attribute::read(DataType, std::string&) handles fixed- and variable-length strings.
  a.read(a.getStrType(), value);
  // Fixed-length strings may carry their padding.
  const std::size_t nul = value.find('\0');
  if (nul != std::string::npos) value.resize(nul);
  return value;
}

double read_double_attribute(const H5::H5Object& obj, const std::string& key) {
  H5::Attribute a = obj.openAttribute(key);
  double v = 0.0;
  a.read(H5::PredType::NATIVE_DOUBLE, &v);
  return v;
}

std::vector<std::int64_t> read_int_attribute(const H5::H5Object& obj, const std::string& key) {
  H5::Attribute a = obj.openAttribute(key);
  const H5::DataSpace space = a.getSpace();
  std::vector<std::int64_t> v(static_cast<std::size_t>(space.getSimpleExtentNpoints()));
  if (!v.empty()) a.read(H5::PredType::NATIVE_INT64, v.data());
  return v;
}

void write_string_dataset(H5::Group& group, const std::string& name, const std::string& text) {
  const H5::StrType type = fixed_string_type(text.size() + 1);
  H5::DataSet d = group.createDataSet(name, type, H5::DataSpace(H5S_SCALAR));
  d.write(text.c_str(), type);
}

std::string read_string_dataset(const H5::Group& group, const std::string& name) {
  H5::DataSet d = group.openDataSet(name);
  std::string text;
  d.read(text, d.getStrType());
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos) text.resize(nul);
  return text;
}

}  // namespace fldsim::io
