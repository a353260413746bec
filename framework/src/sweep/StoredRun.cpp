#include "sweep/StoredRun.hpp"

#include <H5Cpp.h>

#include "io/H5Helpers.hpp"
#include "io/IsolatedRead.hpp"

namespace fldsim {

namespace {

StoredRun read_stored_run_in_process(const std::string& result_file) {
  io::quiet_hdf5();
  H5::H5File f(result_file, H5F_ACC_RDONLY);
  const H5::Group parameters = f.openGroup("/parameters");
  StoredRun run;
  run.interrupted = parameters.attrExists("run_status") &&
                    io::read_string_attribute(parameters, "run_status").rfind("interrupted", 0) == 0;
  run.experiment = io::read_string_dataset(parameters, "experiment");
  return run;
}

}  // namespace

StoredRun read_stored_run(const std::string& result_file) {
  return io::read_isolated(result_file, "result file",
                           [&] { return read_stored_run_in_process(result_file); });
}

}  // namespace fldsim
