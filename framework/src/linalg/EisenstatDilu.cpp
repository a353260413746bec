#include "linalg/EisenstatDilu.hpp"

#include <omp.h>

#include <Eigen/Cholesky>
#include <algorithm>

#include "linalg/Block6Kernels.hpp"
#include "linalg/GrowOnly.hpp"

namespace fldsim {
namespace {
using linalg::Acc6;

// out = B in for a 6x6 block B (the kernels' fixed rounding order).
inline Acc6 block_times(const Mat6& B, const double* in) {
  Acc6 y = Acc6::zero();
  linalg::accumulate_product<1>(y, B.data(), in);
  return y;
}
}  // namespace

bool EisenstatDilu::factorize(const BlockSparseMatrix& A) {
  const std::size_t n = A.blocks();
  pivot_.resize(n);
  inverse_.resize(n);
  k_.resize(n);
  const auto& col_start = A.col_start();
  const auto& by_col = A.by_col();
  const auto& by_col_row = A.by_col_row();
  // Left-looking, rows ascending: P_i needs P_k of the rows k < i that share a block with it.
  for (std::size_t i = 0; i < n; ++i) {
    Mat6 P = A.diagonal(i);
    for (std::int64_t c = col_start[i]; c < col_start[i + 1]; ++c) {
      // P -= A_ki^T P_k^-1 A_ki = (G^-1 A_ki)^T (G^-1 A_ki) with P_k = G G^T (inverse_ holds G^-1 of
      // row k until the end): the subtraction kernel of IC(0), symmetric by construction.
      const Mat6& Aki = A.upper(by_col[c]);
      const Mat6& Ginv = inverse_[by_col_row[c]];
      Mat6 W;
      for (int col = 0; col < 6; ++col) block_times(Ginv, Aki.data() + 6 * col).store(W.data() + 6 * col);
      linalg::subtract_transposed_product(P.data(), W.data(), W.data());
    }
    const Eigen::LLT<Mat6> llt(P);
    if (llt.info() != Eigen::Success) return false;
    pivot_[i] = P;
    inverse_[i] = linalg::lower_inverse(llt.matrixL());  // G^-1, turned into P^-1 below
  }
  for (std::size_t i = 0; i < n; ++i)
    inverse_[i] = (inverse_[i].transpose().lazyProduct(inverse_[i])).eval();  // P^-1 = G^-T G^-1
  return true;
}

void EisenstatDilu::bind(const BlockSparseMatrix& A) {
  const std::size_t n = pivot_.size();
  for (std::size_t i = 0; i < n; ++i) k_[i] = 2.0 * pivot_[i] - A.diagonal(i);
  if (A.pattern_id() == pattern_id_ && forward_.row.size() == n) return;
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const auto& col_start = A.col_start();
  const auto& by_col_row = A.by_col_row();
  linalg::schedule(
      n, false,
      [&](std::size_t i, auto&& depend) {
        for (std::int64_t c = col_start[i]; c < col_start[i + 1]; ++c) depend(by_col_row[std::size_t(c)]);
      },
      forward_, level_scratch_, fill_scratch_);
  linalg::schedule(
      n, true,
      [&](std::size_t i, auto&& depend) {
        for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a) depend(col[std::size_t(a)]);
      },
      backward_, level_scratch_, fill_scratch_);
  pattern_id_ = A.pattern_id();
}

// out_i = P_i^-1 (in_i - sum_{j > i} A_ij out_j), the row's blocks last to first: with the rows
// descending, one descending stream through A (as IC(0)'s backward_row).
void EisenstatDilu::backward_row(const BlockSparseMatrix& A, std::size_t i, const double* in,
                                 double* out) const {
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  Acc6 acc = Acc6::load(in + 6 * i);
  for (std::int64_t a = row_start[i + 1]; a-- > row_start[i];)
    linalg::accumulate_product<-1>(acc, A.upper(a).data(), out + 6 * std::size_t(col[std::size_t(a)]));
  double r[6];
  acc.store(r);
  block_times(inverse_[i], r).store(out + 6 * i);
}

void EisenstatDilu::backward(const BlockSparseMatrix& A, const double* in, double* out) const {
  const std::size_t n = pivot_.size();
  if (omp_get_max_threads() == 1) {
    for (std::size_t i = n; i-- > 0;) backward_row(A, i, in, out);
    return;
  }
  std::atomic<std::uint64_t>* done = flags_.rows(n);
  const std::uint64_t epoch = flags_.epochs(1);
#pragma omp parallel
  backward_by_levels(A, in, out, done, epoch);
}

// The backward sweep's rows by levels, each thread its static share of every level (an orphaned
// `omp for`: call inside a parallel region); a row waits for the rows j > i it reads to carry
// `epoch`, then publishes its own.
void EisenstatDilu::backward_by_levels(const BlockSparseMatrix& A, const double* in, double* out,
                                       std::atomic<std::uint64_t>* done, std::uint64_t epoch) const {
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const std::int64_t levels = std::int64_t(backward_.levels());
  for (std::int64_t l = 0; l < levels; ++l) {
#pragma omp for schedule(static) nowait
    for (std::int64_t r = backward_.level_start[l]; r < backward_.level_start[l + 1]; ++r) {
      const std::size_t i = backward_.row[std::size_t(r)];
      for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a)
        linalg::wait_until(done[col[std::size_t(a)]], epoch);
      backward_row(A, i, in, out);
      done[i].store(epoch, std::memory_order_release);
    }
  }
}

void EisenstatDilu::forward(const BlockSparseMatrix& A, const double* in, double* out) const {
  // By scattering each solved block into the rows below (U streamed in its own layout).
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const std::size_t n = pivot_.size();
  std::copy(in, in + 6 * n, out);
  for (std::size_t i = 0; i < n; ++i) {
    const Acc6 y = block_times(inverse_[i], out + 6 * i);
    y.store(out + 6 * i);
    for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a)
      linalg::add_to_memory<-1>(out + 6 * std::size_t(col[std::size_t(a)]),
                                linalg::transposed_product(A.upper(a).data(), y));
  }
}

void EisenstatDilu::operator_times(const BlockSparseMatrix& A, const double* p, double* q, double* t) const {
  if (omp_get_max_threads() > 1) return operator_times_by_levels(A, p, q, t);
  backward(A, p, t);
  // s = L^-1 (p - K t), scattered as in forward(); q_i = t_i + s_i once row i is solved.
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const std::size_t n = pivot_.size();
  std::fill(q, q + 6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    Acc6 w = Acc6::load(p + 6 * i);
    w -= block_times(k_[i], t + 6 * i);
    w += Acc6::load(q + 6 * i);
    double r[6];
    w.store(r);
    const Acc6 s = block_times(inverse_[i], r);
    for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a)
      linalg::add_to_memory<-1>(q + 6 * std::size_t(col[std::size_t(a)]),
                                linalg::transposed_product(A.upper(a).data(), s));
    Acc6 out = Acc6::load(t + 6 * i);
    out += s;
    out.store(q + 6 * i);
  }
}

void EisenstatDilu::lower_times(const BlockSparseMatrix& A, const double* in, double* out) const {
  const auto& row_start = A.row_start();
  const auto& col = A.col();
  const std::size_t n = pivot_.size();
  std::fill(out, out + 6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Acc6 xi = Acc6::load(in + 6 * i);
    linalg::add_to_memory<1>(out + 6 * i, block_times(pivot_[i], in + 6 * i));
    for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a)
      linalg::add_to_memory<1>(out + 6 * std::size_t(col[std::size_t(a)]),
                               linalg::transposed_product(A.upper(a).data(), xi));
  }
}

void EisenstatDilu::pivot_times(const double* in, double* out) const {
  for (std::size_t i = 0; i < pivot_.size(); ++i) block_times(pivot_[i], in + 6 * i).store(out + 6 * i);
}

// operator_times() on several threads: the backward sweep by levels, then the forward sweep by levels
// in gather form (row i reads the finished s_k of its rows k < i), in one parallel region without
// barriers (a row waits for its own t_i and for the rows it reads). Row i performs, in order, the
// operations the one-thread scatter loop applies to it: 0 - A_k1i^T s_k1 - A_k2i^T s_k2 ... (k
// ascending), then (p_i - K_i t_i) + that sum, so q is bitwise the same.
void EisenstatDilu::operator_times_by_levels(const BlockSparseMatrix& A, const double* p, double* q,
                                             double* t) const {
  const std::size_t n = pivot_.size();
  linalg::resize_grow_only(s_, 6 * n);
  std::atomic<std::uint64_t>* done = flags_.rows(n);
  const std::uint64_t bwd = flags_.epochs(2), fwd = bwd + 1;
  const auto& col_start = A.col_start();
  const auto& by_col = A.by_col();
  const auto& by_col_row = A.by_col_row();
  double* s = s_.data();
  const std::int64_t forward_levels = std::int64_t(forward_.levels());
#pragma omp parallel
  {
    backward_by_levels(A, p, t, done, bwd);
    for (std::int64_t l = 0; l < forward_levels; ++l) {
#pragma omp for schedule(static) nowait
      for (std::int64_t r = forward_.level_start[l]; r < forward_.level_start[l + 1]; ++r) {
        const std::size_t i = forward_.row[std::size_t(r)];
        linalg::wait_until(done[i], bwd);  // its own t_i
        Acc6 sum = Acc6::zero();
        for (std::int64_t c = col_start[i]; c < col_start[i + 1]; ++c) {
          const std::size_t k = by_col_row[std::size_t(c)];
          linalg::wait_until(done[k], fwd);
          sum -= linalg::transposed_product(A.upper(by_col[std::size_t(c)]).data(), Acc6::load(s + 6 * k));
        }
        Acc6 w = Acc6::load(p + 6 * i);
        w -= block_times(k_[i], t + 6 * i);
        w += sum;
        double in[6];
        w.store(in);
        const Acc6 si = block_times(inverse_[i], in);
        si.store(s + 6 * i);
        Acc6 out = Acc6::load(t + 6 * i);
        out += si;
        out.store(q + 6 * i);
        done[i].store(fwd, std::memory_order_release);
      }
    }
  }
}

}  // namespace fldsim
