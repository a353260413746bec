// OpenMP loops that cost nothing extra on one thread (plugin API 5.6; the core's own loops in the
// step use them too).
//
// Every OpenMP parallel region costs a system call, even with a team of one and even with a false
// `if` clause: libgomp ends the region's barrier with futex(FUTEX_WAKE) whether or not a thread
// waits (measured: 1000 regions of one thread, 1000 futex calls). A step of the documented LAMMPS
// scene entered about 115 regions (CG's dots and vector updates, the neighbour refresh, the moves,
// the lubrication assembly), and they were 6 % of its one-thread step (fldsim's bench/README.md,
// "One-thread steps without OpenMP regions"). So on one thread the loop runs directly, in the order a static
// schedule of one thread would run it: results are bitwise the same either way.
#pragma once

#include <omp.h>

namespace fldsim {

// True when a parallel region here would have a single thread: one is requested, or this is
// already inside a region (nested regions are inactive).
inline bool single_thread() {
  return omp_in_parallel() || omp_get_max_threads() == 1;
}

// for (k = 0; k < count; ++k) body(k), statically scheduled over the team when there is one.
template <class Index, class Body>
inline void parallel_for(Index count, const Body& body) {
  if (single_thread()) {
    for (Index k = 0; k < count; ++k) body(k);
    return;
  }
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < count; ++k) body(k);
}

// body() on every thread of a new team, or once on this thread. body may contain orphaned
// `omp for` constructs: outside any region they run the whole range here and their barriers
// return at once (an orphaned construct binds to the implicit one-thread team). Inside a region
// they would bind to the enclosing team, so there the (inactive) nested region is kept.
template <class Body>
inline void parallel_region(const Body& body) {
  if (!omp_in_parallel() && omp_get_max_threads() == 1) {
    body();
    return;
  }
#pragma omp parallel
  body();
}

}  // namespace fldsim
