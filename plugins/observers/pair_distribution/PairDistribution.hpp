// Pair distribution of body centres: radial g(r) and projected maps g(x, y) (and optionally
// g(x, z), g(y, z)) averaged over a slab of the third coordinate, |z| < h:
//   g(x, y) = (1 / 2h) int_{-h}^{h} g(x, y, z) dz       (Kumar & Higdon §3.1, h = a)
// Normalisation: a count in a cell of volume dV (area times 2h for a map, a spherical shell
// for g(r)) is divided by samples * N * n dV with n = (N - 1) / V, the expected count of an
// uncorrelated (ideal-gas) suspension of N bodies, so that g = 1 without correlations.
// Separations are Lees–Edwards minimum images; the range must not exceed L/2.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "fldsim/box.hpp"
#include "fldsim/observer_state.hpp"

namespace fldsim::observers {

enum class Projection { XY = 0, XZ = 1, YZ = 2 };
const char* projection_name(Projection p);  // "xy", "xz", "yz"

struct PairDistributionConfig {
  double range = 5.0;      // a; the maps cover [-range, range]^2, g(r) covers [0, range)
  int bins = 100;          // map cells per axis; g(r) uses bins/2 shells (same resolution)
  double slab_half = 1.0;  // h, a
  std::vector<Projection> projections{Projection::XY};
};

class PairDistribution {
 public:
  explicit PairDistribution(PairDistributionConfig config);

  // Throws std::invalid_argument when range or slab exceed half the box edge.
  void check_box(const LeesEdwardsBox& box) const;
  void add_sample(const std::vector<Vec3>& positions, const LeesEdwardsBox& box);
  // Checkpoint state (exact restart); restore needs the same bins and projections.
  void save(StateWriter& w) const;
  void restore(StateReader& r);

  const PairDistributionConfig& config() const { return config_; }
  int map_bins() const { return config_.bins; }
  int radial_bins() const { return radial_bins_; }
  double map_cell() const { return 2.0 * config_.range / config_.bins; }
  double radial_width() const { return config_.range / radial_bins_; }
  std::size_t samples() const { return samples_; }

  std::vector<double> g_r() const;
  std::vector<double> g_r_stderr() const;  // Poisson in the pair count (uncorrelated samples)
  std::vector<double> r_centres() const;
  // Row-major [first axis][second axis] of the projection; empty if not requested.
  std::vector<double> g_map(Projection p) const;
  std::vector<double> g_map_stderr(Projection p) const;
  bool has(Projection p) const { return !maps_[static_cast<int>(p)].empty(); }
  // Raw counts (ordered pairs) for tests.
  const std::vector<double>& radial_counts() const { return radial_; }

 private:
  double radial_norm(int b) const;
  double map_norm() const;
  PairDistributionConfig config_;
  int radial_bins_;
  int threads_;
  std::vector<double> radial_;
  std::array<std::vector<double>, 3> maps_;
  // Per-thread partial histograms, summed after each sample (integer counts: the sum is exact
  // and so independent of the thread count).
  std::vector<std::vector<double>> thread_radial_;
  std::vector<std::array<std::vector<double>, 3>> thread_maps_;
  std::size_t samples_ = 0;
  double norm_density_volume_ = 0.0;  // sum over samples of N * n
};

}  // namespace fldsim::observers
