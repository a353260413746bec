#include "geometry/LeesEdwardsCellGrid.hpp"

#include <algorithm>
#include <cmath>

namespace fldsim::geometry {

bool LeesEdwardsCellGrid::configure(const LeesEdwardsBox& box, double cutoff) {
  L_ = box.edge();
  cutoff_ = cutoff;
  offset_ = box.offset();
  n_ = static_cast<int>(std::floor(L_ / cutoff));
  if (n_ < 3) {
    n_ = 0;
    return false;
  }
  w_ = L_ / n_;
  return true;
}

int LeesEdwardsCellGrid::cell_of(const Vec3& x) const {
  int i[3];
  for (int k = 0; k < 3; ++k) i[k] = std::clamp(static_cast<int>(x[k] / w_), 0, n_ - 1);
  return index(i[0], i[1], i[2]);
}

int LeesEdwardsCellGrid::neighbour_cells(int cell, std::array<int, max_neighbour_cells>& out) const {
  const int ix = cell % n_, iy = (cell / n_) % n_, iz = cell / (n_ * n_);
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    int jy = iy + dy;
    // A point j in a row reached through the top face has its relevant image at x_j + s (the
    // image above is displaced by +s), so x_j must lie within rc of x_i - s; through the bottom
    // face, within rc of x_i + s.
    double shift = 0.0;
    if (jy >= n_) {
      jy -= n_;
      shift = offset_;
    } else if (jy < 0) {
      jy += n_;
      shift = -offset_;
    }
    const int x_first = static_cast<int>(std::floor((ix * w_ - shift - cutoff_) / w_));
    const int x_last = static_cast<int>(std::floor(((ix + 1) * w_ - shift + cutoff_) / w_));
    // Distinct x cells of this row (at most n_).
    int xs[5], nx = 0;
    for (int jx = x_first; jx <= x_last && nx < std::min(n_, 5); ++jx) {
      const int wrapped = ((jx % n_) + n_) % n_;
      if (std::find(xs, xs + nx, wrapped) == xs + nx) xs[nx++] = wrapped;
    }
    for (int dz = -1; dz <= 1; ++dz) {
      const int jz = (iz + dz + n_) % n_;
      for (int k = 0; k < nx; ++k) out[count++] = index(xs[k], jy, jz);
    }
  }
  return count;
}

}  // namespace fldsim::geometry
