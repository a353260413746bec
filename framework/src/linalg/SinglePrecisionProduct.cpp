#include "linalg/SinglePrecisionProduct.hpp"

#include <omp.h>

#include <algorithm>

#include "fldsim/parallel_loop.hpp"
#include "linalg/Block6Kernels.hpp"
#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {
namespace {

using Mat6f = Eigen::Matrix<float, 6, 6>;

// One thread: each stored block read once, y_i += A_ij x_j and y_j += A_ij^T x_i; row j receives its
// lower terms by increasing i before its diagonal and upper terms, the order of gather_row below.
FLDSIM_KERNEL void scatter(const BlockSparseMatrix& A, const Mat6f* D, const Mat6f* U, const float* x,
                           float* y) {
  const std::int64_t n = std::int64_t(A.blocks());
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  std::fill(y, y + 6 * n, 0.0f);
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec6f xi = Vec6f::load(x + 6 * i);
    Vec6f yi = Vec6f::load(y + 6 * i);
    accumulate_product<1>(yi, D[i].data(), x + 6 * i);
    for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const std::size_t j = col[k];
      accumulate_product<1>(yi, U[k].data(), x + 6 * j);
      Vec6f yj = Vec6f::load(y + 6 * j);
      yj += transposed_product(U[k].data(), xi);
      yj.store(y + 6 * j);
    }
    yi.store(y + 6 * i);
  }
}

// Row i as a gather: lower blocks by increasing row, diagonal, upper blocks by increasing column.
FLDSIM_KERNEL void gather_row(const BlockSparseMatrix& A, const Mat6f* D, const Mat6f* U, std::int64_t i,
                              std::int64_t ahead, const float* x, float* y) {
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const auto& col_start = A.col_start();
  const auto& by_col = A.by_col();
  const auto& by_col_row = A.by_col_row();
  if (const std::int64_t f = i + ahead; ahead > 0 && f < std::int64_t(A.blocks())) {
    prefetch_block(D[f]);
    for (std::int64_t k = col_start[f]; k < col_start[f + 1]; ++k) prefetch_block(U[by_col[k]]);
    for (std::int64_t k = row_start[f]; k < row_start[f + 1]; ++k) prefetch_block(U[k]);
  }
  Vec6f acc = Vec6f::zero();
  for (std::int64_t k = col_start[i]; k < col_start[i + 1]; ++k)
    acc += transposed_product(U[by_col[k]].data(), Vec6f::load(x + 6 * by_col_row[k]));
  accumulate_product<1>(acc, D[i].data(), x + 6 * i);
  for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k)
    accumulate_product<1>(acc, U[k].data(), x + 6 * std::size_t(col[k]));
  acc.store(y + 6 * i);
}

// The whole product: x rounded in, the blocks' product in single precision, y widened out. Written
// once, inlined into a plain and an AVX2 function (an OpenMP region takes its function's
// instruction set).
FLDSIM_KERNEL void product(const BlockSparseMatrix& A, const Mat6f* D, const Mat6f* U, const double* x,
                           float* xf, float* yf, double* y) {
  const std::int64_t n = std::int64_t(A.blocks()), m = 6 * n;
  parallel_for(m, [&](std::int64_t k) { xf[k] = float(x[k]); });
  if (omp_get_max_threads() == 1) {
    scatter(A, D, U, xf, yf);
  } else {
    const std::int64_t ahead = prefetch_distance(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) gather_row(A, D, U, i, ahead, xf, yf);
  }
  parallel_for(m, [&](std::int64_t k) { y[k] = double(yf[k]); });
}

}  // namespace

void SinglePrecisionProduct::bind(const BlockSparseMatrix& A) {
  const std::size_t n = A.blocks(), nnz = A.col().size();
  resize_grow_only(diag_, n + 1);
  resize_grow_only(upper_, nnz + 1);
  parallel_for(std::int64_t(n), [&](std::int64_t i) { diag_[i] = A.diagonal(std::size_t(i)).cast<float>(); });
  parallel_for(std::int64_t(nnz), [&](std::int64_t k) { upper_[k] = A.upper(k).cast<float>(); });
  diag_[n].setZero();
  upper_[nnz].setZero();
  resize_grow_only(x_, 6 * n);
  resize_grow_only(y_, 6 * n);
  bound_ = &A;
  pattern_ = A.pattern_id();
}

void SinglePrecisionProduct::multiply_narrow(const double* x, double* y) const {
  product(*bound_, diag_.data(), upper_.data(), x, x_.data(), y_.data(), y);
}

FLDSIM_AVX2 void SinglePrecisionProduct::multiply_wide(const double* x, double* y) const {
  product(*bound_, diag_.data(), upper_.data(), x, x_.data(), y_.data(), y);
}

void SinglePrecisionProduct::multiply(const double* x, double* y) const {
  if (wide_kernels())
    multiply_wide(x, y);
  else
    multiply_narrow(x, y);
}

}  // namespace fldsim::linalg
