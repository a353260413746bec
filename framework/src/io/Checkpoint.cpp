#include "io/Checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <new>
#include <stdexcept>

#include "fldsim/error.hpp"
#include "io/H5Helpers.hpp"
#include "io/IsolatedRead.hpp"

namespace fldsim {

namespace {

constexpr const char* kFormat = "fldsim-checkpoint";
constexpr std::int64_t kFormatVersion = 1;

void write_matrix(H5::Group& g, const std::string& name, const double* data, hsize_t rows, hsize_t cols) {
  const hsize_t dims[2] = {rows, cols};
  H5::DataSet d = g.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(cols ? 2 : 1, dims));
  if (rows > 0) d.write(data, H5::PredType::NATIVE_DOUBLE);
}

// file_bytes bounds the extent: checkpoints are written contiguous and uncompressed, so a
// dataset holds at most the file's bytes; a larger extent is a corrupt size, refused before
// anything is allocated for it.
std::vector<double> read_doubles(const H5::Group& g, const std::string& name, hsize_t cols, hsize_t& rows,
                                 std::uintmax_t file_bytes) {
  H5::DataSet d = g.openDataSet(name);
  const H5::DataSpace space = d.getSpace();
  const int rank = space.getSimpleExtentNdims();
  hsize_t dims[2] = {0, 0};
  if (rank != (cols ? 2 : 1)) throw H5::DataSetIException("read_checkpoint", name + " has the wrong rank");
  space.getSimpleExtentDims(dims);
  if (cols && dims[1] != cols)
    throw H5::DataSetIException("read_checkpoint", name + " has the wrong row length");
  rows = dims[0];
  if (rows > file_bytes / sizeof(double) / (cols ? cols : 1))
    throw H5::DataSetIException("read_checkpoint", name + " claims " + std::to_string(rows) +
                                                       " rows, more than the file can hold (corrupt)");
  std::vector<double> v(rows * (cols ? cols : 1));
  if (v.empty()) return v;
  // The stored layout must be what write_matrix makes (8-byte floats, contiguous, inside the
  // file): HDF5 itself reads out of bounds on a corrupt file whose datatype or storage size
  // disagrees with the dataspace (found by the fuzzer under AddressSanitizer).
  const std::uintmax_t bytes = v.size() * sizeof(double);
  const haddr_t offset = H5Dget_offset(d.getId());
  if (d.getTypeClass() != H5T_FLOAT || d.getDataType().getSize() != sizeof(double) ||
      d.getStorageSize() != bytes || offset == HADDR_UNDEF || offset > file_bytes ||
      bytes > file_bytes - offset)
    throw H5::DataSetIException("read_checkpoint", name + " is not stored as written (corrupt)");
  d.read(v.data(), H5::PredType::NATIVE_DOUBLE);
  return v;
}

void write_vec3s(H5::Group& g, const std::string& name, const std::vector<Vec3>& v) {
  // std::vector<Vector3d> is contiguous with no padding: 3 doubles per element.
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  write_matrix(g, name, v.empty() ? nullptr : v.front().data(), v.size(), 3);
}

std::vector<Vec3> read_vec3s(const H5::Group& g, const std::string& name, std::uintmax_t file_bytes) {
  hsize_t rows = 0;
  const std::vector<double> flat = read_doubles(g, name, 3, rows, file_bytes);
  std::vector<Vec3> v(rows);
  for (hsize_t i = 0; i < rows; ++i) v[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return v;
}

template <class T>
void write_value(H5::Group& g, const std::string& name, const H5::PredType& type, const T& value) {
  H5::DataSet d = g.createDataSet(name, type, H5::DataSpace(H5S_SCALAR));
  d.write(&value, type);
}

template <class T>
T read_value(const H5::Group& g, const std::string& name, const H5::PredType& type) {
  T value{};
  g.openDataSet(name).read(&value, type);
  return value;
}

// Make the data (and then the directory entry) durable before and after the rename.
void fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) {
    if (directory) return;  // not all file systems allow opening a directory; the data is synced
    throw Error(path + ": cannot reopen the checkpoint to sync it: " + std::strerror(errno));
  }
  const int rc = ::fsync(fd);
  const int why = errno;
  ::close(fd);
  if (rc != 0 && !directory)
    throw Error(path + ": cannot sync the checkpoint to disk: " + std::strerror(why));
}

}  // namespace

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  io::quiet_hdf5();
  const std::size_t n = c.positions.size();
  if (c.orientations.size() != n || c.displacement.size() != n || c.nonaffine.size() != n)
    throw Error(path + ": checkpoint arrays have different body counts");
  const std::string tmp = path + ".tmp";
  try {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
  } catch (const std::filesystem::filesystem_error& e) {
    throw Error(path + ": cannot create the checkpoint directory: " + e.what());
  }
  const io::QuietCerr quiet;  // failed closes are reported once, below
  try {
    H5::H5File file(tmp, H5F_ACC_TRUNC);
    H5::Group root = file.openGroup("/");
    io::set_string_attribute(root, "format", kFormat);
    io::set_int_attribute(root, "format_version", {kFormatVersion});

    write_vec3s(root, "positions", c.positions);
    write_vec3s(root, "displacement", c.displacement);
    write_vec3s(root, "nonaffine", c.nonaffine);
    // Quaternions scalar-first (w, x, y, z), the order of the trajectory (H5MD proposal 104).
    std::vector<double> q(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      q[4 * i] = c.orientations[i].w();
      q[4 * i + 1] = c.orientations[i].x();
      q[4 * i + 2] = c.orientations[i].y();
      q[4 * i + 3] = c.orientations[i].z();
    }
    write_matrix(root, "orientations", q.data(), n, 4);
    write_matrix(root, "warm_start", c.warm_start.data(), c.warm_start.size(), 0);

    write_value(root, "time", H5::PredType::NATIVE_DOUBLE, c.time);
    write_value(root, "strain", H5::PredType::NATIVE_DOUBLE, c.strain);
    write_value(root, "box_edge", H5::PredType::NATIVE_DOUBLE, c.box_edge);
    write_value(root, "step", H5::PredType::NATIVE_INT64, c.step);
    write_value(root, "seed", H5::PredType::NATIVE_UINT64, c.seed);
    io::write_string_dataset(root, "experiment", c.experiment_yaml);

    H5::Group blobs = root.createGroup("blobs");
    for (const auto& [name, data] : c.blobs) {
      if (name.empty() || name.find('/') != std::string::npos || name == ".")
        throw Error(path + ": observer blob name '" + name + "' cannot be an HDF5 link name");
      write_matrix(blobs, name, data.data(), data.size(), 0);
    }
    file.close();
  } catch (const H5::Exception& e) {
    // The previous checkpoint stays as it was; the half-written one goes.
    io::note_write_failure();
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    io::fail(tmp, "cannot write the checkpoint (the previous one is kept)", e);
  }
  try {
    fsync_path(tmp, false);
  } catch (const Error&) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(tmp + ": cannot rename to " + path + ": " + ec.message());
  const std::string dir = std::filesystem::path(path).parent_path().string();
  fsync_path(dir.empty() ? "." : dir, true);
}

namespace {

Checkpoint read_checkpoint_in_process(const std::string& path) {
  io::quiet_hdf5();
  if (!std::filesystem::exists(path)) throw Error(path + ": checkpoint file not found");
  Checkpoint c;
  std::error_code size_error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, size_error);
  if (size_error) throw Error(path + ": cannot read the checkpoint: " + size_error.message());
  try {
    H5::H5File file(path, H5F_ACC_RDONLY);
    H5::Group root = file.openGroup("/");
    if (!root.attrExists("format") || io::read_string_attribute(root, "format") != kFormat)
      throw Error(path + ": not an fldsim checkpoint (no format = \"" + kFormat + "\" attribute)");
    const auto version = io::read_int_attribute(root, "format_version");
    if (version.size() != 1 || version[0] != kFormatVersion)
      throw Error(path + ": checkpoint format version " +
                  (version.empty() ? "?" : std::to_string(version[0])) + " is not the supported version " +
                  std::to_string(kFormatVersion));

    c.positions = read_vec3s(root, "positions", bytes);
    c.displacement = read_vec3s(root, "displacement", bytes);
    c.nonaffine = read_vec3s(root, "nonaffine", bytes);
    hsize_t rows = 0;
    const std::vector<double> q = read_doubles(root, "orientations", 4, rows, bytes);
    c.orientations.resize(rows);
    for (hsize_t i = 0; i < rows; ++i)
      c.orientations[i] = Quat(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
    c.warm_start = read_doubles(root, "warm_start", 0, rows, bytes);

    c.time = read_value<double>(root, "time", H5::PredType::NATIVE_DOUBLE);
    c.strain = read_value<double>(root, "strain", H5::PredType::NATIVE_DOUBLE);
    c.box_edge = read_value<double>(root, "box_edge", H5::PredType::NATIVE_DOUBLE);
    c.step = read_value<std::int64_t>(root, "step", H5::PredType::NATIVE_INT64);
    c.seed = read_value<std::uint64_t>(root, "seed", H5::PredType::NATIVE_UINT64);
    c.experiment_yaml = io::read_string_dataset(root, "experiment");

    H5::Group blobs = root.openGroup("blobs");
    for (hsize_t i = 0; i < blobs.getNumObjs(); ++i) {
      const std::string name = blobs.getObjnameByIdx(i);
      c.blobs[name] = read_doubles(blobs, name, 0, rows, bytes);
    }
  } catch (const H5::Exception& e) {
    io::fail(path, "cannot read the checkpoint", e);
  } catch (const std::bad_alloc&) {  // a size no check above bounds (a string's length)
    throw Error(path + ": cannot read the checkpoint: a size in it exceeds the memory (corrupt file)");
  } catch (const std::length_error&) {
    throw Error(path + ": cannot read the checkpoint: a size in it exceeds the memory (corrupt file)");
  }
  const std::size_t n = c.positions.size();
  if (c.orientations.size() != n || c.displacement.size() != n || c.nonaffine.size() != n)
    throw Error(path + ": checkpoint arrays have different body counts");
  return c;
}

}  // namespace

Checkpoint read_checkpoint(const std::string& path) {
  return io::read_isolated(path, "checkpoint", [&] { return read_checkpoint_in_process(path); });
}

}  // namespace fldsim
