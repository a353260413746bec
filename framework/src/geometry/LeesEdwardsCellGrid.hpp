// Cubic cell grid over a Lees–Edwards box for finding all points within a cutoff rc.
// Cells have edge w = L/n >= rc with n = floor(L/rc). For a cell in row iy, the neighbour rows
// iy-1, iy, iy+1 are searched; when a row index wraps through the y faces, the images there are
// shifted in x by +/- the box offset s, so the x range searched is shifted by -/+ s and may span
// four cells instead of three. The x range is computed exactly for every row (it covers every
// point within rc of any point of the cell), and repeated cells (small n) are removed, so any
// offset is handled and no cell is visited twice.
#pragma once

#include <array>
#include <cstdint>

#include "fldsim/box.hpp"

namespace fldsim::geometry {

class LeesEdwardsCellGrid {
 public:
  // Up to 4 x cells per row (5 allowing for round-off at w == rc), 3 rows, 3 layers.
  static constexpr int max_neighbour_cells = 3 * 3 * 5;

  // Returns false (and sets cells_per_side() = 0) when fewer than 3 cells fit per side, in which
  // case callers must search all pairs.
  bool configure(const LeesEdwardsBox& box, double cutoff);

  int cells_per_side() const { return n_; }
  int cell_count() const { return n_ * n_ * n_; }
  // Cell of a position already wrapped into [0, L)^3.
  int cell_of(const Vec3& wrapped) const;
  // Fills `out` with the distinct cells that can hold points within the cutoff of any point of
  // `cell` under the box's current offset; returns how many.
  int neighbour_cells(int cell, std::array<int, max_neighbour_cells>& out) const;

 private:
  int index(int ix, int iy, int iz) const { return (iz * n_ + iy) * n_ + ix; }
  int n_ = 0;
  double L_ = 1.0, w_ = 1.0, cutoff_ = 0.0, offset_ = 0.0;
};

}  // namespace fldsim::geometry
