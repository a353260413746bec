// Hdf5ResultSink: every ResultSink call read back with the HDF5 C++ API, the H5MD 1.1
// structure (h5md/version = {1,1}, time-dependent elements step/time/value), and the file
// safety rules (no overwrite without permission, `.part` renamed only on commit).
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "IoTestSupport.hpp"
#include "fldsim/error.hpp"
#include "io/Hdf5ResultSink.hpp"

namespace fldsim {
namespace {

using test::dims_of;
using test::read_all;
using test::string_attr;

TEST(Hdf5ResultSink, WritesEveryCallInTheH5mdLayout) {
  test::ScratchDir dir;
  const std::string path = dir.file("sub/dir/run.h5");  // parent directories are created
  const std::string yaml = "system:\n  count: 8\nrun: {dt: 0.001}\n";
  {
    Hdf5ResultSink sink(path, false);
    sink.write_parameters(yaml,
                          {{"shape", "dicolloid", "1.0.0", "/p/fldsim-shape-dicolloid.so"},
                           {"hydro", "fld", "1.2.0", "/p/fldsim-hydro-fld.so"}},
                          18446744073709551557ull, {{"time_unit", "paper"}, {"units", "a, kT, a^2/D0"}});
    sink.write_scalar("/results/orientation/theta_m", 0.9, 0.01, "rad", "peak polar angle");
    const double array[6] = {1, 2, 3, 4, 5, 6};
    sink.write_array("/results/pair/g", {2, 3}, array, "", "pair distribution");
    for (int k = 0; k < 3; ++k) {
      const double v[2] = {10.0 * k, 10.0 * k + 1};
      sink.append_sample("/observables/pair_energy", 100 * k, 0.5 * k, {2}, v, "kT");
      const double s = -k;
      sink.append_sample("/observables/strain", 100 * k, 0.5 * k, {}, &s, "");
    }
    sink.write_attribute("/results/orientation/theta_m", "method", "block average");  // on a dataset
    sink.write_attribute("/particles/bodies/box", "note", "created on demand");       // new group
    sink.write_int_attribute("/particles/bodies/box", "dimension", {3});
    sink.write_string_list_attribute("/particles/bodies/box", "boundary", {"periodic", "periodic", "none"});
    sink.flush();
    sink.commit();
  }

  H5::H5File f(path, H5F_ACC_RDONLY);
  // H5MD 1.1 root group (h5md.mdwn, "H5MD root group").
  H5::Group h5md = f.openGroup("/h5md");
  EXPECT_EQ(test::int_attr(h5md, "version"), (std::vector<long long>{1, 1}));
  EXPECT_EQ(string_attr(f.openGroup("/h5md/creator"), "name"), "fldsim");
  EXPECT_FALSE(string_attr(f.openGroup("/h5md/creator"), "version").empty());
  EXPECT_FALSE(string_attr(f.openGroup("/h5md/author"), "name").empty());

  // Parameters.
  H5::Group p = f.openGroup("/parameters");
  std::string stored;
  H5::DataSet experiment = p.openDataSet("experiment");
  experiment.read(stored, experiment.getStrType());
  EXPECT_EQ(stored.substr(0, stored.find('\0')), yaml);
  H5::DataSet plugins = p.openDataSet("plugins");
  ASSERT_EQ(dims_of(plugins), (std::vector<hsize_t>{2, 4}));
  const H5::StrType t = plugins.getStrType();
  std::vector<char> cells(8 * t.getSize());
  plugins.read(cells.data(), t);
  EXPECT_STREQ(&cells[1 * t.getSize()], "dicolloid");
  EXPECT_STREQ(&cells[6 * t.getSize()], "1.2.0");
  EXPECT_EQ(test::string_list_attr(plugins, "columns"),
            (std::vector<std::string>{"kind", "name", "version", "file"}));
  unsigned long long seed = 0;
  p.openAttribute("seed").read(H5::PredType::NATIVE_ULLONG, &seed);
  EXPECT_EQ(seed, 18446744073709551557ull);
  EXPECT_EQ(string_attr(p, "time_unit"), "paper");
  EXPECT_EQ(string_attr(p, "units"), "a, kT, a^2/D0");

  // Scalar with unit, stderr and description.
  H5::DataSet theta = f.openDataSet("/results/orientation/theta_m");
  EXPECT_EQ(read_all(theta), (std::vector<double>{0.9}));
  EXPECT_EQ(string_attr(theta, "unit"), "rad");
  EXPECT_EQ(test::double_attr(theta, "stderr"), 0.01);
  EXPECT_EQ(string_attr(theta, "description"), "peak polar angle");
  EXPECT_EQ(string_attr(theta, "method"), "block average");

  // Array with its shape.
  H5::DataSet g = f.openDataSet("/results/pair/g");
  EXPECT_EQ(dims_of(g), (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(read_all(g), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(string_attr(g, "description"), "pair distribution");

  // H5MD time-dependent elements: step [3] int64, time [3], value [3][2] and [3].
  H5::DataSet step = f.openDataSet("/observables/pair_energy/step");
  EXPECT_EQ(step.getDataType().getClass(), H5T_INTEGER);
  EXPECT_EQ(step.getDataType().getSize(), 8u);
  EXPECT_EQ(dims_of(step), (std::vector<hsize_t>{3}));
  EXPECT_EQ(read_all(step), (std::vector<double>{0, 100, 200}));
  EXPECT_EQ(read_all(f.openDataSet("/observables/pair_energy/time")), (std::vector<double>{0, 0.5, 1.0}));
  H5::DataSet value = f.openDataSet("/observables/pair_energy/value");
  EXPECT_EQ(dims_of(value), (std::vector<hsize_t>{3, 2}));
  EXPECT_EQ(read_all(value), (std::vector<double>{0, 1, 10, 11, 20, 21}));
  EXPECT_EQ(string_attr(value, "unit"), "kT");
  // Extendible (H5S_UNLIMITED) so a run can keep appending.
  hsize_t cur[2], max[2];
  value.getSpace().getSimpleExtentDims(cur, max);
  EXPECT_EQ(max[0], H5S_UNLIMITED);
  H5::DataSet scalar_series = f.openDataSet("/observables/strain/value");
  EXPECT_EQ(dims_of(scalar_series), (std::vector<hsize_t>{3}));
  EXPECT_EQ(read_all(scalar_series), (std::vector<double>{0, -1, -2}));

  H5::Group box = f.openGroup("/particles/bodies/box");
  EXPECT_EQ(string_attr(box, "note"), "created on demand");
  EXPECT_EQ(test::int_attr(box, "dimension"), (std::vector<long long>{3}));
  EXPECT_EQ(test::string_list_attr(box, "boundary"),
            (std::vector<std::string>{"periodic", "periodic", "none"}));
}

// Times in the run's unit: stored time = internal time / internal time per unit, with the unit
// in H5MD grammar on every time dataset; the units module is declared; numbers in /parameters
// are doubles (bit-exact, 2.5e-7 is not "0.000000"), the experiment text is kept byte for byte.
TEST(Hdf5ResultSink, TimesInTheRunsUnitAndExactParameters) {
  test::ScratchDir dir;
  const std::string path = dir.file("units.h5");
  const std::string text = "# a comment and odd spacing survive\nflow: {peclet:   2.5e-7}\n";
  {
    Hdf5ResultSink sink(path, false);
    sink.set_time_unit("1/gammadot", 0.25);  // gammadot = 4 in internal units
    sink.write_parameters("flow: {peclet: 2.5e-7}\n", {}, 1,
                          {{"peclet", 2.5e-7}, {"time_unit", "1/gammadot"}});
    sink.write_experiment_source(text, {"flow.peclet=2.5e-7"});
    const double v = 1.0;
    sink.append_sample("timeseries/x/q", 10, 0.75, {}, &v, "kT/a^3");
    EXPECT_THROW(sink.set_time_unit("a^2/D0", 1.0), Error);  // too late: a series exists
    sink.commit();
  }
  H5::H5File f(path, H5F_ACC_RDONLY);
  H5::Group units = f.openGroup("/h5md/modules/units");
  EXPECT_EQ(test::int_attr(units, "version"), (std::vector<long long>{1, 0}));
  EXPECT_NE(string_attr(units, "system").find("a = node radius"), std::string::npos);
  H5::DataSet time = f.openDataSet("/timeseries/x/q/time");
  EXPECT_EQ(read_all(time), (std::vector<double>{3.0}));  // 0.75 / 0.25, exact in binary
  EXPECT_EQ(string_attr(time, "unit"), "gammadot-1");
  EXPECT_EQ(string_attr(f.openDataSet("/timeseries/x/q/value"), "unit"), "kT a-3");
  H5::Group p = f.openGroup("/parameters");
  EXPECT_EQ(p.openAttribute("peclet").getDataType().getClass(), H5T_FLOAT);
  EXPECT_EQ(test::double_attr(p, "peclet"), 2.5e-7);
  H5::DataSet source = p.openDataSet("experiment_source");
  std::string stored;
  source.read(stored, source.getStrType());
  EXPECT_EQ(stored.substr(0, stored.find('\0')), text);
  EXPECT_EQ(test::string_list_attr(source, "overrides"), (std::vector<std::string>{"flow.peclet=2.5e-7"}));
}

TEST(Hdf5ResultSink, RefusesToOverwriteAndLeavesTheFileByteIdentical) {
  test::ScratchDir dir;
  const std::string path = dir.file("old.h5");
  const std::string content = "an earlier result that must survive\n";
  std::ofstream(path, std::ios::binary) << content;
  try {
    Hdf5ResultSink sink(path, false);
    FAIL() << "an existing file was accepted without overwrite";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + " exists; refusing to overwrite it"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(test::file_bytes(path), content);
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
}

TEST(Hdf5ResultSink, PartFileRenamedOnlyOnCommit) {
  test::ScratchDir dir;
  const std::string path = dir.file("run.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.write_scalar("/results/x", 1.0, 0.1, "a", "x");
    sink.flush();
    EXPECT_TRUE(std::filesystem::exists(path + ".part"));
    EXPECT_FALSE(std::filesystem::exists(path));
    sink.commit();
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_FALSE(std::filesystem::exists(path + ".part"));
    EXPECT_THROW(sink.write_scalar("/results/y", 1.0, 0.1, "a", "y"), Error);  // closed
  }
  // A run that dies before commit leaves only the .part file.
  const std::string crashed = dir.file("crashed.h5");
  {
    Hdf5ResultSink sink(crashed, false);
    sink.write_scalar("/results/x", 1.0, 0.1, "a", "x");
  }
  EXPECT_FALSE(std::filesystem::exists(crashed));
  EXPECT_TRUE(std::filesystem::exists(crashed + ".part"));
}

TEST(Hdf5ResultSink, OverwriteReplacesTheOldFileOnlyAtCommit) {
  test::ScratchDir dir;
  const std::string path = dir.file("run.h5");
  const std::string content = "old\n";
  std::ofstream(path, std::ios::binary) << content;
  Hdf5ResultSink sink(path, true);
  sink.write_scalar("/results/x", 2.5, 0.0, "", "x");
  EXPECT_EQ(test::file_bytes(path), content);  // untouched while the run is going
  sink.commit();
  H5::H5File f(path, H5F_ACC_RDONLY);
  EXPECT_EQ(read_all(f.openDataSet("/results/x")), (std::vector<double>{2.5}));
}

TEST(Hdf5ResultSink, RejectsInconsistentWrites) {
  test::ScratchDir dir;
  Hdf5ResultSink sink(dir.file("run.h5"), false);
  const double v[3] = {1, 2, 3};
  sink.append_sample("/observables/v", 0, 0.0, {2}, v, "");
  EXPECT_THROW(sink.append_sample("/observables/v", 1, 1.0, {3}, v, ""), Error);
  sink.write_scalar("/results/x", 1.0, 0.1, "", "");
  EXPECT_THROW(sink.write_scalar("/results/x", 1.0, 0.1, "", ""), Error);
}

}  // namespace
}  // namespace fldsim
