#include "linalg/StiffClusterFill.hpp"

#include <algorithm>
#include <cmath>

#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {

void StiffClusterFill::find(const BlockSparseMatrix& A, std::vector<std::uint64_t>& out) {
  out.clear();
  const std::size_t most = A.col().size() / 4 + 64;
  reserve_with_headroom(out, most);
  const std::size_t n = A.blocks();
  resize_grow_only(parent_, n);
  for (std::size_t i = 0; i < n; ++i) parent_[i] = std::uint32_t(i);
  auto root = [&](std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  };
  auto trace3 = [](const Mat6& M) { return M(0, 0) + M(1, 1) + M(2, 2); };
  const auto& a_start = A.row_start();
  const auto& a_col = A.col();
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    const double di = trace3(A.diagonal(i));
    for (std::int64_t a = a_start[i]; a < a_start[i + 1]; ++a) {
      const std::uint32_t j = a_col[std::size_t(a)];
      if (std::abs(trace3(A.upper(a))) <= kStiffRatio * std::min(di, trace3(A.diagonal(j)))) continue;
      const std::uint32_t ri = root(std::uint32_t(i)), rj = root(j);
      if (ri != rj) parent_[std::max(ri, rj)] = std::min(ri, rj);
      any = true;
    }
  }
  if (!any) return;
  // Members grouped by root (a counting sort, which keeps them in ascending order), then the
  // missing pairs of each cluster.
  fill_grow_only(start_, n + 1, std::uint32_t(0));
  for (std::size_t i = 0; i < n; ++i) ++start_[root(std::uint32_t(i)) + 1];
  for (std::size_t i = 0; i < n; ++i) start_[i + 1] += start_[i];
  resize_grow_only(members_, n);
  copy_grow_only(cursor_, start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) members_[cursor_[root(std::uint32_t(i))]++] = std::uint32_t(i);
  for (std::size_t r = 0; r < n; ++r) {
    const std::uint32_t b = start_[r], e = start_[r + 1];
    if (e - b < 3 || e - b > kMaxCluster || out.size() + (e - b) * (e - b - 1) / 2 > most) continue;
    for (std::uint32_t x = b; x < e; ++x)
      for (std::uint32_t y = x + 1; y < e; ++y)
        if (A.find(members_[x], members_[y]) < 0)
          out.push_back((std::uint64_t(members_[x]) << 32) | members_[y]);
  }
  std::sort(out.begin(), out.end());
}

}  // namespace fldsim::linalg
