// Reverse Cuthill-McKee ordering of a BlockSparseMatrix's block graph, for IC(0).
// Core-private.
//
// Why: IC(0) drops every fill block, and how much it drops depends on the order of the rows. Bodies
// are numbered as the start put them (a Monte Carlo start: at random in space; a long run mixes any
// start), so neighbours in the contact network are far apart in the numbering and IC(0) loses
// much of their coupling. A band-reducing order of the graph itself (Cuthill & McKee, Proc. 24th
// ACM National Conference (1969) 157; reversed, George (1971); on orderings for incomplete
// factorisations, Duff & Meurant, BIT 29, 635 (1989)) gives IC(0) a local order from the pattern
// alone, whatever the numbering. Measured (bench/README.md, "Row order"), spheres phi 0.5, Pe 10:
// N = 27000 with the bodies numbered at random 143 -> 60 CG iterations per step (1446 -> 586
// ms/step); a Monte Carlo start of N = 1000, 35 -> 28.5 (-6 % per step).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "linalg/GrowOnly.hpp"

namespace fldsim::linalg {

// Scratch of reverse_cuthill_mckee, kept between calls so that a new pattern does not allocate.
struct CuthillMcKeeScratch {
  std::vector<std::uint32_t> degree, count, by_degree, stamp, level, next;
};

// new_of[i]: position of row i in the new order; old_of[p]: the row at position p. The pattern is
// A's upper blocks by rows (row_start, col) and by columns (col_start, by_col_row). Deterministic:
// every tie is broken by (degree, row). Each connected component starts at a pseudo-peripheral
// row (one George-Liu sweep from its row of least degree), its rows taken breadth first with
// neighbours by increasing degree; the whole order is then reversed.
inline void reverse_cuthill_mckee(std::size_t n, const std::vector<std::int64_t>& row_start,
                                  const std::vector<std::uint32_t>& col,
                                  const std::vector<std::int64_t>& col_start,
                                  const std::vector<std::uint32_t>& by_col_row,
                                  std::vector<std::uint32_t>& new_of, std::vector<std::uint32_t>& old_of,
                                  CuthillMcKeeScratch& s) {
  constexpr std::uint32_t none = 0xffffffffu;
  auto each_neighbour = [&](std::uint32_t v, auto&& f) {
    for (std::int64_t a = row_start[v]; a < row_start[v + 1]; ++a) f(col[std::size_t(a)]);
    for (std::int64_t c = col_start[v]; c < col_start[v + 1]; ++c) f(by_col_row[std::size_t(c)]);
  };
  resize_grow_only(s.degree, n);
  resize_grow_only(s.by_degree, n);
  fill_grow_only(s.stamp, n, none);
  resize_grow_only(s.level, n);
  resize_grow_only(s.next, n);
  fill_grow_only(new_of, n, none);
  resize_grow_only(old_of, n);
  // Rows by (degree, row): a counting sort, since degrees are small (a body has a few tens of
  // neighbours at most). Called at every new factorisation, so kept O(n + blocks).
  std::uint32_t top = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    s.degree[v] = std::uint32_t(row_start[v + 1] - row_start[v] + col_start[v + 1] - col_start[v]);
    top = std::max(top, s.degree[v]);
  }
  fill_grow_only(s.count, std::size_t(top) + 2, std::uint32_t(0));
  for (std::uint32_t v = 0; v < n; ++v) ++s.count[s.degree[v] + 1];
  for (std::size_t d = 0; d + 1 < s.count.size(); ++d) s.count[d + 1] += s.count[d];
  for (std::uint32_t v = 0; v < n; ++v) s.by_degree[s.count[s.degree[v]]++] = v;
  auto lighter = [&](std::uint32_t u, std::uint32_t v) {
    return s.degree[u] != s.degree[v] ? s.degree[u] < s.degree[v] : u < v;
  };

  std::size_t placed = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::uint32_t start = s.by_degree[k];
    if (new_of[start] != none) continue;
    // Breadth-first levels from the component's lightest row; its last level's lightest row is
    // far from it, and starting there gives longer, narrower levels (a narrower band).
    {
      std::size_t head = 0, tail = 0;
      s.next[tail++] = start;
      s.stamp[start] = std::uint32_t(k);
      s.level[start] = 0;
      std::uint32_t far = start;
      while (head < tail) {
        const std::uint32_t v = s.next[head++];
        if (s.level[v] > s.level[far] || (s.level[v] == s.level[far] && lighter(v, far))) far = v;
        each_neighbour(v, [&](std::uint32_t w) {
          if (s.stamp[w] == std::uint32_t(k)) return;
          s.stamp[w] = std::uint32_t(k);
          s.level[w] = s.level[v] + 1;
          s.next[tail++] = w;
        });
      }
      start = far;
    }
    // Cuthill-McKee: breadth first, each row's new neighbours by increasing degree.
    std::size_t head = placed;
    new_of[start] = std::uint32_t(placed);
    old_of[placed++] = start;
    while (head < placed) {
      const std::uint32_t v = old_of[head++];
      const std::size_t first = placed;
      each_neighbour(v, [&](std::uint32_t w) {
        if (new_of[w] != none) return;
        new_of[w] = std::uint32_t(placed);
        old_of[placed++] = w;
      });
      // A row's new neighbours are few: insertion sort.
      for (std::size_t p = first + 1; p < placed; ++p)
        for (std::size_t q = p; q > first && lighter(old_of[q], old_of[q - 1]); --q)
          std::swap(old_of[q], old_of[q - 1]);
      for (std::size_t p = first; p < placed; ++p) new_of[old_of[p]] = std::uint32_t(p);
    }
  }
  std::reverse(old_of.begin(), old_of.begin() + std::ptrdiff_t(n));
  for (std::size_t p = 0; p < n; ++p) new_of[old_of[p]] = std::uint32_t(p);
}

}  // namespace fldsim::linalg
