// y = A x with A's blocks rounded to single precision, for CG on matrices that stream from memory.
// Core-private (BlockPCG holds it behind a pointer).
//
// Why: at N = 64000 the CG iteration reads R (288 bytes a block in double) and IC(0)'s factor
// (already single precision) from memory, and its time per 1000 bodies is 1.7-1.9x that at
// N = 1000 (bench/RESULTS.md, scaling). Half the bytes of R cut the product's traffic in half.
// In the caches (N = 1000) the conversions cost more than the bytes save (a single-precision R
// made the documented scene's step 8 % slower: bench/README.md), hence only from kFromBytes of
// blocks on. Accuracy: a product's rounding error is about 1e-7 of |A| |x|, which near contact
// (large lubrication entries whose terms cancel) reaches 1-3e-6 of |b| (N = 64000 spheres): above
// the default CG tolerance 1e-6. So BlockPCG checks the stopping rule |b - A x| <= tol |b| with A
// itself once the single-precision recurrence says converged, and where it is not met restarts
// from that residual with A's own products (at 1e-6: every solve, 1-2 iterations more).
//
// Rounding order is fixed per block row as in BlockSparseMatrix::multiply (lower blocks by
// increasing row, diagonal, upper blocks by increasing column), so one thread (a scatter that reads
// each block once) and several (a gather) give the same bits, as do the two kernel widths.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fldsim/block_sparse.hpp"

namespace fldsim::linalg {

class SinglePrecisionProduct {
 public:
  // From this size of A's stored blocks on (measured, one thread, spheres Pe 10, lattice starts,
  // bench/README.md "Single-precision products"): N = 8000 at phi 0.3, R 7.0 MB: +1..+3 % per step;
  // phi 0.5, 9.2 MB: -5 %; N = 27000 and 64000 (24-110 MB): -6 .. -12 %.
  static constexpr std::size_t kFromBytes = std::size_t(8) << 20;
  static bool pays(const BlockSparseMatrix& A) {
    return (A.blocks() + A.col().size()) * sizeof(Mat6) >= kFromBytes;
  }

  // Round A's current blocks (grow-only storage: no allocation once sized).
  void bind(const BlockSparseMatrix& A);
  void unbind() { bound_ = nullptr; }
  // Whether the copy is of this matrix, in its current pattern.
  bool bound_to(const BlockSparseMatrix& A) const { return bound_ == &A && pattern_ == A.pattern_id(); }
  // y = A x (A as rounded), x and y in double.
  void multiply(const double* x, double* y) const;

  // The kernels, by width (public for the tests' wide-against-narrow comparison).
  void multiply_narrow(const double* x, double* y) const;
  void multiply_wide(const double* x, double* y) const;

 private:
  using Mat6f = Eigen::Matrix<float, 6, 6>;
  const BlockSparseMatrix* bound_ = nullptr;
  std::uint64_t pattern_ = 0;
  // Diagonal and upper blocks, column-major, each array ending in a zero pad block: the kernels
  // read two floats past a block's last column.
  std::vector<Mat6f> diag_, upper_;
  mutable std::vector<float> x_, y_;
};

}  // namespace fldsim::linalg
