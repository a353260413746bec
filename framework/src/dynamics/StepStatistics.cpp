#include "dynamics/StepStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fldsim/error.hpp"

namespace fldsim {

void StepStatistics::accepted(double dt, double min_gap, double time_at_end, double mean_square_step) {
  if (std::isfinite(mean_square_step)) {
    node_step_sum_ += mean_square_step;
    ++node_steps_;
  }
  if (accepted_ == 0 || dt < min_dt_) min_dt_ = dt;
  if (accepted_ == 0 || dt > max_dt_) max_dt_ = dt;
  ++accepted_;
  sum_dt_ += dt;
  const int bin = int(std::floor((std::log10(dt) - kLowestDecade) * kBinsPerDecade));
  ++histogram_[std::size_t(std::clamp(bin, 0, kBins - 1))];
  if (min_gap < min_gap_) {
    min_gap_ = min_gap;
    min_gap_time_ = time_at_end;
  }
}

std::int64_t StepStatistics::rejected_attempts() const {
  std::int64_t n = 0;
  for (auto r : rejected_) n += r;
  return n;
}

double StepStatistics::dt_quantile(double q) const {
  if (accepted_ == 0) return 0.0;
  const double target = q * double(accepted_);
  double seen = 0.0;
  for (int b = 0; b < kBins; ++b) {
    seen += double(histogram_[std::size_t(b)]);
    if (seen >= target && histogram_[std::size_t(b)] > 0) {
      const double centre = std::pow(10.0, kLowestDecade + (b + 0.5) / kBinsPerDecade);
      return std::clamp(centre, min_dt_, max_dt_);
    }
  }
  return max_dt_;
}

double StepStatistics::rms_node_step() const {
  return node_steps_ ? std::sqrt(node_step_sum_ / double(node_steps_)) : 0.0;
}

double StepStatistics::rms_gap_step() const {
  return gap_pairs_ ? std::sqrt(gap_step_sum_ / double(gap_pairs_)) : 0.0;
}

std::string StepStatistics::text(double time_scale, const std::string& unit) const {
  std::ostringstream s;
  s.precision(3);
  s << accepted_ << " steps, dt mean " << mean_dt() / time_scale
    << " (5/50/95 %: " << dt_quantile(0.05) / time_scale << " / " << dt_quantile(0.5) / time_scale << " / "
    << dt_quantile(0.95) / time_scale << ", min " << min_dt_ / time_scale << ") " << unit << "; rejected "
    << rejected_attempts();
  if (rejected_attempts() > 0) {
    s << " (";
    const char* sep = "";
    for (int r = 0; r < kRejectionKinds; ++r)
      if (rejected_[std::size_t(r)] > 0) {
        s << sep << to_string(Rejection(r)) << " " << rejected_[std::size_t(r)];
        sep = ", ";
      }
    s << ")";
  }
  if (accepted_ > 0)
    s << "; smallest gap " << min_gap_ << " a at t = " << min_gap_time_ / time_scale << " " << unit;
  if (node_steps_ > 0) s << "; rms node step " << rms_node_step() << " a";
  if (gap_pairs_ > 0)
    s << "; rms gap step " << rms_gap_step() << " a (" << double(gap_pairs_) / double(accepted_)
      << " near pairs per step)";
  return s.str();
}

void StepStatistics::write(ResultSink& sink, double time_scale, const std::string& unit) const {
  const double nan = std::nan("");
  sink.write_scalar("/results/steps/accepted", double(accepted_), nan, "", "accepted time steps");
  sink.write_scalar("/results/steps/rejected", double(rejected_attempts()), nan, "",
                    "rejected step attempts, all causes (each retried on a shorter step)");
  for (int r = 0; r < kRejectionKinds; ++r)
    sink.write_scalar("/results/steps/rejected_" + std::string(to_string(Rejection(r))),
                      double(rejected_[std::size_t(r)]), nan, "",
                      "rejected step attempts: " + std::string(to_string(Rejection(r))));
  sink.write_scalar("/results/steps/dt_mean", mean_dt() / time_scale, nan, unit, "mean accepted step");
  sink.write_scalar("/results/steps/dt_min", min_dt_ / time_scale, nan, unit, "shortest accepted step");
  sink.write_scalar("/results/steps/dt_max", max_dt_ / time_scale, nan, unit, "longest accepted step");
  for (const auto& [name, q] : {std::pair{"dt_p05", 0.05}, {"dt_p50", 0.5}, {"dt_p95", 0.95}})
    sink.write_scalar(std::string("/results/steps/") + name, dt_quantile(q) / time_scale, nan, unit,
                      "quantile of the accepted steps (histogram bin centre, 8 bins per decade)");
  if (node_steps_ > 0)
    sink.write_scalar("/results/steps/rms_node_step", rms_node_step(), nan, "a",
                      "root mean square over steps and nodes of a step's node displacement relative to the "
                      "imposed flow (what run.displacement bounds)");
  if (gap_pairs_ > 0) {
    sink.write_scalar(
        "/results/steps/rms_gap_step", rms_gap_step(), nan, "a",
        "root mean square over steps and near node pairs (gap below run.gap_range) of the change "
        "of a pair's surface gap in one step, the imposed flow's normal displacement of the pair "
        "added in quadrature (what run.gap_step bounds)");
    sink.write_scalar("/results/steps/near_pairs", double(gap_pairs_) / double(accepted_), nan, "",
                      "near node pairs per accepted step (those run.gap_step measures)");
  }
  if (accepted_ > 0)
    sink.write_scalar("/results/steps/min_gap", min_gap_, nan, "a",
                      "smallest node surface gap at the end of an accepted step (negative: overlap)");
  // The histogram: counts per log10 bin; edges in the run's time unit.
  std::vector<double> edges(kBins + 1), counts(kBins);
  for (int b = 0; b <= kBins; ++b)
    edges[std::size_t(b)] = std::pow(10.0, kLowestDecade + double(b) / kBinsPerDecade) / time_scale;
  for (int b = 0; b < kBins; ++b) counts[std::size_t(b)] = double(histogram_[std::size_t(b)]);
  sink.write_array("/steps/dt_histogram/counts", {std::size_t(kBins)}, counts.data(), "",
                   "accepted steps per dt bin");
  sink.write_array("/steps/dt_histogram/edges", {std::size_t(kBins + 1)}, edges.data(), unit,
                   "dt bin edges (8 per decade)");
}

std::vector<double> StepStatistics::save() const {
  std::vector<double> v{double(accepted_), sum_dt_, min_dt_, max_dt_, min_gap_, min_gap_time_};
  for (auto r : rejected_) v.push_back(double(r));
  for (auto h : histogram_) v.push_back(double(h));
  v.push_back(node_step_sum_);
  v.push_back(double(node_steps_));
  return v;
}

void StepStatistics::restore(const std::vector<double>& v) {
  if (v.size() != kSavedValues && v.size() != kSavedValuesBefore)
    throw Error("step statistics in the checkpoint have " + std::to_string(v.size()) + " values, expected " +
                std::to_string(kSavedValues) + " (or " + std::to_string(kSavedValuesBefore) +
                " from an earlier build)");
  accepted_ = std::int64_t(v[0]);
  sum_dt_ = v[1];
  min_dt_ = v[2];
  max_dt_ = v[3];
  min_gap_ = v[4];
  min_gap_time_ = v[5];
  for (int r = 0; r < kRejectionKinds; ++r) rejected_[std::size_t(r)] = std::int64_t(v[std::size_t(6 + r)]);
  for (int b = 0; b < kBins; ++b)
    histogram_[std::size_t(b)] = std::int64_t(v[std::size_t(6 + kRejectionKinds + b)]);
  node_step_sum_ = v.size() == kSavedValues ? v[kSavedValues - 2] : 0.0;
  node_steps_ = v.size() == kSavedValues ? std::int64_t(v[kSavedValues - 1]) : 0;
}

}  // namespace fldsim
