// Symmetric block-sparse matrix with 6x6 blocks (one block row per body), stored as the block
// diagonal plus the upper off-diagonal blocks in compressed rows. The pattern is rebuilt only
// when the pair list changes; values are overwritten in place at every assembly, so the time
// step allocates nothing.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "fldsim/api.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim {

class FLDSIM_VISIBLE BlockSparseMatrix {
 public:
  // Set the pattern: n block rows and the (i < j) block pairs that may be non-zero (duplicates
  // allowed). Values are zeroed.
  void set_pattern(std::size_t n, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& upper);
  // set_pattern() without zeroing: the values are undefined until written, for a model that writes
  // every block of the pattern at each assembly (at N = 64000 the zeroing was a pass over R's 56 MB
  // at nearly every assembly; API 5.7).
  void set_pattern_for_overwrite(std::size_t n,
                                 const std::vector<std::pair<std::uint32_t, std::uint32_t>>& upper);
  std::size_t blocks() const { return diag_.size(); }
  std::size_t size() const { return 6 * diag_.size(); }

  void set_zero();
  // *this = other, reusing this matrix's storage (grown with headroom, never shrunk), so that a
  // model keeping a copy of R at every assembly does not allocate in the time step (API 5.4).
  void copy_from(const BlockSparseMatrix& other);
  // Takes other's pattern (and pattern_id) but not its values, which are left as they were: for a
  // model that writes every block of the pattern at each assembly into one of two matrices it
  // alternates between (API 5.7).
  void copy_pattern_from(const BlockSparseMatrix& other);
  Mat6& diagonal(std::size_t i) { return diag_[i]; }
  const Mat6& diagonal(std::size_t i) const { return diag_[i]; }
  // Index of the stored upper block (i, j), i < j; -1 if not in the pattern.
  std::int64_t find(std::uint32_t i, std::uint32_t j) const;
  Mat6& upper(std::int64_t index) { return values_[index]; }
  const Mat6& upper(std::int64_t index) const { return values_[index]; }

  // y = A x (x, y of length 6n, not aliased). Parallel over block rows, deterministic.
  void multiply(const double* x, double* y) const;
  // Dense copy, for tests.
  Eigen::MatrixXd dense() const;
  // The compressed upper pattern: blocks row_start()[i] .. row_start()[i+1] of row i, columns col().
  const std::vector<std::int64_t>& row_start() const { return row_start_; }
  const std::vector<std::uint32_t>& col() const { return col_; }
  // The transposed index: for column j, col_start()[j] .. col_start()[j+1] - 1 list the stored
  // blocks (i, j) by increasing i: their index in the upper storage (by_col) and their row i.
  const std::vector<std::int64_t>& col_start() const { return col_start_; }
  const std::vector<std::int64_t>& by_col() const { return by_col_; }
  const std::vector<std::uint32_t>& by_col_row() const { return by_col_row_; }
  // Changes at every set_pattern() (unique across matrices): lets a preconditioner redo its
  // pattern analysis only when the pattern changed.
  std::uint64_t pattern_id() const { return pattern_id_; }

 private:
  std::vector<Mat6> diag_;
  // Compressed upper part: row_start_[i]..row_start_[i+1] index col_/values_.
  std::vector<std::int64_t> row_start_;
  std::vector<std::uint32_t> col_;
  std::vector<Mat6> values_;
  // Transposed view for the lower part: for each column j, the stored indices with col == j.
  std::vector<std::int64_t> col_start_;
  std::vector<std::int64_t> by_col_;
  std::vector<std::uint32_t> by_col_row_;
  std::uint64_t pattern_id_ = 0;
  // set_pattern() scratch, kept so that a pattern change does not allocate.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted_;
  std::vector<std::int64_t> fill_;
};

// EisenstatDilu: block D-ILU applied with Eisenstat's trick (framework/src/linalg/EisenstatDilu.hpp):
// CG on the transformed system, no product with A inside the iteration.
enum class Preconditioner { BlockJacobi, IncompleteCholesky, EisenstatDilu };
// The row order of the IC(0) factor (API 5.9): reverse Cuthill-McKee of A's block graph alone, or
// that order graded by stiffness, the rows with the smallest diagonal trace first (what IC(0) drops
// is then the fill of soft rows; framework/src/linalg/StiffnessGradedOrder.hpp), or (Automatic, the
// default) graded where A's blocks take less than 8 MB and the median diagonal trace is at least 5
// times the smallest (a sheared contact network), Cuthill-McKee otherwise: beyond the caches the
// graded rows' scattered memory costs more than their fewer iterations save, and near equilibrium
// grading costs iterations.
enum class RowOrder { CuthillMcKee, StiffnessGraded, Automatic };

// Preconditioned conjugate gradients for A x = b with A symmetric positive definite. Work vectors
// are kept between calls; x holds the warm start on entry. Converged when |b - A x| <= tol |b|.
// The preconditioners (block Jacobi, block incomplete Cholesky IC(0)) and the work vectors live
// in the core behind a pointer (framework/src/linalg), so tuning them changes no type that a
// plugin compiles against (API 4.0; before, IC(0)'s members were in this header).
class FLDSIM_VISIBLE BlockPCG {
 public:
  struct Result {
    int iterations = 0;
    double relative_residual = 0.0;
    bool converged = false;
  };
  explicit BlockPCG(Preconditioner kind = Preconditioner::IncompleteCholesky);
  ~BlockPCG();
  BlockPCG(BlockPCG&&) noexcept;
  BlockPCG& operator=(BlockPCG&&) noexcept;
  BlockPCG(const BlockPCG&) = delete;
  BlockPCG& operator=(const BlockPCG&) = delete;
  // Factor the preconditioner (call after each assembly).
  void prepare(const BlockSparseMatrix& A);
  // A's values were (re)assembled (call after each assembly, also when the factor is kept). Where A
  // streams from memory (at least 8 MB of blocks) the solver then keeps a single-precision copy for
  // the CG products; the stopping rule stays |b - A x| <= tol |b| with A itself (API 5.5; without
  // this call the products are A's own).
  void bind(const BlockSparseMatrix& A);
  Result solve(const BlockSparseMatrix& A, const double* b, double* x, double tolerance, int max_iterations);
  // The preconditioner in use after prepare(): on breakdown IC(0) is retried on A + alpha diag(A)
  // for each alpha of set_shifts() in turn, then falls back to Eisenstat D-ILU, and either to block
  // Jacobi.
  Preconditioner active() const;
  // Where IC(0) breaks down (a pivot block not positive definite), factorise A + alpha diag(A) for
  // each alpha in turn (Manteuffel 1980) before falling back; empty: fall back at once. Default
  // kDefaultShifts (API 5.8).
  static constexpr std::array<double, 4> kDefaultShifts = {0.01, 0.04, 0.16, 0.64};
  void set_shifts(const std::vector<double>& shifts);
  // IC(0)'s row order (API 5.9), default Automatic; the next factorisation uses it.
  void set_row_order(RowOrder order);
  // The alpha of the IC(0) factor in use: 0 for A's own (and for the other preconditioners).
  double shift() const;
  // What a checkpoint must carry besides the matrix the preconditioner was built from, so that
  // prepare() on that matrix after a restart builds the same preconditioner (IC(0): its row order
  // and that order's age; empty otherwise). Restore before prepare(); false if malformed (API 5.2).
  std::vector<double> preconditioner_state() const;
  bool restore_preconditioner_state(const std::vector<double>& state, std::size_t blocks);

 private:
  struct Workspace;
  std::unique_ptr<Workspace> w_;
};

}  // namespace fldsim
