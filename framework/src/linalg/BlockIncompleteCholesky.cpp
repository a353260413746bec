#include "linalg/BlockIncompleteCholesky.hpp"

#include <omp.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "fldsim/parallel_loop.hpp"
#include "linalg/Block6Kernels.hpp"
#include "linalg/CuthillMcKee.hpp"
#include "linalg/GrowOnly.hpp"
#include "linalg/LevelSchedule.hpp"
#include "linalg/SinglePrecisionProduct.hpp"
#include "linalg/TransposedIndex.hpp"

namespace fldsim {

void BlockIncompleteCholesky::analyse(const BlockSparseMatrix& A, bool reorder) {
  const std::size_t n = A.blocks();
  // The factor works in reverse Cuthill-McKee order (CuthillMcKee.hpp), graded by stiffness unless
  // set_row_order says otherwise (StiffnessGradedOrder.hpp): row p of the factor is row
  // old_of_[p] of A, and A's upper block a = (i, j) lands at (min, max) of (new_of_[i], new_of_[j]),
  // transposed when new_of_[i] > new_of_[j] (source_ = 2 a + 1 then, else 2 a).
  if (reorder) {
    linalg::reverse_cuthill_mckee(n, A.row_start(), A.col(), A.col_start(), A.by_col_row(), new_of_, old_of_,
                                  order_scratch_);
    // Automatic: graded where A sits in the caches (the threshold of the single-precision
    // products: A's blocks under 8 MB; beyond, the graded rows' scattered reads cost the
    // factorisation 20-25 % more than its 16-20 % fewer iterations save) and its traces are broad
    // (a contact network; near equilibrium grading costs iterations). bench/README.md, "IC(0) rows
    // graded by stiffness".
    const bool graded = row_order_ == RowOrder::StiffnessGraded ||
                        (row_order_ == RowOrder::Automatic && !linalg::SinglePrecisionProduct::pays(A) &&
                         linalg::stiffness_is_broad(A, grade_scratch_));
    if (graded) linalg::grade_by_stiffness(A, new_of_, old_of_, grade_scratch_);
    order_age_ = 0;
  }
  const auto& a_start = A.row_start();
  const auto& a_col = A.col();
  const std::size_t nnz = a_col.size() + cluster_fill_.size();
  linalg::fill_grow_only(row_start_, n + 1, std::int64_t(0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::int64_t a = a_start[i]; a < a_start[i + 1]; ++a)
      ++row_start_[std::min(new_of_[i], new_of_[a_col[std::size_t(a)]]) + 1];
  for (const std::uint64_t f : cluster_fill_)
    ++row_start_[std::min(new_of_[f >> 32], new_of_[f & 0xffffffffu]) + 1];
  for (std::size_t p = 0; p < n; ++p) row_start_[p + 1] += row_start_[p];
  linalg::copy_grow_only(fill_scratch_, row_start_.begin(), row_start_.end() - 1);
  linalg::resize_grow_only(col_, nnz);
  linalg::resize_grow_only(source_, nnz);
  for (std::size_t i = 0; i < n; ++i)
    for (std::int64_t a = a_start[i]; a < a_start[i + 1]; ++a) {
      const std::uint32_t p = new_of_[i], q = new_of_[a_col[std::size_t(a)]];
      const std::int64_t k = fill_scratch_[std::min(p, q)]++;
      col_[std::size_t(k)] = std::max(p, q);
      source_[std::size_t(k)] = 2 * a + (p > q ? 1 : 0);
    }
  for (const std::uint64_t f : cluster_fill_) {
    const std::uint32_t p = new_of_[f >> 32], q = new_of_[f & 0xffffffffu];
    const std::int64_t k = fill_scratch_[std::min(p, q)]++;
    col_[std::size_t(k)] = std::max(p, q);
    source_[std::size_t(k)] = -1;  // fill: starts at zero
  }
  // Columns ascending within each row (rows hold a few blocks: insertion sort).
  for (std::size_t p = 0; p < n; ++p)
    for (std::int64_t a = row_start_[p] + 1; a < row_start_[p + 1]; ++a)
      for (std::int64_t b = a; b > row_start_[p] && col_[std::size_t(b - 1)] > col_[std::size_t(b)]; --b) {
        std::swap(col_[std::size_t(b - 1)], col_[std::size_t(b)]);
        std::swap(source_[std::size_t(b - 1)], source_[std::size_t(b)]);
      }
  linalg::transposed_index(n, row_start_, col_, col_start_, by_col_, by_col_row_, fill_scratch_);
  linalg::resize_grow_only(upper_, nnz);
  inv_lower_.resize(n);
  linalg::resize_grow_only(permuted_r_, 6 * n);
  linalg::resize_grow_only(permuted_z_, 6 * n);
  // The dependency levels serve only the multi-threaded factorisation and sweeps (one thread runs
  // the rows in order): computed there, when first needed after a new pattern (at N = 1000 the
  // pattern changes at nearly every assembly, and the two schedules were half of analyse()).
  levels_ready_ = false;
  pattern_id_ = A.pattern_id();
}

void BlockIncompleteCholesky::schedule_levels() {
  if (levels_ready_) return;
  const std::size_t n = inv_lower_.size();
  // Forward (and factorisation): row i needs the rows k < i with a block (k, i).
  linalg::schedule(
      n, false,
      [&](std::size_t i, auto&& depend) {
        for (std::int64_t c = col_start_[i]; c < col_start_[i + 1]; ++c) depend(by_col_row_[c]);
      },
      forward_, level_scratch_, fill_scratch_);
  // Backward: row i needs the rows j > i of its own blocks (i, j).
  linalg::schedule(
      n, true,
      [&](std::size_t i, auto&& depend) {
        for (std::int64_t a = row_start_[i]; a < row_start_[i + 1]; ++a) depend(col_[a]);
      },
      backward_, level_scratch_, fill_scratch_);
  levels_ready_ = true;
}

// Row i of U (in the factor's order) from the finished rows k < i (left-looking IC(0) restricted to
// A's pattern):
// D_i = A_ii - sum_k U_ki^T U_ki,  W_ij = A_ij - sum_k U_ki^T U_kj  (k ascending, (i, j) stored),
// then D_i = L L^T, U_ii = L^T and U_ij = L^-1 W_ij.
bool BlockIncompleteCholesky::factor_row(const BlockSparseMatrix& A, std::size_t i) {
  Mat6 D = A.diagonal(old_of_[i]);
  if (shift_ != 0.0) D.diagonal() *= 1.0 + shift_;
  const std::int64_t first = row_start_[i], last = row_start_[i + 1];
  for (std::int64_t a = first; a < last; ++a) {
    if (source_[a] < 0) {
      upper_[a].setZero();
      continue;
    }
    const Mat6& Aij = A.upper(source_[a] >> 1);
    if (source_[a] & 1)
      upper_[a] = Aij.transpose();
    else
      upper_[a] = Aij;
  }
  for (std::int64_t c = col_start_[i]; c < col_start_[i + 1]; ++c) {
    const std::int64_t ki = by_col_[c];
    const std::int64_t k_end = row_start_[by_col_row_[c] + 1];
    const Mat6& Uki = upper_[ki];
    linalg::subtract_transposed_product(D.data(), Uki.data(), Uki.data());
    // Blocks (k, j) with j > i, merged against row i's sorted columns.
    std::int64_t b = ki + 1, p = first;
    while (b < k_end && p < last) {
      if (col_[b] < col_[p])
        ++b;
      else if (col_[p] < col_[b])
        ++p;
      else
        linalg::subtract_transposed_product(upper_[p++].data(), Uki.data(), upper_[b++].data());
    }
  }
  const Eigen::LLT<Mat6> llt(D);
  if (llt.info() != Eigen::Success) return false;
  inv_lower_[i] = linalg::lower_inverse(llt.matrixL());
  for (std::int64_t a = first; a < last; ++a) upper_[a] = (inv_lower_[i] * upper_[a]).eval();
  return true;
}

std::vector<double> BlockIncompleteCholesky::order_state() const {
  if (old_of_.empty()) return {};
  std::vector<double> out;
  out.reserve(old_of_.size() + 1);
  out.push_back(double(order_age_));
  for (const std::uint32_t i : old_of_) out.push_back(double(i));
  return out;
}

bool BlockIncompleteCholesky::restore_order_state(const std::vector<double>& state, std::size_t n) {
  // Any age >= 1 is accepted: a build with another kReorderEvery resumes (the order is then renewed
  // at the first factorisation whose age reaches its own period).
  if (state.size() != n + 1 || !(state[0] >= 1.0 && state[0] < 1e9) || state[0] != std::floor(state[0]))
    return false;
  std::vector<std::uint32_t> old_of(n), new_of(n, std::uint32_t(n));
  for (std::size_t p = 0; p < n; ++p) {
    const double i = state[p + 1];
    if (!(i >= 0.0 && i < double(n)) || i != std::floor(i) || new_of[std::size_t(i)] != n) return false;
    old_of[p] = std::uint32_t(i);
    new_of[std::size_t(i)] = std::uint32_t(p);
  }
  old_of_ = std::move(old_of);
  new_of_ = std::move(new_of);
  // The next factorisation is the restored factor's own: it keeps this order and counts again.
  order_age_ = int(state[0]) - 1;
  pattern_id_ = 0;
  return true;
}

bool BlockIncompleteCholesky::factorize(const BlockSparseMatrix& A, double shift) {
  const bool reorder = old_of_.size() != A.blocks() || order_age_ >= kReorderEvery;
  stiff_clusters_.find(A, cluster_fill_next_);
  const bool new_fill = cluster_fill_next_ != cluster_fill_;
  if (new_fill) cluster_fill_.swap(cluster_fill_next_);
  if (reorder || new_fill || pattern_id_ != A.pattern_id() || inv_lower_.size() != A.blocks())
    analyse(A, reorder);
  ++order_age_;
  shift_ = shift;
  return factor_rows(A);
}

void BlockIncompleteCholesky::set_row_order(RowOrder order) {
  if (order == row_order_) return;
  row_order_ = order;
  old_of_.clear();  // a new order at the next factorisation
}

bool BlockIncompleteCholesky::refactorize(const BlockSparseMatrix& A, double shift) {
  shift_ = shift;
  return factor_rows(A);
}

bool BlockIncompleteCholesky::factor_rows(const BlockSparseMatrix& A) {
  const std::int64_t n = std::int64_t(A.blocks());
  bool ok = true;
  if (omp_get_max_threads() == 1) {
    // Ascending rows satisfy every dependency and stream through memory.
    const std::int64_t ahead = linalg::prefetch_distance(n);
    for (std::int64_t i = 0; i < n && ok; ++i) {
      if (ahead > 0) prefetch_factor_inputs(A, i + ahead);
      ok = factor_row(A, std::size_t(i));
    }
  } else {
    // By levels without barriers, as in apply(): a row waits only for the rows it reads. A row
    // whose pivot fails is still published (its blocks are not used: factorize() returns false).
    schedule_levels();
    std::atomic<bool> good{true};
    std::atomic<std::uint64_t>* done = flags_.rows(std::size_t(n));
    const std::uint64_t epoch = flags_.epochs(1);
    const std::int64_t levels = std::int64_t(forward_.levels()), ahead = linalg::prefetch_distance(n);
#pragma omp parallel
    for (std::int64_t l = 0; l < levels; ++l) {
#pragma omp for schedule(static) nowait
      for (std::int64_t s = forward_.level_start[l]; s < forward_.level_start[l + 1]; ++s) {
        const std::size_t i = forward_.row[s];
        if (ahead > 0 && s + ahead < n) prefetch_factor_inputs(A, forward_.row[s + ahead]);
        for (std::int64_t c = col_start_[i]; c < col_start_[i + 1]; ++c)
          linalg::wait_until(done[by_col_row_[c]], epoch);
        if (good.load(std::memory_order_relaxed) && !factor_row(A, i))
          good.store(false, std::memory_order_relaxed);
        done[i].store(epoch, std::memory_order_release);
      }
    }
    ok = good.load();
  }
  gathered_ = false;
  if (!ok) return false;
  const bool gather = omp_get_max_threads() > 1;
  const std::int64_t blocks = std::int64_t(upper_.size());
  linalg::resize_grow_only(pivot_f_, std::size_t(n) + 1);
  linalg::resize_grow_only(upper_f_, std::size_t(blocks) + 1);
  pivot_f_[std::size_t(n)].setZero();
  upper_f_[std::size_t(blocks)].setZero();
  if (gather) {
    linalg::resize_grow_only(lower_f_, std::size_t(blocks) + 1);
    lower_f_[std::size_t(blocks)].setZero();
  }
  parallel_region([&] {
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) pivot_f_[i] = inv_lower_[i].cast<float>();
#pragma omp for schedule(static)
    for (std::int64_t a = 0; a < blocks; ++a) upper_f_[a] = upper_[a].cast<float>();
    // The blocks U_ki in the transposed index's order, so that the level-scheduled forward
    // sweep reads each row's blocks contiguously.
    if (gather) {
#pragma omp for schedule(static)
      for (std::int64_t c = 0; c < blocks; ++c) lower_f_[c] = upper_f_[by_col_[c]];
    }
  });
  gathered_ = gather;
  return true;
}

// The blocks of A that factor_row(p) reads first (A's diagonal and upper blocks of that row, which
// the factor's row order scatters over A's storage); p out of range: none.
void BlockIncompleteCholesky::prefetch_factor_inputs(const BlockSparseMatrix& A, std::int64_t p) const {
  if (p < 0 || p >= std::int64_t(old_of_.size())) return;
  linalg::prefetch_block(A.diagonal(old_of_[std::size_t(p)]));
  for (std::int64_t a = row_start_[p]; a < row_start_[p + 1]; ++a)
    if (source_[a] >= 0) linalg::prefetch_block(A.upper(source_[a] >> 1));
}

// U^T y = r: y_i = (U_ii^T)^-1 (r_i - sum_{k < i} U_ki^T y_k), into z.
FLDSIM_KERNEL void BlockIncompleteCholesky::forward_row(std::size_t i, const float* r, float* z) const {
  using linalg::Vec6f;
  Vec6f acc = Vec6f::load(r + 6 * i);
  for (std::int64_t c = col_start_[i]; c < col_start_[i + 1]; ++c)
    acc -= linalg::transposed_product(lower_f_[c].data(), Vec6f::load(z + 6 * std::size_t(by_col_row_[c])));
  pivot_times(i, acc, z + 6 * i);
}

// y_i = (U_ii^T)^-1 acc into out (the pivot block is lower triangular; the full product keeps the
// kernel's fixed rounding order, and its zeros cost less than a branch per column).
FLDSIM_KERNEL void BlockIncompleteCholesky::pivot_times(std::size_t i, const linalg::Vec6f& acc,
                                                        float* out) const {
  float in[6];
  acc.store(in);
  linalg::Vec6f y{};
  linalg::accumulate_product<1>(y, pivot_f_[i].data(), in);
  y.store(out);
}

// U z = y: z_i = U_ii^-1 (y_i - sum_{j > i} U_ij z_j), in place. The row's blocks are taken last to
// first, so that the sweep (rows descending) reads U_f in one descending stream: ascending within a
// row and descending across rows, the hardware's prefetcher lost it at N = 64000, where the factor
// comes from memory (this order: -17 % per CG iteration there, -1.6 % per step on the documented
// N = 1000 scene; bench/README.md, "Sweep direction and prefetching").
FLDSIM_KERNEL void BlockIncompleteCholesky::backward_row(std::size_t i, float* z) const {
  linalg::Vec6f acc = linalg::Vec6f::load(z + 6 * i);
  for (std::int64_t a = row_start_[i + 1]; a-- > row_start_[i];)
    linalg::accumulate_product<-1>(acc, upper_f_[a].data(), z + 6 * std::size_t(col_[a]));
  linalg::transposed_product(pivot_f_[i].data(), acc).store(z + 6 * i);
}

// One thread. Forward by scattering each solved block into the rows below: streams U in its own
// layout. z_i receives r_i - U_ki^T y_k for k ascending, the operations of forward_row.
FLDSIM_KERNEL void BlockIncompleteCholesky::sweeps_one_thread(const double* r, double* z) const {
  using linalg::Vec6f;
  const std::int64_t n = std::int64_t(inv_lower_.size());
  float* zp = permuted_z_.data();
  for (std::int64_t p = 0; p < n; ++p)
    for (int k = 0; k < 6; ++k) zp[6 * p + k] = float(r[6 * std::size_t(old_of_[p]) + k]);
  for (std::int64_t i = 0; i < n; ++i) {
    pivot_times(std::size_t(i), Vec6f::load(zp + 6 * i), zp + 6 * i);
    const Vec6f y = Vec6f::load(zp + 6 * i);
    for (std::int64_t a = row_start_[i]; a < row_start_[i + 1]; ++a) {
      float* zc = zp + 6 * std::size_t(col_[a]);
      Vec6f t = Vec6f::load(zc);
      t -= linalg::transposed_product(upper_f_[a].data(), y);
      t.store(zc);
    }
  }
  for (std::int64_t i = n; i-- > 0;) backward_row(std::size_t(i), zp);
  for (std::int64_t p = 0; p < n; ++p)
    for (int k = 0; k < 6; ++k) z[6 * std::size_t(old_of_[p]) + k] = double(zp[6 * p + k]);
}

void BlockIncompleteCholesky::sweeps_one_thread_narrow(const double* r, double* z) const {
  sweeps_one_thread(r, z);
}

void BlockIncompleteCholesky::sweeps_one_thread_wide(const double* r, double* z) const {
  sweeps_one_thread(r, z);
}

void BlockIncompleteCholesky::forward_row_narrow(std::size_t i, const float* r, float* z) const {
  forward_row(i, r, z);
}

void BlockIncompleteCholesky::forward_row_wide(std::size_t i, const float* r, float* z) const {
  forward_row(i, r, z);
}

void BlockIncompleteCholesky::backward_row_narrow(std::size_t i, float* z) const {
  backward_row(i, z);
}

void BlockIncompleteCholesky::backward_row_wide(std::size_t i, float* z) const {
  backward_row(i, z);
}

// z = P^T (U^T U)^-1 P r, with P the factor's row order: r is gathered into that order (rounded to
// single precision), the two sweeps run there, and the result is scattered back (widened to double):
// element-wise, so the same for any thread count.
void BlockIncompleteCholesky::apply(const double* r, double* z) const {
  const std::int64_t n = std::int64_t(inv_lower_.size());
  float* rp = permuted_r_.data();
  float* zp = permuted_z_.data();
  if (omp_get_max_threads() == 1 || !gathered_) {
    if (linalg::wide_kernels())
      sweeps_one_thread_wide(r, z);
    else
      sweeps_one_thread_narrow(r, z);
    return;
  }
  // Levels, without barriers between them: each thread takes its static share of every level in
  // level order and waits only for the rows it reads (row k's flag >= this sweep's epoch), so
  // a level costs a barrier only where a dependency really crosses threads (a barrier is 1.5 us on
  // some VMs, and a sweep has ~30 levels). Each row is still summed in its fixed order by whichever
  // thread owns it, so z does not depend on the thread count.
  std::atomic<std::uint64_t>* done = flags_.rows(std::size_t(n));
  const std::uint64_t fwd = flags_.epochs(2), bwd = fwd + 1;
  const std::int64_t forward = std::int64_t(forward_.levels()), backward = std::int64_t(backward_.levels());
  const std::int64_t ahead = linalg::prefetch_distance(n);
  const bool wide = linalg::wide_kernels();
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p)
      for (int k = 0; k < 6; ++k) rp[6 * p + k] = float(r[6 * std::size_t(old_of_[p]) + k]);
    for (std::int64_t l = 0; l < forward; ++l) {
#pragma omp for schedule(static) nowait
      for (std::int64_t s = forward_.level_start[l]; s < forward_.level_start[l + 1]; ++s) {
        const std::size_t i = forward_.row[s];
        if (ahead > 0 && s + ahead < n) {
          const std::size_t f = forward_.row[s + ahead];
          linalg::prefetch_block(pivot_f_[f]);
          for (std::int64_t c = col_start_[f]; c < col_start_[f + 1]; ++c)
            linalg::prefetch_block(lower_f_[c]);
        }
        for (std::int64_t c = col_start_[i]; c < col_start_[i + 1]; ++c)
          linalg::wait_until(done[by_col_row_[c]], fwd);
        if (wide)
          forward_row_wide(i, rp, zp);
        else
          forward_row_narrow(i, rp, zp);
        done[i].store(fwd, std::memory_order_release);
      }
    }
    for (std::int64_t l = 0; l < backward; ++l) {
#pragma omp for schedule(static) nowait
      for (std::int64_t s = backward_.level_start[l]; s < backward_.level_start[l + 1]; ++s) {
        const std::size_t i = backward_.row[s];
        if (ahead > 0 && s + ahead < n) {
          const std::size_t f = backward_.row[s + ahead];
          linalg::prefetch_block(pivot_f_[f]);
          for (std::int64_t a = row_start_[f]; a < row_start_[f + 1]; ++a)
            linalg::prefetch_block(upper_f_[a]);
        }
        linalg::wait_until(done[i], fwd);  // its own forward result
        for (std::int64_t a = row_start_[i]; a < row_start_[i + 1]; ++a)
          linalg::wait_until(done[col_[a]], bwd);
        if (wide)
          backward_row_wide(i, zp);
        else
          backward_row_narrow(i, zp);
        done[i].store(bwd, std::memory_order_release);
      }
    }
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p)
      for (int k = 0; k < 6; ++k) z[6 * std::size_t(old_of_[p]) + k] = double(zp[6 * p + k]);
  }
}

}  // namespace fldsim
