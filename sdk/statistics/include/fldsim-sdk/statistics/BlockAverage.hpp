// Mean of a correlated time series with its standard error from Flyvbjerg–Petersen blocking
// (H. Flyvbjerg & H. G. Petersen, J. Chem. Phys. 91, 461 (1989)): average neighbouring pairs
// repeatedly; the naive standard error of the block means grows with the block size until the
// blocks are longer than the correlation time, then stays on a plateau, which is the SE.
#pragma once

#include <cstddef>
#include <vector>

#include "fldsim/observer_state.hpp"

namespace fldsim::observers {

struct BlockingLevel {
  std::size_t block_size;  // samples per block
  std::size_t blocks;      // number of blocks
  double stderr_value;     // naive SE of the mean at this level: sqrt(var / (blocks - 1))
  double stderr_error;     // its own error, SE / sqrt(2 (blocks - 1))
};

class BlockAverage {
 public:
  // Levels with fewer blocks than this are too noisy to judge a plateau.
  static constexpr std::size_t kMinBlocks = 16;

  void reserve(std::size_t n) { samples_.reserve(n); }
  void add(double x) { samples_.push_back(x); }
  void clear() { samples_.clear(); }
  std::size_t count() const { return samples_.size(); }
  const std::vector<double>& samples() const { return samples_; }
  // Checkpoint state: the samples themselves (blocking needs the whole series).
  void save(StateWriter& w) const { w.put(samples_); }
  void restore(StateReader& r) {
    const std::vector<double> v = r.get_vector();
    samples_.assign(v.begin(), v.end());
  }

  double mean() const;
  // All blocking levels that keep at least kMinBlocks blocks (level 0 = the raw samples).
  std::vector<BlockingLevel> levels() const;
  // Plateau standard error: the first level whose SE agrees, within the error bar of that
  // level, with the SE of every later level (if the series is too short for a plateau, the
  // largest SE seen, a lower bound; see converged()). NaN for fewer than two samples.
  double stderr_mean() const;
  // False when no plateau was found (the SE is then likely an underestimate).
  bool converged() const;
  // Statistical inefficiency s = n SE^2 / var: the number of consecutive samples that carry the
  // information of one independent sample, 2 tau_int for a slowly decaying autocorrelation
  // (Flyvbjerg & Petersen 1989, eq. 32; Sokal, Monte Carlo methods in statistical mechanics
  // (1996), eq. 2.20). 1 for white noise, a lower bound without a plateau; NaN for < 2 samples
  // or a constant series.
  double correlation_samples() const;

 private:
  std::size_t plateau_level(const std::vector<BlockingLevel>& lv) const;
  std::vector<double> samples_;
};

}  // namespace fldsim::observers
