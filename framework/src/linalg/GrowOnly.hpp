// Storage whose length follows the number of lubricated pairs. That number drifts by a few per
// cent from step to step as pairs cross the cutoff; std::vector's assign() and copy-assignment
// reallocate to the exact new length, so every new maximum would touch the heap inside the time
// step. Growing with 25 % headroom instead lets the step run allocation-free once the first
// steps have sized the buffers (tests/dynamics/StepAllocationTest.cpp).
#pragma once

#include <cstddef>
#include <vector>

namespace fldsim::linalg {

template <class T, class A>
void reserve_with_headroom(std::vector<T, A>& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4 + 16);
}

// dst = src, reusing dst's storage.
template <class T, class A>
void copy_grow_only(std::vector<T, A>& dst, const std::vector<T, A>& src) {
  reserve_with_headroom(dst, src.size());
  dst.assign(src.begin(), src.end());
}

}  // namespace fldsim::linalg
