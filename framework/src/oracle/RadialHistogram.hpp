// Pair distribution g(r) in blocks, for equilibrium comparisons with block errors per bin.
// Separations are minimum images; every pair is counted for both members (ordered pairs), and a
// bin's count over S samples is divided by S * P * rho * (4/3) pi (r_hi^3 - r_lo^3), with P the
// number of points that count and rho the density of their partners:
//   body centres: P = N,   rho = (N - 1) / V                         (g = 1 without correlations)
//   nodes:        P = N m, rho = (N - 1) m / V   (nodes of other bodies only)
// Samples go into the current block; end_block() closes it. The range must not exceed L/2.
#pragma once

#include <vector>

#include "fldsim/system.hpp"
#include "geometry/LeesEdwardsCellGrid.hpp"
#include "oracle/BlockStatistics.hpp"

namespace fldsim::oracle {

enum class PairPoints { BodyCentres, Nodes };

class RadialHistogram {
 public:
  RadialHistogram(PairPoints points, double bin_width, double r_max);

  // Counts the pairs of s (node positions must be current for PairPoints::Nodes).
  void add_sample(const System& s);
  void end_block();  // closes the current block (ignored if it has no samples)
  // Appends the closed blocks of `other` (same bins), e.g. independent runs as blocks.
  void append_blocks(const RadialHistogram& other);

  PairPoints points() const { return points_; }
  int bins() const { return int(edges_.size()) - 1; }
  double bin_width() const { return width_; }
  double r_max() const { return edges_.back(); }
  double lower_edge(int k) const { return edges_[std::size_t(k)]; }
  int closed_blocks() const { return int(block_g_.size()); }
  // g of bin k in each closed block.
  std::vector<double> block_values(int k) const;
  MeanError g(int k) const { return block_mean(block_values(k)); }
  // Pair counts of bin k over all closed blocks (for a minimum-count rule).
  double total_count(int k) const;
  // The same blocks in bins `factor` times wider (trailing bins that do not fill one are dropped).
  RadialHistogram rebinned(int factor) const;
  // g of the shell made of the bins whose lower edge lies in [r_from, r_to), per block.
  std::vector<double> shell_block_values(double r_from, double r_to) const;

 private:
  PairPoints points_;
  double width_;
  std::vector<double> edges_;
  std::vector<double> counts_;  // current block
  double norm_ = 0.0;           // current block: sum over samples of P * rho
  std::vector<std::vector<double>> block_g_;
  std::vector<double> total_counts_;
  // Scratch of add_sample (kept: no allocation after the first sample).
  geometry::LeesEdwardsCellGrid grid_;
  std::vector<Vec3> wrapped_;
  std::vector<int> head_, next_, cell_;
};

}  // namespace fldsim::oracle
