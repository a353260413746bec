// Block D-ILU preconditioner applied with Eisenstat's trick: the CG alternative to IC(0) whose
// iteration costs two block triangular sweeps over A's own upper blocks instead of a product (each
// block read twice) plus IC(0)'s two sweeps. Core-private (BlockPCG holds it behind a pointer).
//
// A = D + U + U^T (U: the stored upper blocks). D-ILU keeps A's off-diagonal blocks and changes only
// the pivots: M = (P + U^T) P^-1 (P + U) with P_i = D_i - sum_{k<i} A_ki^T P_k^-1 A_ki, so that
// diag(M) = diag(A); it is exact for pairs and chains of bodies (no fill there) and differs from IC(0)
// only on cycles of the pair graph. With L = P + U^T, A = L + L^T - K, K = 2P - D, so the
// preconditioned operator needs no product with A (Eisenstat, SIAM J. Sci. Stat. Comput. 2, 1 (1981)):
//   L^-1 A L^-T v = t + L^-1 (v - K t),   t = L^-T v.
// CG runs on L^-1 A L^-T with the preconditioner P (a block-diagonal product), x = x0 + L^-T x^.
// Any SPD block-diagonal P gives an SPD M, and the identity holds for any P as long as K and U are the
// solved matrix's: so P may come from an older matrix (ResistanceModel keeps it while R moves little,
// as it keeps IC(0)'s factor) provided bind() sets K = 2P - D from the matrix being solved.
//
// Threads: the two sweeps of operator_times() and backward() run by dependency levels of the solved
// matrix's pattern (as IC(0)'s sweeps), each row summed in the same order as the one-thread row loop,
// so results do not depend on the thread count; the factorisation and the once-per-solve forward()
// and lower_times() run in row order.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "fldsim/block_sparse.hpp"
#include "linalg/LevelSchedule.hpp"

namespace fldsim {

class EisenstatDilu {
 public:
  // P from A; false if a pivot is not positive definite (the caller falls back to block Jacobi).
  bool factorize(const BlockSparseMatrix& A);
  // K = 2P - D from A, the matrix the next calls solve with (same number of bodies as P), and the
  // sweeps' dependency levels when A's pattern is new.
  void bind(const BlockSparseMatrix& A);
  // out = (P + U)^-1 in  (= L^-T in).
  void backward(const BlockSparseMatrix& A, const double* in, double* out) const;
  // out = (P + U^T)^-1 in  (= L^-1 in); out may not alias in.
  void forward(const BlockSparseMatrix& A, const double* in, double* out) const;
  // q = L^-1 A L^-T p, t scratch (both of length 6n).
  void operator_times(const BlockSparseMatrix& A, const double* p, double* q, double* t) const;
  // out = (P + U^T) in  (= L in: the residual of A x = b from the transformed residual).
  void lower_times(const BlockSparseMatrix& A, const double* in, double* out) const;
  // out = P in.
  void pivot_times(const double* in, double* out) const;

 private:
  void backward_row(const BlockSparseMatrix& A, std::size_t i, const double* in, double* out) const;
  void backward_by_levels(const BlockSparseMatrix& A, const double* in, double* out,
                          std::atomic<std::uint64_t>* done, std::uint64_t epoch) const;
  void operator_times_by_levels(const BlockSparseMatrix& A, const double* p, double* q, double* t) const;

  std::vector<Mat6> pivot_, inverse_, k_;  // P_i, P_i^-1, K_i = 2 P_i - D_i
  // Levels of the bound pattern: forward (row i reads rows k < i with a block (k, i)) and backward.
  std::uint64_t pattern_id_ = 0;
  linalg::Levels forward_, backward_;
  std::vector<std::uint32_t> level_scratch_;
  std::vector<std::int64_t> fill_scratch_;
  mutable std::vector<double> s_;   // the forward sweep's solution, read by later rows (threads > 1)
  mutable linalg::RowFlags flags_;  // as in BlockIncompleteCholesky
};

}  // namespace fldsim
