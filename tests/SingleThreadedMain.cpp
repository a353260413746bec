// main() of every GoogleTest executable. ctest runs two tests at a time on the 2-core CI machine;
// a test with two OpenMP threads then shares its cores with the other test, and at every barrier
// (several per conjugate-gradient iteration) one thread spins waiting for a descheduled one: a
// 0.1 s test took 320 s on CI. So each test is single-threaded unless OMP_NUM_THREADS is set
// explicitly. (ctest's ENVIRONMENT property cannot carry this: gtest_discover_tests flattens the
// list and drops all but its first entry.) Tests of thread-count independence set their own counts.
#include <gtest/gtest.h>

#include <cstdlib>

#ifdef _OPENMP
#include <omp.h>
#endif

int main(int argc, char** argv) {
  if (std::getenv("OMP_NUM_THREADS") == nullptr) {
    ::setenv("OMP_NUM_THREADS", "1", 1);  // for fldsim runs that read it (ThreadPlan) and children
#ifdef _OPENMP
    omp_set_num_threads(1);  // libgomp read the environment before main
#endif
  }
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
