#include "io/Hdf5ResultSink.hpp"

#include <pwd.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "fldsim/error.hpp"
#include "fldsim/trajectory_layout.hpp"
#include "io/H5Helpers.hpp"
#include "io/H5mdUnits.hpp"

#ifndef FLDSIM_VERSION
#define FLDSIM_VERSION "unknown"
#endif

namespace fldsim {

namespace fs = std::filesystem;

namespace {
// Chunk length (samples) of a time series: about 64 KiB of values per chunk, at least one
// sample and at most 1024, so both scalar series and large per-particle frames stay efficient.
hsize_t chunk_samples(const std::vector<hsize_t>& sample_shape) {
  hsize_t bytes = sizeof(double);
  for (hsize_t d : sample_shape) bytes *= std::max<hsize_t>(d, 1);
  return std::clamp<hsize_t>((64 * 1024) / bytes, 1, 1024);
}

H5::DataSet create_series(H5::Group& g, const std::string& name, const H5::PredType& type,
                          const std::vector<hsize_t>& sample_shape) {
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{chunk_samples(sample_shape)};
  for (hsize_t d : sample_shape) {
    dims.push_back(d);
    maxdims.push_back(d);
    chunk.push_back(std::max<hsize_t>(d, 1));
  }
  H5::DSetCreatPropList props;
  props.setChunk(static_cast<int>(chunk.size()), chunk.data());
  H5::DataSpace space(static_cast<int>(dims.size()), dims.data(), maxdims.data());
  return g.createDataSet(name, type, space, props);
}

// Append one sample to an extendible dataset whose first dimension counts samples: `extent`
// is the current extent (its first entry grows by one), `offset`/`block` the hyperslab buffers.
void append_rows(H5::DataSet& d, const H5::PredType& type, const void* data, int rank, hsize_t* extent,
                 hsize_t* offset, const hsize_t* block) {
  offset[0] = extent[0];
  extent[0] += 1;
  d.extend(extent);
  H5::DataSpace file_space = d.getSpace();
  file_space.selectHyperslab(H5S_SELECT_SET, block, offset);
  H5::DataSpace mem_space(rank, block);
  d.write(data, type, mem_space, file_space);
}
// H5MD unit attribute; a dimensionless quantity ("") has none.
void set_unit(H5::H5Object& obj, const char* key, const std::string& unit) {
  if (!unit.empty()) io::set_string_attribute(obj, key, io::h5md_unit(unit));
}

std::string without_leading_slash(const std::string& path) {
  return !path.empty() && path.front() == '/' ? path.substr(1) : path;
}

// H5MD requires an author name: the login name, else the account name, else "unknown".
std::string user_name() {
  if (const char* user = std::getenv("USER"); user && *user) return user;
  if (const passwd* pw = ::getpwuid(::getuid()); pw && pw->pw_name) return pw->pw_name;
  return "unknown";
}
}  // namespace

Hdf5ResultSink::Hdf5ResultSink(const std::string& path, bool overwrite)
    : path_(path), part_path_(path + ".part") {
  io::quiet_hdf5();
  if (!overwrite && fs::exists(path))
    throw Error(path + " exists; refusing to overwrite it (use --overwrite or another -o)");
  try {
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty()) fs::create_directories(parent);
  } catch (const fs::filesystem_error& e) {
    throw Error(path + ": cannot create the output directory: " + e.what());
  }
  try {
    file_ = H5::H5File(part_path_, H5F_ACC_TRUNC);
    open_ = true;
    H5::Group root = file_.openGroup("/");
    H5::Group h5md = root.createGroup("h5md");
    io::set_int_attribute(h5md, "version", {1, 1});
    H5::Group author = h5md.createGroup("author");
    io::set_string_attribute(author, "name", user_name());
    H5::Group creator = h5md.createGroup("creator");
    io::set_string_attribute(creator, "name", "fldsim");
    io::set_string_attribute(creator, "version", FLDSIM_VERSION);
    H5::Group units = h5md.createGroup("modules").createGroup("units");
    io::set_int_attribute(units, "version", {1, 0});
    io::set_string_attribute(units, "system", io::kUnitSystem);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot create the result file", e);
  }
}

Hdf5ResultSink::~Hdf5ResultSink() {
  // An uncommitted run keeps its data in `<path>.part` (never under the real name).
  if (open_) {
    try {
      series_.clear();
      file_.close();
    } catch (...) {
    }
  }
}

void Hdf5ResultSink::check_open(const char* what) const {
  if (!open_) throw Error(path_ + ": " + what + " after the result file was committed");
}

void Hdf5ResultSink::write_parameters(const std::string& resolved_yaml,
                                      const std::vector<std::array<std::string, 4>>& plugins,
                                      std::uint64_t seed,
                                      const std::map<std::string, ParameterValue>& extra) {
  check_open("write_parameters");
  try {
    H5::Group p = io::ensure_group(file_.openGroup("/"), "parameters");
    io::write_string_dataset(p, "experiment", resolved_yaml);

    std::size_t width = 1;
    for (const auto& row : plugins)
      for (const auto& cell : row) width = std::max(width, cell.size() + 1);
    std::vector<char> table(plugins.size() * 4 * width, '\0');
    for (std::size_t i = 0; i < plugins.size(); ++i)
      for (std::size_t k = 0; k < 4; ++k)
        std::copy(plugins[i][k].begin(), plugins[i][k].end(), &table[(i * 4 + k) * width]);
    const hsize_t dims[2] = {plugins.size(), 4};
    H5::StrType type(H5::PredType::C_S1, width);
    type.setStrpad(H5T_STR_NULLTERM);
    type.setCset(H5T_CSET_UTF8);
    H5::DataSet d = p.createDataSet("plugins", type, H5::DataSpace(2, dims));
    if (!plugins.empty()) d.write(table.data(), type);
    io::set_string_list_attribute(d, "columns", {"kind", "name", "version", "file"});

    if (p.attrExists("seed")) p.removeAttr("seed");
    H5::Attribute a = p.createAttribute("seed", H5::PredType::NATIVE_UINT64, H5::DataSpace(H5S_SCALAR));
    a.write(H5::PredType::NATIVE_UINT64, &seed);
    for (const auto& [key, value] : extra) {
      if (const auto* number = std::get_if<double>(&value))
        io::set_double_attribute(p, key, *number);
      else
        io::set_string_attribute(p, key, std::get<std::string>(value));
    }
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot write /parameters", e);
  }
}

void Hdf5ResultSink::write_experiment_source(const std::string& file_text,
                                             const std::vector<std::string>& overrides) {
  check_open("write_experiment_source");
  try {
    H5::Group p = io::ensure_group(file_.openGroup("/"), "parameters");
    io::write_string_dataset(p, "experiment_source", file_text);
    H5::DataSet d = p.openDataSet("experiment_source");
    io::set_string_attribute(d, "description",
                             "the experiment file as written; `experiment` is it after overrides");
    io::set_string_list_attribute(d, "overrides", overrides);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot write /parameters/experiment_source", e);
  }
}

void Hdf5ResultSink::set_time_unit(const std::string& unit, double internal_per_unit) {
  if (!series_.empty()) throw Error(part_path_ + ": the time unit is set after time series were written");
  if (!(internal_per_unit > 0.0))
    throw Error(part_path_ + ": time unit " + unit + " must be a positive time");
  time_unit_ = unit;
  time_scale_ = internal_per_unit;
}

H5::Group Hdf5ResultSink::parent_of_new(const std::string& path, std::string& leaf) {
  std::string parent;
  io::split_path(path, parent, leaf);
  H5::Group g = io::ensure_group(file_.openGroup("/"), parent);
  if (H5Lexists(g.getId(), leaf.c_str(), H5P_DEFAULT) > 0)
    throw Error(part_path_ + ": " + path + " written twice");
  return g;
}

void Hdf5ResultSink::write_scalar(const std::string& path, double value, double stderr_value,
                                  const std::string& unit, const std::string& description) {
  check_open("write_scalar");
  try {
    std::string leaf;
    H5::Group g = parent_of_new(path, leaf);
    H5::DataSet d = g.createDataSet(leaf, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
    d.write(&value, H5::PredType::NATIVE_DOUBLE);
    set_unit(d, "unit", unit);
    io::set_double_attribute(d, "stderr", stderr_value);
    io::set_string_attribute(d, "description", description);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot write scalar " + path, e);
  }
}

void Hdf5ResultSink::write_array(const std::string& path, const std::vector<std::size_t>& shape,
                                 const double* data, const std::string& unit,
                                 const std::string& description) {
  check_open("write_array");
  try {
    std::string leaf;
    H5::Group g = parent_of_new(path, leaf);
    const std::vector<hsize_t> dims(shape.begin(), shape.end());
    H5::DataSpace space =
        dims.empty() ? H5::DataSpace(H5S_SCALAR) : H5::DataSpace(static_cast<int>(dims.size()), dims.data());
    H5::DataSet d = g.createDataSet(leaf, H5::PredType::NATIVE_DOUBLE, space);
    if (space.getSimpleExtentNpoints() > 0) d.write(data, H5::PredType::NATIVE_DOUBLE);
    set_unit(d, "unit", unit);
    io::set_string_attribute(d, "description", description);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot write array " + path, e);
  }
}

Hdf5ResultSink::TimeSeries& Hdf5ResultSink::time_series(const std::string& path,
                                                        const std::vector<std::size_t>& shape,
                                                        const std::string& unit) {
  auto it = series_.find(path);
  if (it != series_.end()) {
    if (!std::equal(shape.begin(), shape.end(), it->second.sample_shape.begin(),
                    it->second.sample_shape.end()))
      throw Error(part_path_ + ": " + path + ": sample shape changed between appends");
    return it->second;
  }
  H5::Group g = io::ensure_group(file_.openGroup("/"), path);
  if (H5Lexists(g.getId(), "value", H5P_DEFAULT) > 0)
    throw Error(part_path_ + ": " + path + " already holds a time series not written by this run");
  TimeSeries ts;
  ts.sample_shape.assign(shape.begin(), shape.end());
  ts.step = create_series(g, "step", H5::PredType::NATIVE_INT64, {});
  ts.time = create_series(g, "time", H5::PredType::NATIVE_DOUBLE, {});
  ts.value = create_series(g, "value", H5::PredType::NATIVE_DOUBLE, ts.sample_shape);
  if (without_leading_slash(path) == without_leading_slash(trajectory::kPosition)) {
    set_unit(g, "unit", unit);  // MDAnalysis 2.4 (see the header)
    set_unit(g, "time_unit", time_unit_);
  } else {
    set_unit(ts.value, "unit", unit);
    set_unit(ts.time, "unit", time_unit_);
  }
  ts.extent.assign(1 + shape.size(), 0);
  std::copy(ts.sample_shape.begin(), ts.sample_shape.end(), ts.extent.begin() + 1);
  ts.offset.assign(1 + shape.size(), 0);
  ts.block = ts.extent;
  ts.block[0] = 1;
  return series_.emplace(path, std::move(ts)).first->second;
}

void Hdf5ResultSink::append_sample(const std::string& path, std::int64_t step, double time,
                                   const std::vector<std::size_t>& shape, const double* data,
                                   const std::string& unit) {
  check_open("append_sample");
  try {
    TimeSeries& ts = time_series(path, shape, unit);
    // step and time are one-dimensional with the same sample count as value.
    const hsize_t one = 1;
    hsize_t count = ts.extent[0], offset = 0;
    append_rows(ts.step, H5::PredType::NATIVE_INT64, &step, 1, &count, &offset, &one);
    count = ts.extent[0];
    const double user_time = time / time_scale_;
    append_rows(ts.time, H5::PredType::NATIVE_DOUBLE, &user_time, 1, &count, &offset, &one);
    append_rows(ts.value, H5::PredType::NATIVE_DOUBLE, data, static_cast<int>(ts.extent.size()),
                ts.extent.data(), ts.offset.data(), ts.block.data());
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot append a sample to " + path, e);
  }
}

template <class Fn>
void Hdf5ResultSink::on_object(const std::string& path, Fn&& fn) {
  H5::Group root = file_.openGroup("/");
  std::string trimmed = path;
  while (!trimmed.empty() && trimmed.front() == '/') trimmed.erase(trimmed.begin());
  if (trimmed.empty()) {
    fn(root);
    return;
  }
  if (io::path_exists(root, trimmed) && root.childObjType(trimmed) == H5O_TYPE_DATASET) {
    H5::DataSet d = root.openDataSet(trimmed);
    fn(d);
    return;
  }
  H5::Group g = io::ensure_group(root, trimmed);
  fn(g);
}

template <class Fn>
void Hdf5ResultSink::set_attribute(const char* what, const std::string& path, const std::string& key,
                                   Fn&& fn) {
  check_open(what);
  try {
    on_object(path, fn);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot write attribute " + key + " of " + path, e);
  }
}

void Hdf5ResultSink::write_attribute(const std::string& path, const std::string& key,
                                     const std::string& value) {
  set_attribute("write_attribute", path, key,
                [&](H5::H5Object& o) { io::set_string_attribute(o, key, value); });
}

void Hdf5ResultSink::write_int_attribute(const std::string& path, const std::string& key,
                                         const std::vector<std::int64_t>& values) {
  set_attribute("write_int_attribute", path, key,
                [&](H5::H5Object& o) { io::set_int_attribute(o, key, values); });
}

void Hdf5ResultSink::write_string_list_attribute(const std::string& path, const std::string& key,
                                                 const std::vector<std::string>& values) {
  set_attribute("write_string_list_attribute", path, key,
                [&](H5::H5Object& o) { io::set_string_list_attribute(o, key, values); });
}

void Hdf5ResultSink::flush() {
  check_open("flush");
  try {
    file_.flush(H5F_SCOPE_GLOBAL);
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot flush", e);
  }
}

void Hdf5ResultSink::commit() {
  check_open("commit");
  try {
    series_.clear();
    file_.close();
    open_ = false;
  } catch (const H5::Exception& e) {
    io::fail(part_path_, "cannot close", e);
  }
  std::error_code ec;
  fs::rename(part_path_, path_, ec);
  if (ec) throw Error(part_path_ + ": cannot rename to " + path_ + ": " + ec.message());
}

}  // namespace fldsim
