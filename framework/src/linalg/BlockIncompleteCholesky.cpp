#include <Eigen/Cholesky>

#include "fldsim/block_sparse.hpp"

namespace fldsim {
namespace {
// Inverse of a lower-triangular 6x6 block by forward substitution (Eigen's triangular solve with a
// matrix right-hand side takes its general blocked path at this size, several times slower).
Mat6 lower_inverse(const Mat6& L) {
  Mat6 X = Mat6::Zero();
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
}  // namespace

bool BlockIncompleteCholesky::factorize(const BlockSparseMatrix& A) {
  const std::size_t n = A.blocks();
  row_start_ = A.row_start();
  col_ = A.col();
  upper_.resize(col_.size());
  inv_lower_.resize(n);
  // Start from A: inv_lower_ holds the running pivot blocks D_i, upper_ the running W_ij.
  for (std::size_t k = 0; k < col_.size(); ++k) upper_[k] = A.upper(std::int64_t(k));
  for (std::size_t i = 0; i < n; ++i) inv_lower_[i] = A.diagonal(i);
  for (std::size_t i = 0; i < n; ++i) {
    // D_i = L L^T, U_ii = L^T; row i of U: U_ij = L^-1 W_ij (from U_ii^T U_ij = W_ij).
    const Eigen::LLT<Mat6> llt(inv_lower_[i]);
    if (llt.info() != Eigen::Success) return false;
    inv_lower_[i] = lower_inverse(llt.matrixL());
    const std::int64_t first = row_start_[i], last = row_start_[i + 1];
    for (std::int64_t a = first; a < last; ++a) upper_[a] = (inv_lower_[i] * upper_[a]).eval();
    // Schur complement of block i, kept only on the pattern: D_j -= U_ij^T U_ij,
    // W_jl -= U_ij^T U_il for j < l both in row i.
    for (std::int64_t a = first; a < last; ++a) {
      const std::uint32_t j = col_[a];
      inv_lower_[j].noalias() -= upper_[a].transpose() * upper_[a];
      for (std::int64_t b = a + 1; b < last; ++b) {
        const std::int64_t jl = A.find(j, col_[b]);
        if (jl >= 0) upper_[jl].noalias() -= upper_[a].transpose() * upper_[b];
      }
    }
  }
  return true;
}

void BlockIncompleteCholesky::apply(const double* r, double* z) const {
  const std::size_t n = inv_lower_.size();
  std::copy(r, r + 6 * n, z);
  // U^T y = r, forward, scattering each solved block into the rows below.
  for (std::size_t i = 0; i < n; ++i) {
    const Vec6 y = inv_lower_[i] * Eigen::Map<const Vec6>(z + 6 * i);
    Eigen::Map<Vec6>(z + 6 * i) = y;
    for (std::int64_t a = row_start_[i]; a < row_start_[i + 1]; ++a)
      Eigen::Map<Vec6>(z + 6 * std::size_t(col_[a])).noalias() -= upper_[a].transpose() * y;
  }
  // U z = y, backward.
  for (std::size_t i = n; i-- > 0;) {
    Vec6 acc = Eigen::Map<const Vec6>(z + 6 * i);
    for (std::int64_t a = row_start_[i]; a < row_start_[i + 1]; ++a)
      acc.noalias() -= upper_[a] * Eigen::Map<const Vec6>(z + 6 * std::size_t(col_[a]));
    Eigen::Map<Vec6>(z + 6 * i) = inv_lower_[i].transpose() * acc;
  }
}

}  // namespace fldsim
