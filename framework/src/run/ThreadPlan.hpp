// How many OpenMP threads a run uses, and why. OpenMP threads that outnumber the free cores do
// not just share them: at every barrier (several per conjugate-gradient iteration) a thread spins
// waiting for one that is descheduled, and a step can become a hundred times slower. So the
// automatic choice takes the cores this process may use (affinity mask) minus those already busy
// (1-minute load average), and no more threads than the system has work for.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fldsim {

struct ThreadPlan {
  int threads = 1;
  bool automatic = false;             // chosen here, not by run.threads or OMP_NUM_THREADS
  std::string reason;                 // for the run log
  std::vector<std::string> warnings;  // oversubscription risks, for the run log
};

// requested: the experiment's run.threads (0 = automatic).
ThreadPlan plan_threads(std::int64_t requested, std::size_t bodies);

// Bodies per thread below which another thread costs more (fork/join, and waits wherever an IC(0)
// dependency crosses threads: 28 dependency levels per sweep at N = 1000, phi = 0.5) than it saves. At N =
// 1000, bench/step measured a 2-thread speed-up of 1.24-1.38 on a quiet machine but 0.93-1.53 on the shared
// 2-core one (bench/RESULTS.md), so one thread up to 2000 bodies. Above, a long run checks the plan on its
// first steps (ThreadTrial).
inline constexpr std::size_t kBodiesPerThread = 2000;

}  // namespace fldsim
