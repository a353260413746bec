// IC(0)'s rows graded by stiffness: the softest bodies first, the stiffest last. Core-private.
//
// Why: IC(0) drops the fill that eliminating a row creates among its later neighbours, and that
// fill is as large as the row's couplings. A body in stiff near contact eliminated early throws
// away fill of the size of its lubrication blocks (up to 1e3-1e4 times R_0); eliminated last, the
// fill dropped onto it comes from soft rows and is small. So the order of the rows by increasing
// stiffness is IC(0)'s minimum-discarded-fill idea in its cheapest form (D'Azevedo, Forsyth & Tang,
// SIAM J. Matrix Anal. Appl. 13, 944 (1992): eliminate first the rows whose elimination discards
// least). Measured (bench/README.md, "IC(0) rows graded by stiffness"): 1000 fused dumbbells sheared
// 40 strains at kT = 0, 55.5 -> 39.3 CG iterations a step (at Pe 1000, 45.9 -> 33.3), IC(0)'s
// breakdowns 233 -> fewer than 16 in 500 factorisations. Beyond the caches the scattered rows cost
// more than that saves, and near equilibrium (narrow traces) grading costs iterations:
// BlockIncompleteCholesky grades only small matrices with broad traces unless told to.
//
// The grade of row i is the bucket of its diagonal block's trace t_i against the smallest one,
// floor(4 log2(t_i / t_min)) (buckets 2^(1/4) = 1.19 wide), and the rows are sorted by grade
// stably, so that rows of one grade keep the reverse Cuthill-McKee order they come in (its
// locality, and whole lattices of equal bodies keep it entirely: no order from rounding noise).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fldsim/block_sparse.hpp"
#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {

// Grades of grade_by_stiffness (the ratio's cap, 1e15, is grade 199).
inline constexpr std::uint32_t kGrades = 256;

// Scratch of grade_by_stiffness and stiffness_is_broad, kept between calls so that a reorder does
// not allocate.
struct StiffnessGradeScratch {
  std::vector<std::uint32_t> grade, count, sorted;
  std::vector<double> trace;
};

// True when the median body's diagonal trace is at least kBroad times the smallest: most bodies
// are held by lubrication much stiffer than their own drag, as in a sheared contact network
// (median/smallest 39-65 in 1000 fused dumbbells sheared at kT = 0 and Pe 1000, 6.4 at Pe 10).
// Where the traces are narrow (near equilibrium, 2.8-3.9 in the scenes that grading made dearer:
// spheres phi 0.5 on a lattice +5 % CG iterations, homonuclear c/a 0.2 phi 0.5 Pe 0.1 +4.5 %,
// LAMMPS's documented scene +2.6 %) the grades only split near-equal rows into classes, a
// multicolour-like order that IC(0) can do worse with (bench/README.md, "IC(0) rows graded by
// stiffness").
inline constexpr double kBroad = 5.0;
inline bool stiffness_is_broad(const BlockSparseMatrix& A, StiffnessGradeScratch& s) {
  const std::size_t n = A.blocks();
  if (n == 0) return false;
  // All of the scratch is sized here, so that a state that turns broad later in a run is graded
  // without allocating inside the time step (tests/dynamics/StepAllocationTest.cpp).
  resize_grow_only(s.trace, n);
  resize_grow_only(s.grade, n);
  resize_grow_only(s.sorted, n);
  fill_grow_only(s.count, std::size_t(kGrades) + 1, std::uint32_t(0));
  for (std::size_t i = 0; i < n; ++i) s.trace[i] = A.diagonal(i).trace();
  const double t_min = *std::min_element(s.trace.begin(), s.trace.begin() + std::ptrdiff_t(n));
  auto median = s.trace.begin() + std::ptrdiff_t(n / 2);
  std::nth_element(s.trace.begin(), median, s.trace.begin() + std::ptrdiff_t(n));
  return t_min > 0.0 && *median >= kBroad * t_min;
}

// Reorders old_of (a permutation of A's rows, e.g. reverse Cuthill-McKee) stably by grade and
// writes new_of as its inverse. Deterministic: the grade comes from the exponent of a double
// (std::ilogb), not from a library logarithm.
inline void grade_by_stiffness(const BlockSparseMatrix& A, std::vector<std::uint32_t>& new_of,
                               std::vector<std::uint32_t>& old_of, StiffnessGradeScratch& s) {
  const std::size_t n = A.blocks();
  if (n == 0) return;
  double t_min = A.diagonal(0).trace();
  for (std::size_t i = 1; i < n; ++i) t_min = std::min(t_min, A.diagonal(i).trace());
  if (!(t_min > 0.0)) return;  // not an SPD matrix's diagonal: keep the order as it is
  resize_grow_only(s.grade, n);
  for (std::size_t i = 0; i < n; ++i) {
    // (t / t_min)^4 has exponent floor(4 log2(t / t_min)), up to its rounding. The ratio is capped
    // at 1e15 (grade 199; no lubrication block comes near it) so that the power stays finite.
    const double r = std::min(A.diagonal(i).trace() / t_min, 1e15);
    const double r4 = (r * r) * (r * r);
    const int g = r4 >= 1.0 ? std::ilogb(r4) : 0;  // also for a NaN trace: grade 0
    s.grade[i] = std::uint32_t(std::min(g, int(kGrades) - 1));
  }
  // Counting sort by grade: stable, O(n), no allocation once the scratch has grown.
  fill_grow_only(s.count, kGrades + 1, std::uint32_t(0));
  for (std::size_t i = 0; i < n; ++i) ++s.count[s.grade[i] + 1];
  for (std::uint32_t g = 0; g < kGrades; ++g) s.count[g + 1] += s.count[g];
  resize_grow_only(s.sorted, n);
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint32_t i = old_of[p];
    s.sorted[s.count[s.grade[i]]++] = i;
  }
  std::copy_n(s.sorted.begin(), n, old_of.begin());
  for (std::size_t p = 0; p < n; ++p) new_of[old_of[p]] = std::uint32_t(p);
}

}  // namespace fldsim::linalg
