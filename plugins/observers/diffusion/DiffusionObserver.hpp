// Observer `diffusion`: shear-corrected and total mean square displacements per axis, director
// autocorrelations, and the self-diffusivities and rotational diffusivity derived from them
// (definitions in DiffusionStatistics.hpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "DiffusionStatistics.hpp"
#include "fldsim/observer.hpp"

namespace fldsim::observers {

struct DiffusionConfig {
  double max_lag = 10.0;  // largest lag, in the run's user time unit
  int lags = 20;          // log-spaced lags
  int origins = 20;       // time origins held in memory at once
};

class DiffusionObserver : public Observer {
 public:
  explicit DiffusionObserver(DiffusionConfig config) : config_(config) {}
  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;
  void finish(const RunInfo& run, ResultSink& out) override;
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& state) override;
  const DiffusionStatistics* statistics() const { return stats_.get(); }

 private:
  DiffusionConfig config_;
  std::unique_ptr<DiffusionStatistics> stats_;
  std::vector<Vec3> directors_;
  bool anisotropic_ = true;
  std::string time_unit_ = "a^2/D0";  // the run's time unit (RunInfo::time_unit)
  double time_scale_ = 1.0;           // internal time per run time unit
};

}  // namespace fldsim::observers
