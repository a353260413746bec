// Symmetric block-sparse matrix with 6x6 blocks (one block row per body), stored as the block
// diagonal plus the upper off-diagonal blocks in compressed rows. The pattern is rebuilt only
// when the pair list changes; values are overwritten in place at every assembly, so the time
// step allocates nothing.
#pragma once

#include <Eigen/Core>
#include <atomic>
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
  std::size_t blocks() const { return diag_.size(); }
  std::size_t size() const { return 6 * diag_.size(); }

  void set_zero();
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

// Block incomplete Cholesky IC(0): A ~ U^T U with U block upper triangular on A's own pattern
// (fill outside it is dropped). Exact for an isolated pair of bodies, so it removes the 1/gap
// squeeze coupling of near-contact pairs that block Jacobi leaves to the iterations. Applying it
// is two block triangular sweeps (about one matrix-vector product). Both the factorisation and the
// sweeps are row-oriented ("gather": row i reads only finished rows), scheduled by dependency
// levels computed once per pattern: rows of one level are independent and run in parallel, a
// thread waiting (per-row flags, no barrier between levels) only for the rows it reads, and
// every row is summed in the same fixed order whatever the thread count, so the result does not
// depend on it. If a pivot block is not positive definite (IC(0) of a general SPD matrix can break
// down) factorize() returns false and the caller falls back to block Jacobi.
class FLDSIM_VISIBLE BlockIncompleteCholesky {
 public:
  bool factorize(const BlockSparseMatrix& A);
  // z = (U^T U)^-1 r.
  void apply(const double* r, double* z) const;
  // Dependency levels of the forward and backward sweeps (each level is one parallel step).
  std::size_t forward_levels() const { return forward_.levels(); }
  std::size_t backward_levels() const { return backward_.levels(); }

 private:
  // Rows row[level_start[l]] .. row[level_start[l+1] - 1] form level l, ascending within it.
  struct Levels {
    std::vector<std::int64_t> level_start;
    std::vector<std::uint32_t> row;
    std::size_t levels() const { return level_start.empty() ? 0 : level_start.size() - 1; }
  };
  void analyse(const BlockSparseMatrix& A);
  bool factor_row(const BlockSparseMatrix& A, std::size_t i);
  void forward_row(std::size_t i, const double* r, double* z) const;
  void backward_row(std::size_t i, double* z) const;

  std::uint64_t pattern_id_ = 0;
  // A's upper pattern by rows and its transposed index (see BlockSparseMatrix).
  std::vector<std::int64_t> row_start_, col_start_, by_col_;
  std::vector<std::uint32_t> col_, by_col_row_;
  Levels forward_, backward_;
  // The factorisation runs in double: inv_lower_ = (U_ii^T)^-1 (lower triangular) and upper_ =
  // U_ij (i < j, laid out as A's upper blocks).
  std::vector<Mat6> inv_lower_, upper_;
  // The sweeps read single-precision copies: they are memory-bound, and a rounded factor is still
  // an exact U^T U of a slightly different U, so the preconditioner stays symmetric positive
  // definite and CG's accuracy (set by the double-precision residual) is unchanged.
  using Mat6f = Eigen::Matrix<float, 6, 6>;
  std::vector<Mat6f> pivot_f_, upper_f_;
  std::vector<Mat6f> lower_f_;  // upper_f_ in the transposed index's order (by_col); threads > 1
  bool gathered_ = false;       // lower_f_ holds the current factor
  // Multi-threaded factorisation and sweeps: done_[i] is the epoch of the last pass (factorisation,
  // forward or backward sweep) that finished row i; each pass has a larger epoch than the last.
  std::atomic<std::uint64_t>* done_flags(std::size_t n) const;
  mutable std::unique_ptr<std::atomic<std::uint64_t>[]> done_;
  mutable std::size_t done_size_ = 0;
  mutable std::uint64_t epoch_ = 0;
  // analyse() scratch, kept so that a pattern change does not allocate.
  std::vector<std::uint32_t> level_scratch_;
  std::vector<std::int64_t> fill_scratch_;
};

enum class Preconditioner { BlockJacobi, IncompleteCholesky };

// Preconditioned conjugate gradients for A x = b with A symmetric positive definite. Work vectors
// are kept between calls; x holds the warm start on entry. Converged when |b - A x| <= tol |b|.
class FLDSIM_VISIBLE BlockPCG {
 public:
  struct Result {
    int iterations = 0;
    double relative_residual = 0.0;
    bool converged = false;
  };
  explicit BlockPCG(Preconditioner kind = Preconditioner::IncompleteCholesky) : kind_(kind) {}
  // Factor the preconditioner (call after each assembly).
  void prepare(const BlockSparseMatrix& A);
  Result solve(const BlockSparseMatrix& A, const double* b, double* x, double tolerance, int max_iterations);
  // The preconditioner in use after prepare() (IC(0) falls back to block Jacobi on breakdown).
  Preconditioner active() const { return active_; }

 private:
  void precondition(const std::vector<double>& in, std::vector<double>& out) const;
  // Dot product as a sum of fixed-size chunks, added in chunk order: reproducible for any
  // thread count.
  double dot(const std::vector<double>& a, const std::vector<double>& b);
  Preconditioner kind_, active_ = Preconditioner::BlockJacobi;
  std::vector<Mat6> inv_diag_;
  BlockIncompleteCholesky ic_;
  std::vector<double> r_, z_, p_, q_, partial_;
};

}  // namespace fldsim
