// `fldsim sweep`: a study of many experiments from one sweep file (docs/sweep.md), on the local
// cores or, under mpirun/srun, over MPI ranks.
#pragma once

#include <string>
#include <vector>

namespace fldsim {

extern const char* kSweepHelp;

int sweep_command(const std::vector<std::string>& args);

// True when this process was started by an MPI launcher (mpirun, srun) as one of several ranks.
bool launched_by_mpi();

}  // namespace fldsim
