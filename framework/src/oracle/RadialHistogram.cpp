#include "oracle/RadialHistogram.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "fldsim/error.hpp"
#include "oracle/PeriodicDifference.hpp"

namespace fldsim::oracle {

RadialHistogram::RadialHistogram(PairPoints points, double bin_width, double r_max)
    : points_(points), width_(bin_width) {
  if (!(bin_width > 0.0) || !(r_max > bin_width)) throw Error("g(r): expected 0 < bin width < r_max");
  const int n = int(std::round(r_max / bin_width));
  for (int k = 0; k <= n; ++k) edges_.push_back(k * bin_width);
  counts_.assign(std::size_t(n), 0.0);
  total_counts_.assign(std::size_t(n), 0.0);
}

void RadialHistogram::add_sample(const System& s) {
  const auto& box = s.box();
  if (2.0 * r_max() > box.edge() + 1e-12)
    throw Error("g(r): range " + std::to_string(r_max()) + " a exceeds half the box edge " +
                std::to_string(0.5 * box.edge()) + " a");
  const bool nodes = points_ == PairPoints::Nodes;
  const std::size_t m = nodes ? s.nodes_per_body() : 1, n = s.size();
  const auto& x = nodes ? s.node_positions() : s.positions();
  const double rmax2 = r_max() * r_max(), inv_w = 1.0 / width_, L = box.edge();
  const bool sheared = box.offset() != 0.0;
  auto count = [&](std::size_t p, std::size_t q) {
    if (p / m == q / m) return;
    const Vec3 d = wrapped_[q] - wrapped_[p];
    const double d2 = (sheared ? box.minimum_image(d) : periodic_difference(d, L)).squaredNorm();
    if (d2 >= rmax2) return;
    const auto k = std::size_t(std::sqrt(d2) * inv_w);
    if (k < counts_.size()) counts_[k] += 2.0;  // ordered pairs
  };
  wrapped_.assign(x.begin(), x.end());
  for (auto& w : wrapped_) box.wrap(w);
  if (!grid_.configure(box, r_max())) {
    for (std::size_t p = 0; p < n * m; ++p)
      for (std::size_t q = p + 1; q < n * m; ++q) count(p, q);
  } else {
    // Linked cells: each pair once (q > p) from the distinct neighbour cells of p's cell.
    head_.assign(std::size_t(grid_.cell_count()), -1);
    next_.resize(n * m);
    cell_.resize(n * m);
    for (std::size_t p = 0; p < n * m; ++p) {
      cell_[p] = grid_.cell_of(wrapped_[p]);
      next_[p] = head_[std::size_t(cell_[p])];
      head_[std::size_t(cell_[p])] = int(p);
    }
    std::array<int, geometry::LeesEdwardsCellGrid::max_neighbour_cells> cells;
    for (std::size_t p = 0; p < n * m; ++p) {
      const int nc = grid_.neighbour_cells(cell_[p], cells);
      for (int c = 0; c < nc; ++c)
        for (int q = head_[std::size_t(cells[std::size_t(c)])]; q >= 0; q = next_[std::size_t(q)])
          if (std::size_t(q) > p) count(p, std::size_t(q));
    }
  }
  const double V = box.volume();
  norm_ += double(n * m) * double((n - 1) * m) / V;
}

void RadialHistogram::end_block() {
  if (norm_ == 0.0) return;
  std::vector<double> g(counts_.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double shell = 4.0 / 3.0 * std::numbers::pi * (std::pow(edges_[k + 1], 3) - std::pow(edges_[k], 3));
    g[k] = counts_[k] / (norm_ * shell);
    total_counts_[k] += counts_[k];
    counts_[k] = 0.0;
  }
  block_g_.push_back(std::move(g));
  norm_ = 0.0;
}

std::vector<double> RadialHistogram::block_values(int k) const {
  std::vector<double> v;
  v.reserve(block_g_.size());
  for (const auto& b : block_g_) v.push_back(b[std::size_t(k)]);
  return v;
}

double RadialHistogram::total_count(int k) const {
  return total_counts_[std::size_t(k)];
}

void RadialHistogram::append_blocks(const RadialHistogram& other) {
  if (other.points_ != points_ || other.edges_.size() != edges_.size() ||
      std::abs(other.width_ - width_) > 1e-12)
    throw Error("g(r): cannot append the blocks of a histogram with other bins");
  for (const auto& b : other.block_g_) block_g_.push_back(b);
  for (std::size_t k = 0; k < total_counts_.size(); ++k) total_counts_[k] += other.total_counts_[k];
}

RadialHistogram RadialHistogram::rebinned(int factor) const {
  if (factor < 1 || bins() / factor < 1) throw Error("g(r): cannot merge bins by " + std::to_string(factor));
  const int n = bins() / factor;
  RadialHistogram out(points_, width_ * factor, edges_[std::size_t(n * factor)]);
  for (const auto& b : block_g_) {
    std::vector<double> g(std::size_t(n), 0.0);
    for (int j = 0; j < n; ++j) {
      double sum = 0.0, volume = 0.0;
      for (int k = j * factor; k < (j + 1) * factor; ++k) {
        const double shell = std::pow(edges_[std::size_t(k) + 1], 3) - std::pow(edges_[std::size_t(k)], 3);
        sum += b[std::size_t(k)] * shell;
        volume += shell;
      }
      g[std::size_t(j)] = sum / volume;
    }
    out.block_g_.push_back(std::move(g));
  }
  for (int j = 0; j < n; ++j)
    for (int k = j * factor; k < (j + 1) * factor; ++k)
      out.total_counts_[std::size_t(j)] += total_counts_[std::size_t(k)];
  return out;
}

std::vector<double> RadialHistogram::shell_block_values(double r_from, double r_to) const {
  // Volume-weighted: the g of the union of the bins, sum g_k V_k / sum V_k.
  std::vector<double> v;
  for (const auto& b : block_g_) {
    double sum = 0.0, volume = 0.0;
    for (int k = 0; k < bins(); ++k) {
      const double lo = edges_[std::size_t(k)], hi = edges_[std::size_t(k) + 1];
      if (lo < r_from - 1e-9 || lo >= r_to - 1e-9) continue;
      const double shell = hi * hi * hi - lo * lo * lo;
      sum += b[std::size_t(k)] * shell;
      volume += shell;
    }
    v.push_back(volume > 0.0 ? sum / volume : 0.0);
  }
  return v;
}

}  // namespace fldsim::oracle
