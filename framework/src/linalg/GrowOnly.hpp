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

// v.resize(n), reusing v's storage.
template <class T, class A>
void resize_grow_only(std::vector<T, A>& v, std::size_t n) {
  reserve_with_headroom(v, n);
  v.resize(n);
}

// v.assign(n, value), reusing v's storage.
template <class T, class A>
void fill_grow_only(std::vector<T, A>& v, std::size_t n, const T& value) {
  reserve_with_headroom(v, n);
  v.assign(n, value);
}

// dst.assign(first, last), reusing dst's storage.
template <class T, class A, class It>
void copy_grow_only(std::vector<T, A>& dst, It first, It last) {
  reserve_with_headroom(dst, std::size_t(last - first));
  dst.assign(first, last);
}

// dst = src, reusing dst's storage.
template <class T, class A>
void copy_grow_only(std::vector<T, A>& dst, const std::vector<T, A>& src) {
  copy_grow_only(dst, src.begin(), src.end());
}

}  // namespace fldsim::linalg
