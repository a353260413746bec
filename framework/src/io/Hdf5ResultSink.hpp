// The run's result file: HDF5 in the H5MD 1.1 layout (de Buyl, Colberg & Höfling, Comput. Phys.
// Commun. 185, 1546 (2014); spec h5md.mdwn release 1.1.0). Root group `h5md` with version {1,1},
// author, creator and the units module (/h5md/modules/units, system = fldsim's reduced units);
// `/parameters` with the experiment as written and as resolved; observer results under the
// paths they choose (steady-state numbers under /results, time series under /timeseries,
// trajectories under /particles). Unit attributes use the units module's grammar (H5mdUnits).
//
// Times: observers pass internal time (a^2/D0); every time dataset holds the run's own time
// unit (set_time_unit) and says so in its `unit` attribute.
//
// One exception, for MDAnalysis 2.4 (the version Debian 12 ships): its H5MD reader refuses any
// `unit` string outside its own table (nm, ps, ...), even with convert_units=False, and reads
// the units of /particles/<group>/position only. So that element keeps its two units as
// attributes of its group (`unit`, `time_unit`) instead of on its `value` and `time` datasets.
//
// Everything is written into `<path>.part`; commit() renames it to `path` only at the end of a
// successful run, so an existing result is never lost and a crashed run never leaves a half
// file under the real name.
#pragma once

#include <H5Cpp.h>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "fldsim/api.hpp"
#include "fldsim/results.hpp"

namespace fldsim {

class FLDSIM_VISIBLE Hdf5ResultSink : public ResultSink {
 public:
  // Throws fldsim::Error if `path` exists and !overwrite, or if the file cannot be created.
  Hdf5ResultSink(const std::string& path, bool overwrite);
  ~Hdf5ResultSink() override;
  Hdf5ResultSink(const Hdf5ResultSink&) = delete;
  Hdf5ResultSink& operator=(const Hdf5ResultSink&) = delete;

  // A /parameters attribute: text, or a number stored as a double (exactly).
  using ParameterValue = std::variant<std::string, double>;
  // /parameters: the resolved YAML (dataset `experiment`), the plugin table (dataset `plugins`,
  // strings [n][4] with columns kind, name, version, file), the seed and `extra` attributes
  // (e.g. time_unit, peclet).
  void write_parameters(const std::string& resolved_yaml,
                        const std::vector<std::array<std::string, 4>>& plugins, std::uint64_t seed,
                        const std::map<std::string, ParameterValue>& extra);
  // /parameters/experiment_source: the experiment file byte for byte, and the --set overrides
  // applied to it (attribute `overrides`, in order).
  void write_experiment_source(const std::string& file_text, const std::vector<std::string>& overrides);

  // The run's time unit: stored times are internal times / internal_per_unit, and every time
  // dataset gets `unit` = h5md_unit(unit). Call before the first append_sample (default: the
  // internal unit a^2/D0).
  void set_time_unit(const std::string& unit, double internal_per_unit);

  void write_scalar(const std::string& path, double value, double stderr_value, const std::string& unit,
                    const std::string& description) override;
  void write_array(const std::string& path, const std::vector<std::size_t>& shape, const double* data,
                   const std::string& unit, const std::string& description) override;
  void append_sample(const std::string& path, std::int64_t step, double time,
                     const std::vector<std::size_t>& shape, const double* data,
                     const std::string& unit) override;
  void write_attribute(const std::string& path, const std::string& key, const std::string& value) override;
  void write_int_attribute(const std::string& path, const std::string& key,
                           const std::vector<std::int64_t>& values) override;
  void write_string_list_attribute(const std::string& path, const std::string& key,
                                   const std::vector<std::string>& values) override;

  // Push buffered data to disk (the .part file is readable up to here after a crash).
  void flush();
  // Close the file and rename `<path>.part` to `path`. Nothing may be written afterwards.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& part_path() const { return part_path_; }

 private:
  // An H5MD time-dependent element being appended to.
  struct TimeSeries {
    H5::DataSet step, time, value;
    std::vector<hsize_t> sample_shape;  // shape of one sample
    std::vector<hsize_t> extent;        // current value extent: {count, sample_shape...}
    std::vector<hsize_t> offset;        // hyperslab start, {count, 0, ...}
    std::vector<hsize_t> block;         // hyperslab count, {1, sample_shape...}
  };
  TimeSeries& time_series(const std::string& path, const std::vector<std::size_t>& shape,
                          const std::string& unit);
  void check_open(const char* what) const;
  // The group that will hold the new dataset at `path` (created as needed); its last component
  // goes to `leaf`. A path written before is refused.
  H5::Group parent_of_new(const std::string& path, std::string& leaf);
  // Apply `fn` to the group or dataset at `path` (a group is created if nothing is there).
  template <class Fn>
  void on_object(const std::string& path, Fn&& fn);
  // Apply `fn` to the group or dataset at `path`, turning HDF5 failures into fldsim::Error.
  template <class Fn>
  void set_attribute(const char* what, const std::string& path, const std::string& key, Fn&& fn);

  std::string path_;
  std::string part_path_;
  H5::H5File file_;
  bool open_ = false;
  std::map<std::string, TimeSeries> series_;
  std::string time_unit_ = "a^2/D0";
  double time_scale_ = 1.0;
};

}  // namespace fldsim
