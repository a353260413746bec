// Exact restart: everything the run needs to continue bit-for-bit, in one HDF5 file. The
// counter-based RNG is keyed by (seed, step, ...), so seed and step are its whole state.
// Doubles are native double datasets, hence stored and read back bit-exactly.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fldsim/box.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

struct Checkpoint {
  std::vector<Vec3> positions, displacement, nonaffine;
  std::vector<Quat> orientations;
  double time = 0, strain = 0, box_edge = 0;
  std::int64_t step = 0;
  std::uint64_t seed = 0;
  std::string experiment_yaml;                       // resolved experiment, for a consistency check
  std::vector<double> warm_start;                    // last dU of the solver
  std::map<std::string, std::vector<double>> blobs;  // observer accumulators, by observer name
};

// Written to `path.tmp`, fsync'ed, then renamed over `path` (rename is atomic on POSIX), so a
// crash during the write leaves the previous checkpoint intact.
void write_checkpoint(const std::string& path, const Checkpoint& c);
// Throws fldsim::Error naming the file if it is missing, not a checkpoint, or inconsistent.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace fldsim
