// Mean square displacements and director autocorrelations at log-spaced lags from multiple
// time origins, with bounded memory: an origin (a copy of the displacements and directors) is
// stored every `origin_spacing` steps and released once it has reached the largest lag, so at
// most max_lag / origin_spacing + 1 origins are held. Each completed origin gives one sample
// of every lag's MSD (averaged over bodies); successive origins are correlated when the lag
// exceeds their spacing, which the blocking analysis of the origin series accounts for.
// Origins still open at the end of the run are dropped.
//   MSD_a(t)    = <(d_a(t0 + t) - d_a(t0))^2>, per axis a, d = nonaffine (shear-corrected) or total
//   C1(t)       = <n(t0 + t) . n(t0)>                 = exp(-2 D_r t)  for rotational diffusion
//   C2(t)       = <P2(n(t0 + t) . n(t0))>             = exp(-6 D_r t)  (Berne & Pecora 1976)
//   D_a(short)  = MSD_a(t_1) / (2 t_1) at the first lag; D_a(long) = slope/2 of MSD_a between the
//   lag nearest half the largest lag and the largest lag (Einstein: MSD_a = 2 D_a t).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fldsim-sdk/statistics/BlockAverage.hpp"
#include "fldsim/box.hpp"

namespace fldsim::observers {

class DiffusionStatistics {
 public:
  // lag_steps: strictly increasing, > 0; time per step dt; bodies N.
  DiffusionStatistics(std::vector<std::int64_t> lag_steps, std::int64_t origin_spacing, double dt,
                      std::size_t bodies);
  // Log-spaced integer lags (in multiples of `unit` steps) from unit to max_units*unit.
  static std::vector<std::int64_t> log_spaced_lags(std::int64_t max_units, int count, std::int64_t unit);

  void add_sample(std::int64_t step, const std::vector<Vec3>& nonaffine, const std::vector<Vec3>& total,
                  const std::vector<Vec3>& directors);

  std::size_t lags() const { return lag_steps_.size(); }
  double lag_time(std::size_t j) const { return static_cast<double>(lag_steps_[j]) * dt_; }
  std::size_t completed_origins() const { return c1_[0].count(); }
  const BlockAverage& msd_nonaffine(std::size_t j, int axis) const { return msd_na_[j][axis]; }
  const BlockAverage& msd_total(std::size_t j, int axis) const { return msd_tot_[j][axis]; }
  const BlockAverage& c1(std::size_t j) const { return c1_[j]; }
  const BlockAverage& c2(std::size_t j) const { return c2_[j]; }

  // Per-origin estimates (as series, for their mean and blocking SE).
  BlockAverage d_short(int axis) const;
  BlockAverage d_long(int axis) const;
  // D_r from ln C_l(t) = -l(l+1) D_r t, least squares through the origin over the lags where the
  // mean C_l exceeds `floor` (l = 1 or 2).
  BlockAverage d_rot(int l, double floor = 0.1) const;
  std::size_t long_lag_start() const;  // index of the lag nearest half the largest lag
  // Checkpoint state: origins in flight and the per-origin series (restore needs the same lags).
  void save(StateWriter& w) const;
  void restore(StateReader& r);

 private:
  struct Origin {
    bool active = false;
    std::int64_t step = 0;
    std::vector<Vec3> nonaffine, total, directors;
    std::vector<std::array<double, 8>> values;  // per lag: msd_na xyz, msd_tot xyz, C1, C2
  };
  std::vector<std::int64_t> lag_steps_;
  std::int64_t spacing_;
  double dt_;
  std::vector<Origin> origins_;
  std::int64_t last_origin_step_ = 0;
  bool any_origin_ = false;
  std::vector<std::array<BlockAverage, 3>> msd_na_, msd_tot_;
  std::vector<BlockAverage> c1_, c2_;
};

}  // namespace fldsim::observers
