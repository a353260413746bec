// Observer `pair_distribution`: front-view g(x, y) (and other projections) and g(r) of the
// body centres, accumulated over the samples after `start`.
#pragma once

#include "PairDistribution.hpp"
#include "fldsim/observer.hpp"

namespace fldsim::observers {

class PairDistributionObserver : public Observer {
 public:
  explicit PairDistributionObserver(PairDistributionConfig config) : pd_(std::move(config)) {}
  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;
  void finish(const RunInfo& run, ResultSink& out) override;
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& state) override;
  const PairDistribution& distribution() const { return pd_; }

 private:
  PairDistribution pd_;
};

}  // namespace fldsim::observers
