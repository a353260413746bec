// The 6x6 block products of the CG solve and of IC(0)'s factorisation and sweeps, written out for the
// compiler's two-wide double vectors (GCC/Clang vector extensions; SSE2 on x86-64, the only
// target measured and tested: on a target with FMA, -ffp-contract would need to be off here for the
// thread-count invariance below to be guaranteed).
// Eigen's fixed-size products of 6x6 blocks leave the transposed product A^T x to six scalar
// reductions and add every column of A x into one chain of dependent additions; these kernels
// take about 20 % less time per block (bench/README.md, "Block kernels"). Core-private.
//
// The order of every rounding is fixed by the kernel, not by the caller's loop, so a sum built
// block by block from these calls is the same whichever thread builds it (the multi-threaded
// gathers in BlockSparseMatrix and BlockIncompleteCholesky rely on it).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

namespace fldsim::linalg {

typedef double Double2 __attribute__((vector_size(16)));

// A block row vector of 6 doubles as three pairs.
struct Acc6 {
  Double2 v[3];
  static Acc6 load(const double* p) {
    Acc6 a;
    for (int k = 0; k < 3; ++k) __builtin_memcpy(&a.v[k], p + 2 * k, sizeof(Double2));
    return a;
  }
  static Acc6 zero() { return Acc6{{Double2{0.0, 0.0}, Double2{0.0, 0.0}, Double2{0.0, 0.0}}}; }
  void store(double* p) const {
    for (int k = 0; k < 3; ++k) __builtin_memcpy(p + 2 * k, &v[k], sizeof(Double2));
  }
  Acc6& operator+=(const Acc6& o) {
    for (int k = 0; k < 3; ++k) v[k] += o.v[k];
    return *this;
  }
  Acc6& operator-=(const Acc6& o) {
    for (int k = 0; k < 3; ++k) v[k] -= o.v[k];
    return *this;
  }
};

// Software prefetch of the blocks a loop will read a few rows ahead, where the hardware cannot
// guess them: IC(0)'s factorisation reads R's blocks in the factor's row order (a gather over R's
// storage) and the multi-threaded passes read rows in level order. At N = 64000 (about 140 MB of
// matrix and factor, read from memory) asking kPrefetchAhead rows ahead cut the factorisation's
// share of a step by 8 % (bench/README.md, "Sweep direction and prefetching"). A streaming loop
// gains nothing from it (the hardware follows a single stream), nor does a matrix that sits in the
// caches (N = 1000: two threads were 3 % slower with it), hence only from kPrefetchFromRows block
// rows on. Only a hint: no result changes.
constexpr std::int64_t kPrefetchAhead = 4;
constexpr std::int64_t kPrefetchFromRows = 4096;

// How many rows ahead a pass over `rows` block rows asks for its blocks (0: not at all).
inline std::int64_t prefetch_distance(std::int64_t rows) {
  return rows >= kPrefetchFromRows ? kPrefetchAhead : 0;
}

template <class Block>
inline void prefetch_block(const Block& b) {
  const char* p = reinterpret_cast<const char*>(&b);
  for (std::size_t o = 0; o < sizeof(Block); o += 64) __builtin_prefetch(p + o);
}

// y (6 doubles in memory) +=/-= t.
template <int Sign>
inline void add_to_memory(double* y, const Acc6& t) {
  Acc6 acc = Acc6::load(y);
  if constexpr (Sign > 0)
    acc += t;
  else
    acc -= t;
  acc.store(y);
}

// Column c, rows 2k and 2k+1 of a column-major 6x6 block of doubles or floats, as doubles.
template <class Scalar>
inline Double2 column_pair(const Scalar* A, int c, int k) {
  return Double2{double(A[6 * c + 2 * k]), double(A[6 * c + 2 * k + 1])};
}

// acc += s A x, s = +1 or -1: the columns of A in order, each scaled by x_c and added (or
// subtracted) to the accumulator.
template <int Sign, class Scalar>
inline void accumulate_product(Acc6& acc, const Scalar* A, const double* x) {
  for (int c = 0; c < 6; ++c) {
    const Double2 b = {x[c], x[c]};
    for (int k = 0; k < 3; ++k) {
      if constexpr (Sign > 0)
        acc.v[k] += column_pair(A, c, k) * b;
      else
        acc.v[k] -= column_pair(A, c, k) * b;
    }
  }
}

// t = A^T x: for each column c, (A_0:2,c x_0:2 + A_2:4,c x_2:4) + A_4:6,c x_4:6 in two lanes,
// then the lanes added.
template <class Scalar>
inline Acc6 transposed_product(const Scalar* A, const Acc6& x) {
  Double2 lanes[6];
  for (int c = 0; c < 6; ++c)
    lanes[c] =
        (column_pair(A, c, 0) * x.v[0] + column_pair(A, c, 1) * x.v[1]) + column_pair(A, c, 2) * x.v[2];
  Acc6 t;
  for (int k = 0; k < 3; ++k) {
    const Double2 lo = {lanes[2 * k][0], lanes[2 * k + 1][0]};
    const Double2 hi = {lanes[2 * k][1], lanes[2 * k + 1][1]};
    t.v[k] = lo + hi;
  }
  return t;
}

// C -= A^T B for 6x6 column-major blocks of doubles: column by column, each A^T B_c as above.
inline void subtract_transposed_product(double* C, const double* A, const double* B) {
  for (int c = 0; c < 6; ++c) add_to_memory<-1>(C + 6 * c, transposed_product(A, Acc6::load(B + 6 * c)));
}

// Inverse of a lower-triangular 6x6 block by forward substitution (Eigen's triangular solve with a
// matrix right-hand side takes its general blocked path at this size, several times slower).
inline Eigen::Matrix<double, 6, 6> lower_inverse(const Eigen::Matrix<double, 6, 6>& L) {
  Eigen::Matrix<double, 6, 6> X = Eigen::Matrix<double, 6, 6>::Zero();
  for (int c = 0; c < 6; ++c) {
    X(c, c) = 1.0 / L(c, c);
    for (int r = c + 1; r < 6; ++r) {
      double s = 0.0;
      for (int k = c; k < r; ++k) s += L(r, k) * X(k, c);
      X(r, c) = -s / L(r, r);
    }
  }
  return X;
}

}  // namespace fldsim::linalg
