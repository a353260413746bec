// Block incomplete Cholesky IC(0) of a BlockSparseMatrix: the core's default CG preconditioner.
// Core-private (not part of the plugin API): BlockPCG holds it behind a pointer.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "fldsim/block_sparse.hpp"
#include "linalg/Block6Kernels.hpp"
#include "linalg/CuthillMcKee.hpp"
#include "linalg/LevelSchedule.hpp"
#include "linalg/StiffClusterFill.hpp"
#include "linalg/StiffnessGradedOrder.hpp"

namespace fldsim {

// Block incomplete Cholesky IC(0): A ~ U^T U with U block upper triangular on A's own pattern
// (fill outside it is dropped) plus the fill inside clusters of bodies joined by stiff blocks
// (StiffClusterFill). Exact for an isolated pair of bodies, and with the cluster fill for an
// isolated cluster, so it removes the 1/gap squeeze coupling of near-contact pairs that block
// Jacobi leaves to the iterations. Applying it is two block triangular sweeps (about one
// matrix-vector product). Both the factorisation and the sweeps are row-oriented ("gather": row i
// reads only finished rows), scheduled by dependency levels computed once per pattern (and fill):
// rows of one level are independent and run in parallel, a
// thread waiting (per-row flags, no barrier between levels) only for the rows it reads, and
// every row is summed in the same fixed order whatever the thread count, so the result does not
// depend on it. The factor's rows are in reverse Cuthill-McKee order of A's graph, not the bodies'
// numbering (CuthillMcKee.hpp: a random numbering more than doubled the iterations at N = 27000). If a pivot
// block is not positive definite (IC(0) of a general SPD matrix can break down) factorize() returns false;
// BlockPCG then factorises A + alpha diag(A) (refactorize) and only then falls back to Eisenstat D-ILU
// (and, if that breaks down too, to block Jacobi).
class FLDSIM_VISIBLE BlockIncompleteCholesky {
 public:
  // The factor of A + shift diag(A): every diagonal element scaled by 1 + shift (Manteuffel's
  // shifted incomplete Cholesky, Math. Comp. 34, 473 (1980); 0: IC(0) of A itself). False if a
  // pivot block is not positive definite.
  bool factorize(const BlockSparseMatrix& A, double shift = 0.0);
  // The row order of the next factorisations (a change takes effect at the next factorize()).
  void set_row_order(RowOrder order);
  // After factorize(A) failed: the same rows (order, pattern, fill) again with another shift.
  bool refactorize(const BlockSparseMatrix& A, double shift);
  // z = (U^T U)^-1 r.
  void apply(const double* r, double* z) const;
  // The row order of the current factor and its age, for checkpoints: [age, old_of...] (empty
  // before the first factorisation). A run restored with it factorises as the uninterrupted run.
  std::vector<double> order_state() const;
  // Restores order_state() output for n rows before the next factorize(); false if malformed.
  bool restore_order_state(const std::vector<double>& state, std::size_t n);
  // Dependency levels of the forward and backward sweeps (each level is one parallel step).
  std::size_t forward_levels() {
    schedule_levels();
    return forward_.levels();
  }
  std::size_t backward_levels() {
    schedule_levels();
    return backward_.levels();
  }

 private:
  using Levels = linalg::Levels;
  void analyse(const BlockSparseMatrix& A, bool reorder);
  void schedule_levels();  // forward_ and backward_ for the current pattern, if not yet done
  bool factor_rows(const BlockSparseMatrix& A);  // every row with shift_, then the float copies
  bool factor_row(const BlockSparseMatrix& A, std::size_t i);
  void prefetch_factor_inputs(const BlockSparseMatrix& A, std::int64_t p) const;
  void forward_row(std::size_t i, const float* r, float* z) const;
  void backward_row(std::size_t i, float* z) const;
  // One row of the multi-threaded sweeps, out of line, compiled for plain x86-64 or for AVX2 (an
  // OpenMP region takes the instruction set of the function it is written in, so the row, not the
  // region, is what the two builds share; same bits).
  void forward_row_narrow(std::size_t i, const float* r, float* z) const;
  FLDSIM_AVX2 void forward_row_wide(std::size_t i, const float* r, float* z) const;
  void backward_row_narrow(std::size_t i, float* z) const;
  FLDSIM_AVX2 void backward_row_wide(std::size_t i, float* z) const;
  void pivot_times(std::size_t i, const linalg::Vec6f& acc, float* out) const;
  // apply() on one thread: the same loop compiled for plain x86-64 and for AVX2 (same bits).
  void sweeps_one_thread(const double* r, double* z) const;
  void sweeps_one_thread_narrow(const double* r, double* z) const;
  FLDSIM_AVX2 void sweeps_one_thread_wide(const double* r, double* z) const;

  std::uint64_t pattern_id_ = 0;
  // The factor's row order (reverse Cuthill-McKee of A's graph, CuthillMcKee.hpp): factor row p is
  // A's row old_of_[p], A's row i is factor row new_of_[i].
  // The order is computed anew every kReorderEvery factorisations (bodies drift apart slowly;
  // computing it at every new pattern cost as much as it saved on 1000 fused dumbbells), so its
  // age is part of the state a checkpoint carries (order_state()).
  std::vector<std::uint32_t> new_of_, old_of_;
  static constexpr int kReorderEvery = 100;
  int order_age_ = 0;  // factorisations with the current order, the last one included
  RowOrder row_order_ = RowOrder::Automatic;
  linalg::CuthillMcKeeScratch order_scratch_;
  linalg::StiffnessGradeScratch grade_scratch_;
  // A's upper pattern in that order, by rows and its transposed index (as in BlockSparseMatrix);
  // source_[a] = 2 b + t: the factor's block a is A's upper block b, transposed if t = 1.
  std::vector<std::int64_t> row_start_, col_start_, by_col_, source_;
  std::vector<std::uint32_t> col_, by_col_row_;
  // apply()'s r and z in the factor's order, in single precision (the sweeps' arithmetic).
  mutable std::vector<float> permuted_r_, permuted_z_;
  Levels forward_, backward_;
  bool levels_ready_ = false;  // forward_ and backward_ are the current pattern's
  // The factorisation runs in double: inv_lower_ = (U_ii^T)^-1 (lower triangular) and upper_ =
  // U_ij (i < j, laid out as A's upper blocks).
  std::vector<Mat6> inv_lower_, upper_;
  double shift_ = 0.0;  // of the factorisation under way
  // The sweeps read single-precision copies and compute in single precision (Block6Kernels.hpp,
  // "Single-precision kernels"): the preconditioner need only be a fixed operator close to R^-1,
  // and CG's accuracy is set by its double-precision residual. Each copy ends in a zero pad block
  // (the kernels read two floats past a block).
  using Mat6f = Eigen::Matrix<float, 6, 6>;
  std::vector<Mat6f> pivot_f_, upper_f_;
  std::vector<Mat6f> lower_f_;  // upper_f_ in the transposed index's order (by_col); threads > 1
  bool gathered_ = false;       // lower_f_ holds the current factor
  // Multi-threaded factorisation and sweeps: row i's flag is the epoch of the last pass
  // (factorisation, forward or backward sweep) that finished it.
  mutable linalg::RowFlags flags_;
  // analyse() scratch, kept so that a pattern change does not allocate.
  std::vector<std::uint32_t> level_scratch_;
  std::vector<std::int64_t> fill_scratch_;
  // The fill positions of the current factor and of the next factorisation (StiffClusterFill,
  // found at every factorisation from A's values).
  linalg::StiffClusterFill stiff_clusters_;
  std::vector<std::uint64_t> cluster_fill_, cluster_fill_next_;
};

}  // namespace fldsim
