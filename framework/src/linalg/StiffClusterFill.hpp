// Fill positions for an incomplete Cholesky factor inside clusters of stiffly coupled bodies.
// Core-private (BlockIncompleteCholesky uses it).
//
// Near contact a lubricated pair's block dominates its bodies' resistance. IC(0) is exact on a
// chain of such pairs but drops the fill of a loop (three or more bodies in mutual near contact),
// and each such loop leaves CG an outlying eigenvalue: with N the clusters multiply and CG's
// iterations grew with them (bench/README.md, "Why the CG iterations grow with N"). Bodies joined by
// stiff blocks are grouped by union-find; every pair of a cluster of 3 to kMaxCluster bodies that
// is missing from A's pattern is a fill position, so that the factor of an isolated cluster is
// exact, its loops included.
#pragma once

#include <cstdint>
#include <vector>

#include "fldsim/block_sparse.hpp"

namespace fldsim::linalg {

class StiffClusterFill {
 public:
  // A block is stiff when the trace of its translational part exceeds this share of the smaller
  // translational diagonal trace of its two rows. Spheres phi 0.3, N = 27000, Pe 10: 0.5 cut the
  // CG iterations 33.7 -> 23.2 a step with 2 % more blocks in the factor; 0.3 to 20.2 with 25 % more
  // (each iteration dearer); 0.15 let clusters merge beyond kMaxCluster (no fill, no gain).
  static constexpr double kStiffRatio = 0.5;
  static constexpr std::uint32_t kMaxCluster = 24;

  // The fill positions of A into `out`: (i << 32) | j with i < j in A's numbering, sorted. A
  // function of A's values alone, at most a quarter of A's blocks (plus 64), so that a resumed run
  // factorises as the uninterrupted one and the time step does not allocate.
  void find(const BlockSparseMatrix& A, std::vector<std::uint64_t>& out);

 private:
  std::vector<std::uint32_t> parent_, start_, cursor_, members_;
};

}  // namespace fldsim::linalg
