#include "run/ThreadPlan.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fldsim {
namespace {

int usable_cpus() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return 1;
}

double load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : 0.0;
}

std::string format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

}  // namespace

ThreadPlan plan_threads(std::int64_t requested, std::size_t bodies) {
  ThreadPlan plan;
#ifndef _OPENMP
  (void)requested;
  (void)bodies;
  plan.reason = "built without OpenMP";
  return plan;
#else
  const int cpus = usable_cpus();
  const double load = load_average();
  const int idle = std::max(1, cpus - int(std::lround(load)));
  if (requested > 0) {
    plan.threads = int(requested);
    plan.reason = "run.threads";
  } else if (std::getenv("OMP_NUM_THREADS") != nullptr) {
    plan.threads = omp_get_max_threads();
    plan.reason = "OMP_NUM_THREADS";
  } else {
    const int useful = int(std::max<std::size_t>(1, bodies / kBodiesPerThread));
    plan.threads = std::max(1, std::min(idle, useful));
    plan.automatic = true;
    std::ostringstream why;
    why << "automatic: " << cpus << " usable CPU(s), load average " << format(load) << ", " << bodies
        << " bodies (one thread per " << kBodiesPerThread << ")";
    plan.reason = why.str();
  }
  if (plan.threads > cpus)
    plan.warnings.push_back(std::to_string(plan.threads) + " threads on " + std::to_string(cpus) +
                            " usable CPU(s): oversubscribed OpenMP threads wait for each other; expect a "
                            "much slower run");
  else if (plan.threads > 1 && plan.threads > idle)
    plan.warnings.push_back("load average " + format(load) + " on " + std::to_string(cpus) +
                            " CPU(s): only about " + std::to_string(idle) + " idle for " +
                            std::to_string(plan.threads) +
                            " threads; consider run.threads: " + std::to_string(idle));
  return plan;
#endif
}

}  // namespace fldsim
