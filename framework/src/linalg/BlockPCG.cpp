#include <Eigen/Cholesky>
#include <cmath>

#include "fldsim/block_sparse.hpp"

namespace fldsim {
namespace {
// Length of a dot-product chunk (256 bodies): partial sums are per chunk, never per thread.
constexpr std::size_t kChunk = 6 * 256;
}  // namespace

void BlockPCG::prepare(const BlockSparseMatrix& A) {
  const std::size_t n = A.blocks();
  r_.resize(6 * n);
  z_.resize(6 * n);
  p_.resize(6 * n);
  q_.resize(6 * n);
  partial_.resize((6 * n + kChunk - 1) / kChunk);
  if (kind_ == Preconditioner::IncompleteCholesky && ic_.factorize(A)) {
    active_ = Preconditioner::IncompleteCholesky;
    return;
  }
  active_ = Preconditioner::BlockJacobi;
  inv_diag_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < std::int64_t(n); ++i) {
    // Diagonal blocks of an SPD matrix are SPD: invert through their Cholesky factor.
    Eigen::LLT<Mat6> llt(A.diagonal(std::size_t(i)));
    inv_diag_[i] = llt.solve(Mat6::Identity());
  }
}

double BlockPCG::dot(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t m = a.size();
  const std::int64_t chunks = std::int64_t(partial_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    double s = 0.0;
    for (std::size_t k = std::size_t(c) * kChunk, end = std::min(m, k + kChunk); k < end; ++k) s += a[k] * b[k];
    partial_[c] = s;
  }
  double s = 0.0;
  for (const double v : partial_) s += v;
  return s;
}

void BlockPCG::precondition(const std::vector<double>& in, std::vector<double>& out) const {
  if (active_ == Preconditioner::IncompleteCholesky) {
    ic_.apply(in.data(), out.data());
    return;
  }
  const std::int64_t n = std::int64_t(inv_diag_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    Eigen::Map<Vec6>(out.data() + 6 * i) = inv_diag_[i] * Eigen::Map<const Vec6>(in.data() + 6 * i);
}

BlockPCG::Result BlockPCG::solve(const BlockSparseMatrix& A, const double* b, double* x, double tolerance,
                                 int max_iterations) {
  const std::int64_t m = std::int64_t(6 * A.blocks());
  Result result;
  A.multiply(x, q_.data());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < m; ++k) {
    r_[k] = b[k] - q_[k];
    z_[k] = b[k];
  }
  const double bnorm = std::sqrt(dot(z_, z_));
  if (bnorm == 0.0) {
    std::fill(x, x + m, 0.0);
    result.converged = true;
    return result;
  }
  double rnorm = std::sqrt(dot(r_, r_));
  result.relative_residual = rnorm / bnorm;
  if (result.relative_residual <= tolerance) {
    result.converged = true;
    return result;
  }
  precondition(r_, z_);
  p_ = z_;
  double rz = dot(r_, z_);
  for (int it = 1; it <= max_iterations; ++it) {
    A.multiply(p_.data(), q_.data());
    const double alpha = rz / dot(p_, q_);
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < m; ++k) {
      x[k] += alpha * p_[k];
      r_[k] -= alpha * q_[k];
    }
    rnorm = std::sqrt(dot(r_, r_));
    result.iterations = it;
    result.relative_residual = rnorm / bnorm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    precondition(r_, z_);
    const double rz_new = dot(r_, z_);
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < m; ++k) p_[k] = z_[k] + beta * p_[k];
  }
  return result;
}

}  // namespace fldsim
