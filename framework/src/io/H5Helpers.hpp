// Thin helpers over the official HDF5 C++ API (HDF5 1.10) shared by the result file, the
// checkpoint, the frame reader and `fldsim summary`: groups created on demand, string and
// numeric attributes, and HDF5 exceptions turned into fldsim::Error naming the file.
#pragma once

#include <H5Cpp.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

namespace fldsim::io {

// Silence the HDF5 error stack printer once per process (errors become exceptions instead).
void quiet_hdf5();

// After a failed write (a full disk) HDF5 1.10's own state can be inconsistent, and closing any
// file, not only the one that failed, can then crash (SIGSEGV in H5F__close). Writers record
// the failure; files still open are then left open for the (immediate) exit of the program.
void note_write_failure();
bool write_failed();

// While alive, std::cerr prints nothing: the HDF5 C++ destructors print "H5Dclose failed" there
// themselves when a close fails (a full disk), and the reason is reported once, by fail().
class QuietCerr {
 public:
  QuietCerr();
  ~QuietCerr();
  QuietCerr(const QuietCerr&) = delete;
  QuietCerr& operator=(const QuietCerr&) = delete;

 private:
  std::streambuf* saved_;
};

// Throw fldsim::Error("<file>: <what>: <HDF5 detail>").
[[noreturn]] void fail(const std::string& file, const std::string& what, const H5::Exception& e);

// Open the group at absolute or relative `path` below `root`, creating every missing level.
H5::Group ensure_group(H5::Group root, const std::string& path);
// True when every component of `path` exists below `root` (no exception on a missing link).
bool path_exists(const H5::Group& root, const std::string& path);
// Split "a/b/c" into parent "a/b" and leaf "c" (parent "" for a top-level name).
void split_path(const std::string& path, std::string& parent, std::string& leaf);

// Attributes (replacing an existing one of the same name). Strings are fixed-length,
// null-terminated, UTF-8, as H5MD readers expect.
void set_string_attribute(H5::H5Object& obj, const std::string& key, const std::string& value);
void set_string_list_attribute(H5::H5Object& obj, const std::string& key,
                               const std::vector<std::string>& values);
void set_double_attribute(H5::H5Object& obj, const std::string& key, double value);
// One value is written as a scalar attribute, several as a vector.
void set_int_attribute(H5::H5Object& obj, const std::string& key, const std::vector<std::int64_t>& values);
std::string read_string_attribute(const H5::H5Object& obj, const std::string& key);
double read_double_attribute(const H5::H5Object& obj, const std::string& key);
std::vector<std::int64_t> read_int_attribute(const H5::H5Object& obj, const std::string& key);

// A scalar string dataset (for long text such as the resolved YAML: attributes are limited to
// 64 KiB in the default compact storage).
void write_string_dataset(H5::Group& group, const std::string& name, const std::string& text);
std::string read_string_dataset(const H5::Group& group, const std::string& name);

}  // namespace fldsim::io
