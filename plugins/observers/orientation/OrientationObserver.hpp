// Observer `orientation`: P(theta), P(phi), P(theta, phi), theta_m, phi_m, their deviations from
// isotropy, the order parameters S_ii and the order tensor with its principal axes.
#pragma once

#include <string>
#include <vector>

#include "OrientationStatistics.hpp"
#include "fldsim/observer.hpp"

namespace fldsim::observers {

struct OrientationConfig {
  int theta_bins = 18;
  int phi_bins = 36;
};

class OrientationObserver : public Observer {
 public:
  explicit OrientationObserver(OrientationConfig config);
  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;
  void finish(const RunInfo& run, ResultSink& out) override;
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& state) override;

  const OrientationStatistics& statistics() const { return stats_; }
  bool skipped() const { return skipped_; }

 private:
  void write_decorrelation_time(const RunInfo& run, ResultSink& out) const;
  OrientationConfig config_;
  OrientationStatistics stats_;
  std::vector<Vec3> directors_;
  bool skipped_ = false;
};

}  // namespace fldsim::observers
