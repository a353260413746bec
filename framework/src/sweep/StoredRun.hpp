// What a point's result file says about its run: the experiment it holds (/parameters/experiment)
// and whether a signal stopped it (RunExperiment's stop_early marks /parameters run_status).
#pragma once

#include <string>

namespace fldsim {

struct StoredRun {
  std::string experiment;
  bool interrupted = false;  // partial results: the run was stopped by SIGINT/SIGTERM
};

// Throws H5::Exception when the file is not a readable fldsim result.
StoredRun read_stored_run(const std::string& result_file);

}  // namespace fldsim
