#include <Eigen/Cholesky>
#include <cmath>

#include "fldsim/block_sparse.hpp"
#include "fldsim/parallel_loop.hpp"
#include "linalg/BlockIncompleteCholesky.hpp"
#include "linalg/EisenstatDilu.hpp"
#include "linalg/SinglePrecisionProduct.hpp"

namespace fldsim {
namespace {
// Length of a dot-product chunk (256 bodies): partial sums are per chunk, never per thread.
constexpr std::size_t kChunk = 6 * 256;
}  // namespace

// The solver's state: which preconditioner, its factors and the CG work vectors.
struct BlockPCG::Workspace {
  explicit Workspace(Preconditioner k) : kind(k) {}
  void precondition(const std::vector<double>& in, std::vector<double>& out) const;
  // Dot product as a sum of fixed-size chunks, added in chunk order: reproducible for any
  // thread count.
  double dot(const std::vector<double>& a, const std::vector<double>& b);
  // x += alpha p, r -= alpha q, and r.r summed exactly as dot(r, r) would (same chunks, same order):
  // one pass over r instead of two (r leaves the last-level cache between them at N of 10^4 and up).
  double step_and_norm(double alpha, double* x);
  // CG on the Eisenstat-transformed system (EisenstatDilu), after solve() has formed r0.
  BlockPCG::Result solve_transformed(const BlockSparseMatrix& A, double* x, double tolerance,
                                     int max_iterations, double bnorm, BlockPCG::Result result);

  Preconditioner kind, active = Preconditioner::BlockJacobi;
  std::vector<double> shifts{BlockPCG::kDefaultShifts.begin(), BlockPCG::kDefaultShifts.end()};
  double shift = 0.0;  // of the IC(0) factor in use; 0 while another preconditioner is
  std::vector<Mat6> inv_diag;
  BlockIncompleteCholesky ic;
  EisenstatDilu dilu;
  linalg::SinglePrecisionProduct single;  // R rounded, for the products of large matrices
  std::vector<double> r, z, p, q, partial;
  std::vector<double> r_hat, x_hat, t;  // EisenstatDilu: the transformed system's vectors
};

BlockPCG::BlockPCG(Preconditioner kind) : w_(std::make_unique<Workspace>(kind)) {}
BlockPCG::~BlockPCG() = default;
BlockPCG::BlockPCG(BlockPCG&&) noexcept = default;
BlockPCG& BlockPCG::operator=(BlockPCG&&) noexcept = default;
Preconditioner BlockPCG::active() const {
  return w_->active;
}
void BlockPCG::set_shifts(const std::vector<double>& shifts) {
  w_->shifts = shifts;
}
void BlockPCG::set_row_order(RowOrder order) {
  w_->ic.set_row_order(order);
}
double BlockPCG::shift() const {
  return w_->shift;
}

std::vector<double> BlockPCG::preconditioner_state() const {
  return w_->kind == Preconditioner::IncompleteCholesky ? w_->ic.order_state() : std::vector<double>{};
}

bool BlockPCG::restore_preconditioner_state(const std::vector<double>& state, std::size_t blocks) {
  if (state.empty()) return true;
  return w_->kind == Preconditioner::IncompleteCholesky && w_->ic.restore_order_state(state, blocks);
}

void BlockPCG::bind(const BlockSparseMatrix& A) {
  if (linalg::SinglePrecisionProduct::pays(A))
    w_->single.bind(A);
  else
    w_->single.unbind();
}

void BlockPCG::prepare(const BlockSparseMatrix& A) {
  Workspace& w = *w_;
  const std::size_t n = A.blocks();
  w.r.resize(6 * n);
  w.z.resize(6 * n);
  w.p.resize(6 * n);
  w.q.resize(6 * n);
  w.partial.resize((6 * n + kChunk - 1) / kChunk);
  if (w.kind == Preconditioner::IncompleteCholesky) {
    // IC(0) can break down on an SPD matrix (the fill it drops can leave a pivot block indefinite;
    // seen in the reverse Cuthill-McKee order of 1000 spheres near a periodic cubic lattice at
    // phi 0.3, and at most factorisations of sheared fused-dumbbell networks). A diagonal shift
    // makes the factorisation succeed (for a large enough shift it always does) and keeps the
    // factor of a matrix close to A: 1000 fused dumbbells sheared 500 strains at kT = 0 took 59.6 CG
    // iterations a step over the next 10 strains where the D-ILU fallback took 79.7 (bench/README.md,
    // "Shifted IC(0)").
    w.shift = 0.0;
    bool ok = w.ic.factorize(A);
    for (std::size_t k = 0; !ok && k < w.shifts.size(); ++k) {
      w.shift = w.shifts[k];
      ok = w.ic.refactorize(A, w.shift);
    }
    if (ok) {
      w.active = Preconditioner::IncompleteCholesky;
      return;
    }
    w.shift = 0.0;
  }
  // D-ILU next. It factorises in the bodies' own numbering and updates only the pivots, so it
  // breaks down on other matrices than IC(0) does; block Jacobi is the last resort (its pivots
  // are R's own diagonal blocks, always positive definite).
  if (w.kind != Preconditioner::BlockJacobi && w.dilu.factorize(A)) {
    w.r_hat.resize(6 * n);
    w.x_hat.resize(6 * n);
    w.t.resize(6 * n);
    w.active = Preconditioner::EisenstatDilu;
    return;
  }
  w.active = Preconditioner::BlockJacobi;
  w.inv_diag.resize(n);
  parallel_for(std::int64_t(n), [&](std::int64_t i) {
    // Diagonal blocks of an SPD matrix are SPD: invert through their Cholesky factor.
    Eigen::LLT<Mat6> llt(A.diagonal(std::size_t(i)));
    w.inv_diag[i] = llt.solve(Mat6::Identity());
  });
}

namespace {
// sum_k a[k] b[k] over [begin, end) in four interleaved sums: one running sum is a chain of dependent
// additions (one FP-add latency per element, about 3 % of a step at N = 1000); four let them overlap.
double chunk_dot(const double* a, const double* b, std::size_t begin, std::size_t end) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t k = begin;
  for (; k + 4 <= end; k += 4) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
    s2 += a[k + 2] * b[k + 2];
    s3 += a[k + 3] * b[k + 3];
  }
  for (; k < end; ++k) s0 += a[k] * b[k];
  return (s0 + s1) + (s2 + s3);
}
}  // namespace

double BlockPCG::Workspace::dot(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t m = a.size();
  const std::int64_t chunks = std::int64_t(partial.size());
  parallel_for(chunks, [&](std::int64_t c) {
    const std::size_t begin = std::size_t(c) * kChunk, end = std::min(m, begin + kChunk);
    partial[c] = chunk_dot(a.data(), b.data(), begin, end);
  });
  double s = 0.0;
  for (const double v : partial) s += v;
  return s;
}

double BlockPCG::Workspace::step_and_norm(double alpha, double* x) {
  const std::size_t m = r.size();
  const std::int64_t chunks = std::int64_t(partial.size());
  parallel_for(chunks, [&](std::int64_t c) {
    const std::size_t begin = std::size_t(c) * kChunk, end = std::min(m, begin + kChunk);
    for (std::size_t k = begin; k < end; ++k) {
      x[k] += alpha * p[k];
      r[k] -= alpha * q[k];
    }
    partial[c] = chunk_dot(r.data(), r.data(), begin, end);  // as dot(r, r)
  });
  double s = 0.0;
  for (const double v : partial) s += v;
  return s;
}

void BlockPCG::Workspace::precondition(const std::vector<double>& in, std::vector<double>& out) const {
  if (active == Preconditioner::IncompleteCholesky) {
    ic.apply(in.data(), out.data());
    return;
  }
  const std::int64_t n = std::int64_t(inv_diag.size());
  parallel_for(n, [&](std::int64_t i) {
    Eigen::Map<Vec6>(out.data() + 6 * i) = inv_diag[i] * Eigen::Map<const Vec6>(in.data() + 6 * i);
  });
}

// With a single-precision copy of A bound (bind()), CG's products use it and the recurrence
// converges for the rounded matrix; the stopping rule is then checked with A itself, and if
// |b - A x| is still above the tolerance (a stale copy, or a tolerance near the rounding) CG
// restarts from that true residual with A's own products.
BlockPCG::Result BlockPCG::solve(const BlockSparseMatrix& A, const double* b, double* x, double tolerance,
                                 int max_iterations) {
  Workspace& w = *w_;
  std::vector<double>&r_ = w.r, &z_ = w.z, &p_ = w.p, &q_ = w.q;
  const std::int64_t m = std::int64_t(6 * A.blocks());
  bool single = w.single.bound_to(A) && w.active != Preconditioner::EisenstatDilu;
  auto multiply = [&](const double* in, double* out) {
    if (single)
      w.single.multiply(in, out);
    else
      A.multiply(in, out);
  };
  auto residual = [&] {
    multiply(x, q_.data());
    parallel_for(m, [&](std::int64_t k) { r_[k] = b[k] - q_[k]; });
    return std::sqrt(w.dot(r_, r_));
  };
  Result result;
  parallel_for(m, [&](std::int64_t k) { z_[k] = b[k]; });
  const double bnorm = std::sqrt(w.dot(z_, z_));
  if (bnorm == 0.0) {
    std::fill(x, x + m, 0.0);
    result.converged = true;
    return result;
  }
  double rnorm = residual();
  result.relative_residual = rnorm / bnorm;
  // Converged by the recurrence's residual: true, unless the products were rounded and A's own
  // residual says otherwise (then r_ holds that residual, and the products are A's from now on).
  auto converged = [&] {
    if (result.relative_residual > tolerance) return false;
    if (!single) return true;
    single = false;
    rnorm = residual();
    result.relative_residual = rnorm / bnorm;
    return result.relative_residual <= tolerance;
  };
  if (converged()) {
    result.converged = true;
    return result;
  }
  if (w.active == Preconditioner::EisenstatDilu)
    return w.solve_transformed(A, x, tolerance, max_iterations, bnorm, result);
  w.precondition(r_, z_);
  p_ = z_;
  double rz = w.dot(r_, z_);
  for (int it = 1; it <= max_iterations; ++it) {
    multiply(p_.data(), q_.data());
    const double alpha = rz / w.dot(p_, q_);
    rnorm = std::sqrt(w.step_and_norm(alpha, x));
    result.iterations = it;
    result.relative_residual = rnorm / bnorm;
    const bool was_single = single;
    if (converged()) {
      result.converged = true;
      return result;
    }
    w.precondition(r_, z_);
    const double rz_new = w.dot(r_, z_);
    if (was_single != single) {  // restart from A's own residual (keeping p diverges: 75 against
      rz = rz_new;               // 38 CG it/step at N = 64000)
      p_ = z_;
      continue;
    }
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_for(m, [&](std::int64_t k) { p_[k] = z_[k] + beta * p_[k]; });
  }
  return result;
}

// CG on L^-1 A L^-T x^ = L^-1 r0 with the preconditioner P (EisenstatDilu.hpp), from x^ = 0, r holding
// r0 = b - A x0, bnorm = |b| and |r0| / |b| in result. The stopping rule is the other solves' |b - A x|
// <= tol |b|: b - A x = L r^, estimated each iteration as c sqrt(r^.P r^) (c calibrated on r0) and,
// when the estimate says converged, computed (L r^) and checked, c recalibrated if it was not.
BlockPCG::Result BlockPCG::Workspace::solve_transformed(const BlockSparseMatrix& A, double* x,
                                                        double tolerance, int max_iterations, double bnorm,
                                                        BlockPCG::Result result) {
  Workspace& w = *this;
  std::vector<double>&r = w.r, &z = w.z, &p = w.p, &q = w.q, &rh = w.r_hat, &xh = w.x_hat;
  const std::int64_t m = std::int64_t(6 * A.blocks());
  const double limit = tolerance * bnorm;
  w.dilu.bind(A);
  w.dilu.forward(A, r.data(), rh.data());
  w.dilu.pivot_times(rh.data(), z.data());
  double rz = w.dot(rh, z);
  double c = result.relative_residual * bnorm / std::sqrt(rz);
  p = z;
  std::fill(xh.begin(), xh.end(), 0.0);
  for (int it = 1; it <= max_iterations; ++it) {
    w.dilu.operator_times(A, p.data(), q.data(), w.t.data());
    const double alpha = rz / w.dot(p, q);
    parallel_for(m, [&](std::int64_t k) {
      xh[k] += alpha * p[k];
      rh[k] -= alpha * q[k];
    });
    result.iterations = it;
    w.dilu.pivot_times(rh.data(), z.data());
    const double rz_new = w.dot(rh, z);
    result.relative_residual = c * std::sqrt(rz_new) / bnorm;
    if (c * std::sqrt(rz_new) <= limit) {
      w.dilu.lower_times(A, rh.data(), r.data());
      const double rnorm = std::sqrt(w.dot(r, r));
      result.relative_residual = rnorm / bnorm;
      if (rnorm <= limit) {
        result.converged = true;
        break;
      }
      c = rnorm / std::sqrt(rz_new);
    }
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_for(m, [&](std::int64_t k) { p[k] = z[k] + beta * p[k]; });
  }
  w.dilu.backward(A, xh.data(), w.t.data());
  parallel_for(m, [&](std::int64_t k) { x[k] += w.t[k]; });
  return result;
}

}  // namespace fldsim
