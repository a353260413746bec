#include "MpiSweep.hpp"

#include <unistd.h>

#include <memory>
#include <ostream>

#include "fldsim/error.hpp"

#ifdef FLDSIM_WITH_MPI
// The C API only: OpenMPI's mpi.h otherwise pulls in its removed C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace fldsim {

#ifdef FLDSIM_WITH_MPI

namespace {

constexpr int kTagWork = 1;  // rank 0 -> worker: position in `order`, or -1 = no more work
constexpr int kTagDone = 2;  // worker -> rank 0: {position, exit code}, then the seconds

// Receives one message without spinning on a core (OpenMPI's blocking receive polls).
template <typename T>
void receive_politely(T* data, int count, MPI_Datatype type, int source, int tag) {
  MPI_Request request;
  MPI_Irecv(data, count, type, source, tag, MPI_COMM_WORLD, &request);
  int done = 0;
  while (!done) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done) usleep(20000);
  }
}

// A worker rank: run the points it is given until told to stop.
void serve(const SweepPlan& plan, const std::vector<PointState>& points,
           const std::vector<std::size_t>& order, const std::string& program) {
  for (;;) {
    int position = -1;
    receive_politely(&position, 1, MPI_INT, 0, kTagWork);
    if (position < 0) return;
    PointProcess p(plan, points[order[std::size_t(position)]], program);
    int exit_code = 1;
    double seconds = 0.0;
    try {
      p.start();
      bool forwarded = false;
      while (!p.poll()) {
        if (sweep_signal() && !forwarded) {
          p.signal(sweep_signal());
          forwarded = true;
        }
        usleep(20000);
      }
      exit_code = p.result().exit_code;
      seconds = p.result().seconds;
    } catch (const Error&) {
      exit_code = 1;
    }
    int done[2] = {position, exit_code};
    MPI_Send(done, 2, MPI_INT, 0, kTagDone, MPI_COMM_WORLD);
    MPI_Send(&seconds, 1, MPI_DOUBLE, 0, kTagDone, MPI_COMM_WORLD);
  }
}

}  // namespace

bool mpi_available() {
  return true;
}

void mpi_begin(int& rank, int& size) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SINGLE, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
}

void mpi_end() {
  MPI_Finalize();
}

int mpi_broadcast(int value) {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

SweepRunOutcome run_sweep_mpi(const SweepPlan& plan, const std::vector<PointState>& points,
                              const std::vector<std::size_t>& order, const std::string& program,
                              std::ostream& log, int& rank) {
  int size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  SweepRunOutcome outcome;
  if (rank != 0) {
    serve(plan, points, order, program);
    return outcome;
  }
  std::size_t next = 0;
  std::vector<bool> busy(std::size_t(size), false);
  std::unique_ptr<PointProcess> own;  // rank 0 runs points too
  bool stopping = false;
  log << "fldsim sweep: " << order.size() << " point(s) over " << size << " MPI rank(s)\n";
  auto give = [&](int worker) {
    int position = (!stopping && next < order.size()) ? int(next++) : -1;
    if (position >= 0)
      log << "start " << plan.points[order[std::size_t(position)]].label << " on rank " << worker << "\n";
    MPI_Send(&position, 1, MPI_INT, worker, kTagWork, MPI_COMM_WORLD);
    busy[std::size_t(worker)] = position >= 0;
  };
  for (int w = 1; w < size; ++w) give(w);
  for (;;) {
    if (sweep_signal() && !stopping) {
      stopping = true;
      outcome.interrupted = true;
      if (own) own->signal(sweep_signal());
      log << "fldsim sweep: signal: running points checkpoint and stop; no new point starts\n";
    }
    if (!own && !stopping && next < order.size()) {
      log << "start " << plan.points[order[next]].label << " on rank 0\n";
      own = std::make_unique<PointProcess>(plan, points[order[next++]], program);
      own->start();
    }
    if (own && own->poll()) {
      outcome.results.push_back(own->result());
      report_point(plan, outcome.results.back(), outcome.results.size(), order.size(), log);
      own.reset();
    }
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagDone, MPI_COMM_WORLD, &flag, &status);
    if (flag) {
      const int worker = status.MPI_SOURCE;
      int done[2] = {0, 0};
      double seconds = 0.0;
      MPI_Recv(done, 2, MPI_INT, worker, kTagDone, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Recv(&seconds, 1, MPI_DOUBLE, worker, kTagDone, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      PointResult r;
      r.index = order[std::size_t(done[0])];
      r.exit_code = done[1];
      r.seconds = seconds;
      r.last_line = "see the point's log";
      outcome.results.push_back(r);
      report_point(plan, r, outcome.results.size(), order.size(), log);
      give(worker);
      continue;
    }
    bool any_busy = own != nullptr;
    for (int w = 1; w < size; ++w) any_busy = any_busy || busy[std::size_t(w)];
    if (!any_busy && (stopping || next >= order.size())) break;
    usleep(20000);
  }
  if (stopping && next < order.size()) outcome.interrupted = true;
  return outcome;
}

#else

bool mpi_available() {
  return false;
}
void mpi_begin(int& rank, int& size) {
  rank = 0;
  size = 1;
}
void mpi_end() {}
int mpi_broadcast(int value) {
  return value;
}
SweepRunOutcome run_sweep_mpi(const SweepPlan&, const std::vector<PointState>&,
                              const std::vector<std::size_t>&, const std::string&, std::ostream&, int& rank) {
  rank = 0;
  throw Error(
      "this fldsim was built without MPI (Debian: apt-get install libopenmpi-dev openmpi-bin, then rebuild)");
}

#endif

}  // namespace fldsim
