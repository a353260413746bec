// The sweep over MPI ranks (OpenMPI, Debian's libopenmpi): rank 0 hands out points, longest
// first, to whichever rank is free (dynamic scheduling) and runs points itself between
// messages; every rank runs its point as a child `fldsim run` process, so a point that crashes
// costs only that point. Polling with short sleeps (MPI_Iprobe/MPI_Test) keeps idle ranks off
// the cores their points need.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sweep/LocalSweep.hpp"

namespace fldsim {

// Whether this fldsim was built with MPI.
bool mpi_available();

// Runs `order` over the ranks of MPI_COMM_WORLD. Every rank calls it with the same plan and
// points. Returns on every rank; `outcome` is filled on rank 0 only. Sets `rank`.
SweepRunOutcome run_sweep_mpi(const SweepPlan& plan, const std::vector<PointState>& points,
                              const std::vector<std::size_t>& order, const std::string& program,
                              std::ostream& log, int& rank);

// MPI_Init / MPI_Finalize around a sweep (no-ops without MPI).
void mpi_begin(int& rank, int& size);
void mpi_end();
// Broadcast of a status code from rank 0 (e.g. "the points are valid"); identity without MPI.
int mpi_broadcast(int value);

}  // namespace fldsim
