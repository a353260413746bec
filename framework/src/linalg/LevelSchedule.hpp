// Dependency levels of a block triangular sweep over a BlockSparseMatrix pattern, and the per-row
// flags and spin-wait the level-scheduled sweeps use instead of barriers (BlockIncompleteCholesky,
// EisenstatDilu).
// Core-private.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {

// Rows row[level_start[l]] .. row[level_start[l+1] - 1] form level l, ascending within it: a row's
// dependencies are all in earlier levels.
struct Levels {
  std::vector<std::int64_t> level_start;
  std::vector<std::uint32_t> row;
  std::size_t levels() const { return level_start.empty() ? 0 : level_start.size() - 1; }
};

// Level of each row (0 for rows without dependencies, else 1 + the deepest dependency), visiting
// rows so that dependencies come first (descending for a backward sweep); then the rows grouped by
// level. each_dependency(i, depend) calls depend(k) for every row k that row i reads. level and
// fill are scratch.
template <class Dependencies>
void schedule(std::size_t n, bool descending, Dependencies&& each_dependency, Levels& out,
              std::vector<std::uint32_t>& level, std::vector<std::int64_t>& fill) {
  level.assign(n, 0);
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t i = descending ? n - 1 - t : t;
    each_dependency(i, [&](std::size_t k) { level[i] = std::max(level[i], level[k] + 1); });
  }
  const std::uint32_t top = n == 0 ? 0 : *std::max_element(level.begin(), level.end());
  fill_grow_only(out.level_start, std::size_t(top) + 2, std::int64_t(0));
  for (const std::uint32_t l : level) ++out.level_start[l + 1];
  for (std::size_t l = 0; l + 1 < out.level_start.size(); ++l) out.level_start[l + 1] += out.level_start[l];
  out.row.resize(n);
  copy_grow_only(fill, out.level_start.begin(), out.level_start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) out.row[fill[level[i]]++] = std::uint32_t(i);
}

// Spin until another thread has published `flag` >= epoch; yield after a while, so a descheduled
// owner gets the core back on an oversubscribed machine.
inline void wait_until(const std::atomic<std::uint64_t>& flag, std::uint64_t epoch) {
  for (int spins = 0; flag.load(std::memory_order_acquire) < epoch; ++spins)
    if (spins > 2000) std::this_thread::yield();
}

// Per-row completion flags of the level-scheduled passes: row i's flag holds the epoch of the last
// pass that finished it, and every pass takes epochs larger than all before, so no reset is needed
// between passes (a level then costs a barrier only where a dependency crosses threads).
class RowFlags {
 public:
  // Flags of n rows: allocated, and the epochs restarted, only when n changes (they outlive
  // pattern changes).
  std::atomic<std::uint64_t>* rows(std::size_t n) {
    if (size_ != n) {
      flags_ = std::make_unique<std::atomic<std::uint64_t>[]>(n);
      for (std::size_t i = 0; i < n; ++i) flags_[i].store(0, std::memory_order_relaxed);
      size_ = n;
      epoch_ = 0;
    }
    return flags_.get();
  }
  // The first of k new epochs (call after rows()).
  std::uint64_t epochs(int k) {
    const std::uint64_t first = epoch_ + 1;
    epoch_ += std::uint64_t(k);
    return first;
  }

 private:
  std::unique_ptr<std::atomic<std::uint64_t>[]> flags_;
  std::size_t size_ = 0;
  std::uint64_t epoch_ = 0;
};

}  // namespace fldsim::linalg
