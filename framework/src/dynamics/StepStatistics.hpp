// What the steps of a run were: accepted steps, rejected attempts by cause, the distribution of
// the accepted step lengths (log-spaced histogram), and the smallest node gap seen at the end of
// an accepted step, and the root mean square node displacement per step relative to the imposed
// flow (what run.displacement bounds; docs/time_steps.md), and with run.gap_step the rms gap change
// of near node pairs per step (what it bounds). Kept across --resume (save/restore), written to
// the log, to /results/steps in the result file and so to `fldsim summary`.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/StepControl.hpp"
#include "fldsim/results.hpp"

namespace fldsim {

class StepStatistics {
 public:
  static constexpr int kBinsPerDecade = 8;
  static constexpr int kLowestDecade = -14;  // internal time units
  static constexpr int kBins = 16 * kBinsPerDecade;

  // mean_square_step: TimeIntegrator::mean_square_node_step of the step, a^2.
  void accepted(double dt, double min_gap, double time_at_end, double mean_square_step);
  void rejected(Rejection why) { ++rejected_[std::size_t(why)]; }

  std::int64_t accepted_steps() const { return accepted_; }
  std::int64_t rejected_attempts(Rejection why) const { return rejected_[std::size_t(why)]; }
  std::int64_t rejected_attempts() const;
  double smallest_gap() const { return min_gap_; }
  double smallest_gap_time() const { return min_gap_time_; }
  double mean_dt() const { return accepted_ ? sum_dt_ / double(accepted_) : 0.0; }
  double min_dt() const { return min_dt_; }
  double max_dt() const { return max_dt_; }
  // q-quantile of the accepted step lengths, from the histogram (bin centre, geometric).
  double dt_quantile(double q) const;
  // sqrt of the mean over steps of the mean square node step, a (0 before any step; a checkpoint
  // of an earlier build leaves the steps before it out).
  double rms_node_step() const;
  // With run.gap_step: one step's near pairs, the sum over them of the squared gap change plus
  // the imposed flow's (PairGapSteps), and their count; and the root mean square over all of
  // them, a (0 without any): what run.gap_step bounds.
  void gap_steps(double sum_square, std::size_t pairs) {
    gap_step_sum_ += sum_square;
    gap_pairs_ += std::int64_t(pairs);
  }
  double rms_gap_step() const;
  // Saved after the rest (StepLoop::save_state), so that earlier checkpoints keep their layout.
  std::pair<double, double> gap_step_state() const { return {gap_step_sum_, double(gap_pairs_)}; }
  void restore_gap_steps(double sum_square, double pairs) {
    gap_step_sum_ = sum_square;
    gap_pairs_ = std::int64_t(pairs);
  }

  // One line for the log; times divided by time_scale and shown in `unit`.
  std::string text(double time_scale, const std::string& unit) const;
  // /results/steps/...: counts, dt statistics (in the run's time unit) and the smallest gap.
  void write(ResultSink& sink, double time_scale, const std::string& unit) const;

  static constexpr std::size_t kSavedValues = 8 + kRejectionKinds + kBins;
  static constexpr std::size_t kSavedValuesBefore = 6 + kRejectionKinds + kBins;  // no node steps
  std::vector<double> save() const;
  void restore(const std::vector<double>& state);  // throws fldsim::Error on a wrong size

 private:
  std::int64_t accepted_ = 0;
  std::array<std::int64_t, kRejectionKinds> rejected_{};
  std::array<std::int64_t, kBins> histogram_{};
  double sum_dt_ = 0.0, min_dt_ = 0.0, max_dt_ = 0.0;
  double min_gap_ = 1e300, min_gap_time_ = 0.0;
  double node_step_sum_ = 0.0;  // sum over steps of the mean square node step, a^2
  std::int64_t node_steps_ = 0;
  double gap_step_sum_ = 0.0;  // sum over steps and near pairs of the squared gap change, a^2
  std::int64_t gap_pairs_ = 0;
};

}  // namespace fldsim
