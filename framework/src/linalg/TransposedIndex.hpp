// The column index of a block pattern stored by rows. Core-private.
#pragma once

#include <cstdint>
#include <vector>

#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {

// For a pattern of n block rows stored by rows (row_start, col), the blocks of each column j in
// increasing row: col_start[j] .. col_start[j+1] - 1 index by_col (a block's position in the row
// storage) and by_col_row (its row), so that a column is always summed in the same order. fill is
// scratch. (BlockSparseMatrix's own pattern, and IC(0)'s pattern in its row order.)
inline void transposed_index(std::size_t n, const std::vector<std::int64_t>& row_start,
                             const std::vector<std::uint32_t>& col, std::vector<std::int64_t>& col_start,
                             std::vector<std::int64_t>& by_col, std::vector<std::uint32_t>& by_col_row,
                             std::vector<std::int64_t>& fill) {
  const std::size_t nnz = std::size_t(row_start[n]);
  fill_grow_only(col_start, n + 1, std::int64_t(0));
  for (std::size_t a = 0; a < nnz; ++a) ++col_start[col[a] + 1];
  for (std::size_t j = 0; j < n; ++j) col_start[j + 1] += col_start[j];
  copy_grow_only(fill, col_start.begin(), col_start.end() - 1);
  resize_grow_only(by_col, nnz);
  resize_grow_only(by_col_row, nnz);
  for (std::size_t i = 0; i < n; ++i)
    for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a) {
      const std::int64_t k = fill[col[std::size_t(a)]]++;
      by_col[std::size_t(k)] = a;
      by_col_row[std::size_t(k)] = std::uint32_t(i);
    }
}

}  // namespace fldsim::linalg
