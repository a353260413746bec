#include <omp.h>

#include <algorithm>
#include <atomic>

#include "fldsim/block_sparse.hpp"
#include "linalg/Block6Kernels.hpp"
#include "linalg/GrowOnly.hpp"
#include "linalg/TransposedIndex.hpp"

namespace fldsim {

namespace linalg {
namespace {
std::atomic<bool>& wide_switch() {
  static std::atomic<bool> on{FLDSIM_HAS_AVX2()};
  return on;
}
}  // namespace
bool wide_kernels() {
  return wide_switch().load(std::memory_order_relaxed);
}
void set_wide_kernels(bool on) {
  wide_switch().store(on && FLDSIM_HAS_AVX2());
}
}  // namespace linalg

void BlockSparseMatrix::set_pattern(std::size_t n,
                                    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& upper) {
  set_pattern_for_overwrite(n, upper);
  std::fill(diag_.begin(), diag_.end(), Mat6(Mat6::Zero()));
  std::fill(values_.begin(), values_.end(), Mat6(Mat6::Zero()));
}

void BlockSparseMatrix::set_pattern_for_overwrite(
    std::size_t n, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& upper) {
  using linalg::resize_grow_only;
  static std::atomic<std::uint64_t> patterns{0};
  pattern_id_ = ++patterns;
  resize_grow_only(diag_, n);
  // Sort and deduplicate the (i, j) pairs: rows in order, columns ascending within a row.
  linalg::copy_grow_only(sorted_, upper);
  // Callers usually pass the pairs in order already (a sorted neighbour list): then no sort. Node
  // pairs of dicolloids come grouped by row (body i) but with one ascending run per node of i:
  // then only each row is sorted (a few entries), not the whole list.
  if (!std::is_sorted(sorted_.begin(), sorted_.end())) {
    const bool grouped = std::is_sorted(sorted_.begin(), sorted_.end(),
                                        [](const auto& u, const auto& v) { return u.first < v.first; });
    if (grouped) {
      for (auto row = sorted_.begin(); row != sorted_.end();) {
        auto end = std::find_if(row, sorted_.end(), [&](const auto& p) { return p.first != row->first; });
        if (!std::is_sorted(row, end)) std::sort(row, end);
        row = end;
      }
    } else {
      std::sort(sorted_.begin(), sorted_.end());
    }
  }
  sorted_.erase(std::unique(sorted_.begin(), sorted_.end()), sorted_.end());
  const std::size_t nnz = sorted_.size();

  row_start_.assign(n + 1, 0);
  resize_grow_only(col_, nnz);
  for (const auto& [i, j] : sorted_) ++row_start_[i + 1];
  for (std::size_t i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  for (std::size_t k = 0; k < nnz; ++k) col_[k] = sorted_[k].second;
  resize_grow_only(values_, nnz);

  // Transposed index: for column j, the stored blocks (i, j) in increasing i, so the lower part of a
  // row is summed in a fixed order.
  linalg::transposed_index(n, row_start_, col_, col_start_, by_col_, by_col_row_, fill_);
}

void BlockSparseMatrix::copy_from(const BlockSparseMatrix& other) {
  if (this == &other) return;
  linalg::copy_grow_only(diag_, other.diag_);
  linalg::copy_grow_only(row_start_, other.row_start_);
  linalg::copy_grow_only(col_, other.col_);
  linalg::copy_grow_only(values_, other.values_);
  linalg::copy_grow_only(col_start_, other.col_start_);
  linalg::copy_grow_only(by_col_, other.by_col_);
  linalg::copy_grow_only(by_col_row_, other.by_col_row_);
  pattern_id_ = other.pattern_id_;
}

void BlockSparseMatrix::copy_pattern_from(const BlockSparseMatrix& other) {
  if (this == &other) return;
  linalg::resize_grow_only(diag_, other.diag_.size());
  linalg::copy_grow_only(row_start_, other.row_start_);
  linalg::copy_grow_only(col_, other.col_);
  linalg::resize_grow_only(values_, other.values_.size());
  linalg::copy_grow_only(col_start_, other.col_start_);
  linalg::copy_grow_only(by_col_, other.by_col_);
  linalg::copy_grow_only(by_col_row_, other.by_col_row_);
  pattern_id_ = other.pattern_id_;
}

void BlockSparseMatrix::set_zero() {
  for (auto& d : diag_) d.setZero();
  for (auto& v : values_) v.setZero();
}

std::int64_t BlockSparseMatrix::find(std::uint32_t i, std::uint32_t j) const {
  if (i >= diag_.size()) return -1;
  const auto first = col_.begin() + row_start_[i];
  const auto last = col_.begin() + row_start_[i + 1];
  const auto it = std::lower_bound(first, last, j);
  if (it == last || *it != j) return -1;
  return std::int64_t(it - col_.begin());
}

namespace {

// One thread: each stored block is read once, y_i += A_ij x_j and y_j += A_ij^T x_i. Row j receives
// its lower terms by increasing i before its own diagonal and upper terms: the operations, in the
// order, of the gather below (which reads every block twice). Acc: the kernel set (Acc6, or Acc6w
// inside an FLDSIM_AVX2 function).
template <class Acc>
FLDSIM_KERNEL void multiply_scatter(const BlockSparseMatrix& A, const double* x, double* y) {
  const std::int64_t n = std::int64_t(A.blocks());
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  std::fill(y, y + 6 * n, 0.0);
  for (std::int64_t i = 0; i < n; ++i) {
    const Acc xi = Acc::load(x + 6 * i);
    Acc yi = Acc::load(y + 6 * i);
    linalg::accumulate_product<1>(yi, A.diagonal(std::size_t(i)).data(), x + 6 * i);
    for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const std::size_t j = col[k];
      linalg::accumulate_product<1>(yi, A.upper(k).data(), x + 6 * j);
      linalg::add_to_memory<1>(y + 6 * j, linalg::transposed_product(A.upper(k).data(), xi));
    }
    yi.store(y + 6 * i);
  }
}

// Row i of y = A x as a gather: lower part by increasing row index, diagonal, upper part by
// increasing column, so y does not depend on which thread owns the row.
template <class Acc>
FLDSIM_KERNEL void multiply_row(const BlockSparseMatrix& A, std::int64_t i, std::int64_t ahead,
                                const double* x, double* y) {
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const auto& col_start = A.col_start();
  const auto& by_col = A.by_col();
  const auto& by_col_row = A.by_col_row();
  if (const std::int64_t f = i + ahead; ahead > 0 && f < std::int64_t(A.blocks())) {
    linalg::prefetch_block(A.diagonal(std::size_t(f)));
    for (std::int64_t k = col_start[f]; k < col_start[f + 1]; ++k) linalg::prefetch_block(A.upper(by_col[k]));
    for (std::int64_t k = row_start[f]; k < row_start[f + 1]; ++k) linalg::prefetch_block(A.upper(k));
  }
  Acc acc = Acc::zero();
  for (std::int64_t k = col_start[i]; k < col_start[i + 1]; ++k)
    acc += linalg::transposed_product(A.upper(by_col[k]).data(), Acc::load(x + 6 * by_col_row[k]));
  linalg::accumulate_product<1>(acc, A.diagonal(std::size_t(i)).data(), x + 6 * i);
  for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k)
    linalg::accumulate_product<1>(acc, A.upper(k).data(), x + 6 * std::size_t(col[k]));
  acc.store(y + 6 * i);
}

// The parallel loop is written once per kernel set: an OpenMP region takes the instruction set of
// the function it is written in.
void multiply_gather(const BlockSparseMatrix& A, const double* x, double* y) {
  const std::int64_t n = std::int64_t(A.blocks()), ahead = linalg::prefetch_distance(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) multiply_row<linalg::Acc6>(A, i, ahead, x, y);
}

FLDSIM_AVX2 void multiply_gather_wide(const BlockSparseMatrix& A, const double* x, double* y) {
  const std::int64_t n = std::int64_t(A.blocks()), ahead = linalg::prefetch_distance(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) multiply_row<linalg::Acc6w>(A, i, ahead, x, y);
}

FLDSIM_AVX2 void multiply_scatter_wide(const BlockSparseMatrix& A, const double* x, double* y) {
  multiply_scatter<linalg::Acc6w>(A, x, y);
}

}  // namespace

void BlockSparseMatrix::multiply(const double* x, double* y) const {
  const bool wide = linalg::wide_kernels();
  if (omp_get_max_threads() == 1) {
    if (wide)
      multiply_scatter_wide(*this, x, y);
    else
      multiply_scatter<linalg::Acc6>(*this, x, y);
  } else if (wide) {
    multiply_gather_wide(*this, x, y);
  } else {
    multiply_gather(*this, x, y);
  }
}

Eigen::MatrixXd BlockSparseMatrix::dense() const {
  const std::size_t n = diag_.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (std::size_t i = 0; i < n; ++i) {
    A.block<6, 6>(6 * i, 6 * i) = diag_[i];
    for (std::int64_t k = row_start_[i]; k < row_start_[i + 1]; ++k) {
      const std::size_t j = col_[k];
      A.block<6, 6>(6 * i, 6 * j) += values_[k];
      A.block<6, 6>(6 * j, 6 * i) += values_[k].transpose();
    }
  }
  return A;
}

}  // namespace fldsim
