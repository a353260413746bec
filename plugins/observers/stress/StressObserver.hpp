// Observer `stress`: relative viscosity, normal stress differences and particle pressure, each
// split into hydrodynamic, interparticle and Brownian parts (formulas in BulkStress.hpp), and for
// Brownian runs the compressibility factor Z = 1 + Pi_interparticle/(n kT).
#pragma once

#include <string>

#include "BulkStress.hpp"
#include "fldsim-sdk/statistics/BlockAverage.hpp"
#include "fldsim/observer.hpp"

namespace fldsim::observers {

class StressObserver : public Observer {
 public:
  StressObserver() = default;
  ObserverNeeds needs() const override { return {.stress = true, .every_step = false}; }
  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;
  void finish(const RunInfo& run, ResultSink& out) override;
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& state) override;

  // Per-sample series in internal units: [part][quantity], quantity 0..3 = shear, N1, N2, Pi.
  const BlockAverage& series(int part, int quantity) const { return series_[part][quantity]; }
  Eigen::Matrix3d mean_tensor(int part) const;
  // Unit of the raw (internal) stress values: kT/a^3 when Brownian (kT = 1).
  std::string stress_unit() const;

 private:
  double volume_ = 1.0, viscosity_ = 1.0, shear_rate_ = 0.0, kT_ = 0.0;
  std::size_t bodies_ = 0;
  BlockAverage series_[4][4];
  Eigen::Matrix3d sum_[4];
  std::size_t samples_ = 0;
};

}  // namespace fldsim::observers
