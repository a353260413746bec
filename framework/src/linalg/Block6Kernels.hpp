// The 6x6 block products of the CG solve, of IC(0)'s factorisation and of D-ILU, written out for the
// compiler's two-wide double vectors (GCC/Clang vector extensions; SSE2 on x86-64, the only
// target measured and tested: on a target with FMA, -ffp-contract would need to be off here for the
// thread-count invariance below to be guaranteed), and a four-wide set for CPUs with AVX2 (below;
// `target("avx2")` does not enable FMA, so nothing is contracted) that gives the same bits.
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

#include "fldsim/api.hpp"

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

// y (6 doubles in memory) +=/-= t, for either kernel set's accumulator (Acc6, Acc6w below).
template <int Sign, class Acc>
__attribute__((always_inline)) inline void add_to_memory(double* y, const Acc& t) {
  Acc acc = Acc::load(y);
  if constexpr (Sign > 0)
    acc += t;
  else
    acc -= t;
  acc.store(y);
}

// Column c, rows 2k and 2k+1 of a column-major 6x6 block.
inline Double2 column_pair(const double* A, int c, int k) {
  return Double2{A[6 * c + 2 * k], A[6 * c + 2 * k + 1]};
}

// acc += s A x, s = +1 or -1: A x summed as ((c0 + c1) + (c2 + c3)) + (c4 + c5), c_k = A_:k x_k,
// then added to (or subtracted from) the accumulator. The tree, not a running sum over the columns:
// a triangular sweep is a chain of rows, each waiting for the last, and a running sum made that chain
// six dependent additions per block long; with the tree it is one.
template <int Sign>
inline void accumulate_product(Acc6& acc, const double* A, const double* x) {
  for (int k = 0; k < 3; ++k) {
    Double2 c[6];
    for (int j = 0; j < 6; ++j) c[j] = column_pair(A, j, k) * Double2{x[j], x[j]};
    const Double2 t = ((c[0] + c[1]) + (c[2] + c[3])) + (c[4] + c[5]);
    if constexpr (Sign > 0)
      acc.v[k] += t;
    else
      acc.v[k] -= t;
  }
}

// t = A^T x: for each column c, (A_0:2,c x_0:2 + A_2:4,c x_2:4) + A_4:6,c x_4:6 in two lanes,
// then the lanes added.
inline Acc6 transposed_product(const double* A, const Acc6& x) {
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

// ---- Four-wide kernels (AVX2) ----
// The same products with rows 0-3 of a block in one four-double vector and rows 4-5 in a pair.
// Every element sees the operations of the two-wide kernels above, in the same order (products,
// then the sums in the order written there; no fused multiply-add), so a result is bit for bit the
// same whichever set computed it. A CG product takes 0.65-0.77x the time (BM_BlockSparseMatVec;
// bench/README.md, "Four-wide kernels"). Only for code compiled for AVX2: the loops that use
// them are functions marked FLDSIM_AVX2, called when wide_kernels() is true. `always_inline`: no
// out-of-line copy is ever emitted, so none can be taken by code compiled for plain x86-64.
// GCC warns that a 32-byte vector is passed differently without AVX; these are always inlined, so
// none is passed at all (the warning would come at each template's instantiation, hence not pushed).
#pragma GCC diagnostic ignored "-Wpsabi"

#if defined(__x86_64__) || defined(__i386__)
#define FLDSIM_AVX2 __attribute__((target("avx2")))
#define FLDSIM_HAS_AVX2() (__builtin_cpu_supports("avx2") != 0)
#else  // elsewhere the wide loops are plain code that is never called
#define FLDSIM_AVX2
#define FLDSIM_HAS_AVX2() false
#endif
#define FLDSIM_KERNEL __attribute__((always_inline)) inline

typedef double Double4 __attribute__((vector_size(32)));

struct Acc6w {
  Double4 lo;
  Double2 hi;
  FLDSIM_KERNEL static Acc6w load(const double* p) {
    Acc6w a;
    __builtin_memcpy(&a.lo, p, sizeof(Double4));
    __builtin_memcpy(&a.hi, p + 4, sizeof(Double2));
    return a;
  }
  FLDSIM_KERNEL static Acc6w zero() { return Acc6w{Double4{0.0, 0.0, 0.0, 0.0}, Double2{0.0, 0.0}}; }
  FLDSIM_KERNEL void store(double* p) const {
    __builtin_memcpy(p, &lo, sizeof(Double4));
    __builtin_memcpy(p + 4, &hi, sizeof(Double2));
  }
  FLDSIM_KERNEL Acc6w& operator+=(const Acc6w& o) {
    lo += o.lo;
    hi += o.hi;
    return *this;
  }
  FLDSIM_KERNEL Acc6w& operator-=(const Acc6w& o) {
    lo -= o.lo;
    hi -= o.hi;
    return *this;
  }
};

// Rows 0-3 and rows 4-5 of column c of a column-major 6x6 block, as doubles.
FLDSIM_KERNEL Double4 column_top(const double* A, int c) {
  Double4 v;
  __builtin_memcpy(&v, A + 6 * c, sizeof(Double4));
  return v;
}
FLDSIM_KERNEL Double2 column_bottom(const double* A, int c) {
  return Double2{A[6 * c + 4], A[6 * c + 5]};
}

template <int Sign>
FLDSIM_KERNEL void accumulate_product(Acc6w& acc, const double* A, const double* x) {
  Double4 top[6];
  Double2 bottom[6];
  for (int j = 0; j < 6; ++j) {
    top[j] = column_top(A, j) * Double4{x[j], x[j], x[j], x[j]};
    bottom[j] = column_bottom(A, j) * Double2{x[j], x[j]};
  }
  const Double4 t = ((top[0] + top[1]) + (top[2] + top[3])) + (top[4] + top[5]);
  const Double2 b = ((bottom[0] + bottom[1]) + (bottom[2] + bottom[3])) + (bottom[4] + bottom[5]);
  if constexpr (Sign > 0) {
    acc.lo += t;
    acc.hi += b;
  } else {
    acc.lo -= t;
    acc.hi -= b;
  }
}

// t = A^T x with the two-wide kernel's sums: t_c = ((A_0c x_0 + A_2c x_2) + A_4c x_4)
// + ((A_1c x_1 + A_3c x_3) + A_5c x_5).
FLDSIM_KERNEL Acc6w transposed_product(const double* A, const Acc6w& x) {
  double t[6];
  for (int c = 0; c < 6; ++c) {
    const Double4 top = column_top(A, c) * x.lo;
    const Double2 lanes = (Double2{top[0], top[1]} + Double2{top[2], top[3]}) + column_bottom(A, c) * x.hi;
    t[c] = lanes[0] + lanes[1];
  }
  return Acc6w::load(t);
}

// ---- Single-precision kernels for IC(0)'s sweeps ----
// The preconditioner only has to be a fixed symmetric positive definite operator close to R^-1: CG's
// accuracy is set by its double-precision residual. IC(0)'s factor is already stored in single
// precision; these kernels also do the sweeps' arithmetic in it, a block row vector of 6 floats in
// one eight-float vector (lanes 6-7 are don't-care), so a block product is six multiplies and five
// adds of whole vectors with no conversions (the double kernels above convert every column and
// take two vectors per column). Lane-wise IEEE operations round the same at any vector width, so
// these give the same bits compiled for AVX2 (one 32-byte register) or plain x86-64 (two 16-byte
// registers): the caller compiles the same loop both ways (FLDSIM_AVX2) and results do not depend
// on the CPU.
//
// A block is read as columns of eight floats from A + 6 c, two past the column: the storage must
// hold two readable, finite floats after its last block (a zero pad block). Block row vectors in
// memory are read and written as exactly six floats (no over-read: a multi-threaded sweep's
// neighbouring rows belong to other threads).
typedef float Float8 __attribute__((vector_size(32)));
typedef float Float4 __attribute__((vector_size(16)));
typedef float Float2 __attribute__((vector_size(8)));

struct Vec6f {
  Float8 v;
  FLDSIM_KERNEL static Vec6f load(const float* p) {
    Float4 lo;
    Float2 hi;
    __builtin_memcpy(&lo, p, sizeof(Float4));
    __builtin_memcpy(&hi, p + 4, sizeof(Float2));
    const Float4 hi4 = __builtin_shufflevector(hi, hi, 0, 1, 0, 1);
    return Vec6f{__builtin_shufflevector(lo, hi4, 0, 1, 2, 3, 4, 5, 6, 7)};
  }
  FLDSIM_KERNEL void store(float* p) const {
    const Float4 lo = __builtin_shufflevector(v, v, 0, 1, 2, 3);
    const Float2 hi = __builtin_shufflevector(v, v, 4, 5);
    __builtin_memcpy(p, &lo, sizeof(Float4));
    __builtin_memcpy(p + 4, &hi, sizeof(Float2));
  }
  FLDSIM_KERNEL static Vec6f zero() { return Vec6f{Float8{}}; }
  FLDSIM_KERNEL Vec6f& operator+=(const Vec6f& o) {
    v += o.v;
    return *this;
  }
  FLDSIM_KERNEL Vec6f& operator-=(const Vec6f& o) {
    v -= o.v;
    return *this;
  }
};

// Column c of a column-major 6x6 float block in lanes 0-5 (lanes 6-7: the next two floats).
FLDSIM_KERNEL Float8 block_column(const float* A, int c) {
  Float8 v;
  __builtin_memcpy(&v, A + 6 * c, sizeof(Float8));
  return v;
}

// acc +=/-= A x (x: 6 floats in memory), A x summed as ((c0 + c1) + (c2 + c3)) + (c4 + c5).
template <int Sign>
FLDSIM_KERNEL void accumulate_product(Vec6f& acc, const float* A, const float* x) {
  Float8 c[6];
  for (int j = 0; j < 6; ++j) c[j] = block_column(A, j) * x[j];
  const Float8 t = ((c[0] + c[1]) + (c[2] + c[3])) + (c[4] + c[5]);
  if constexpr (Sign > 0)
    acc.v += t;
  else
    acc.v -= t;
}

// Pairwise sums within each 128-bit half, as x86's haddps: [a0+a1, a2+a3, b0+b1, b2+b3 | a4+a5,
// a6+a7, b4+b5, b6+b7].
FLDSIM_KERNEL Float8 pair_sums(Float8 a, Float8 b) {
  const Float8 even = __builtin_shufflevector(a, b, 0, 2, 8, 10, 4, 6, 12, 14);
  const Float8 odd = __builtin_shufflevector(a, b, 1, 3, 9, 11, 5, 7, 13, 15);
  return even + odd;
}

// t = A^T y: t_c = (A_01,c y_01 + A_23,c y_23) + (A_45,c y_45 + 0), each pair summed first. y's
// lanes 6-7 are zeroed, so the two floats read past each column contribute exact zeros.
FLDSIM_KERNEL Vec6f transposed_product(const float* A, const Vec6f& y) {
  const Float8 zero = {};
  const Float8 y6 = __builtin_shufflevector(y.v, zero, 0, 1, 2, 3, 4, 5, 8, 8);
  Float8 p[6];
  for (int c = 0; c < 6; ++c) p[c] = block_column(A, c) * y6;
  const Float8 g = pair_sums(pair_sums(p[0], p[1]), pair_sums(p[2], p[3]));  // columns 0-3
  const Float8 h = pair_sums(pair_sums(p[4], p[5]), zero);                   // columns 4-5
  const Float8 first = __builtin_shufflevector(g, h, 0, 1, 2, 3, 8, 9, 8, 9);
  const Float8 second = __builtin_shufflevector(g, h, 4, 5, 6, 7, 12, 13, 12, 13);
  return Vec6f{first + second};
}

// Whether the loops take the four-wide kernels: the CPU has AVX2, unless a test turned them off
// (set_wide_kernels(false) compares the two sets).
FLDSIM_VISIBLE bool wide_kernels();
FLDSIM_VISIBLE void set_wide_kernels(bool on);

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
