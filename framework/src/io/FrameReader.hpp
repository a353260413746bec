// Read the last frame of the trajectory that the `trajectory` observer wrote into a result
// file (/particles/bodies in the H5MD layout), so a new run can start from an earlier result.
#pragma once

#include <string>

#include "io/Checkpoint.hpp"

namespace fldsim {

// positions (wrapped centres), orientations, box edge, strain, and the frame's step and time.
// The displacements start again from zero (a new run measures its own); warm_start, seed,
// experiment_yaml and blobs are left empty. Throws fldsim::Error naming the file if it holds
// no trajectory or the trajectory is inconsistent.
Checkpoint read_last_frame(const std::string& result_h5);

}  // namespace fldsim
