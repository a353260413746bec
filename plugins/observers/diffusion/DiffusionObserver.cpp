#include "DiffusionObserver.hpp"

#include <cmath>
#include <iostream>
#include <string>

#include "fldsim-sdk/statistics/ObserverOutput.hpp"
#include "fldsim/error.hpp"
#include "fldsim/number_text.hpp"

namespace fldsim::observers {

void DiffusionObserver::begin(const System& system, const RunInfo& run, ResultSink& out) {
  const std::int64_t every = std::max<std::int64_t>(1, this->every());
  time_unit_ = run.time_unit;
  time_scale_ = run.time_scale > 0.0 ? run.time_scale : 1.0;
  const double max_lag = config_.max_lag * run.time_scale;  // internal time
  const auto max_samples = std::max<std::int64_t>(1, std::llround(max_lag / (every * run.dt)));
  auto lags = DiffusionStatistics::log_spaced_lags(max_samples, config_.lags, every);
  const std::int64_t spacing =
      every * std::max<std::int64_t>(1, (max_samples + config_.origins - 1) / std::max(1, config_.origins));
  stats_ = std::make_unique<DiffusionStatistics>(std::move(lags), spacing, run.dt, system.size());
  directors_.resize(system.size());
  anisotropic_ = system.shape().anisotropic();
  if (max_samples * every > run.total_steps)
    std::clog << "diffusion: max_lag exceeds the run; no origin will complete\n";
  out.write_attribute("results/diffusion", "origin_spacing_steps", std::to_string(spacing));
}

void DiffusionObserver::sample(const StepView& view, ResultSink& out) {
  const System& s = view.system;
  for (std::size_t i = 0; i < s.size(); ++i) directors_[i] = s.director(i);
  stats_->add_sample(s.step(), s.nonaffine_displacement(), s.displacement(), directors_);
  // Running MSD since the start of the run, per axis (shear-corrected).
  double msd[3] = {0.0, 0.0, 0.0};
  for (const Vec3& d : s.nonaffine_displacement())
    for (int a = 0; a < 3; ++a) msd[a] += d[a] * d[a];
  for (double& m : msd) m /= static_cast<double>(std::max<std::size_t>(1, s.size()));
  out.append_sample("timeseries/diffusion/msd_nonaffine_since_start", s.step(), s.time(), {3}, msd, "a^2");
}

void DiffusionObserver::finish(const RunInfo&, ResultSink& out) {
  const std::string r = "results/diffusion/";
  if (!stats_ || stats_->completed_origins() == 0) {
    out.write_attribute("results/diffusion", "skipped", "no time origin reached max_lag");
    return;
  }
  const DiffusionStatistics& st = *stats_;
  const std::size_t L = st.lags();
  std::vector<double> t(L), na(3 * L), na_e(3 * L), tot(3 * L), tot_e(3 * L), c1(L), c1e(L), c2(L), c2e(L);
  for (std::size_t j = 0; j < L; ++j) {
    t[j] = st.lag_time(j) / time_scale_;  // in the run's time unit, like max_lag
    for (int a = 0; a < 3; ++a) {
      na[3 * j + a] = st.msd_nonaffine(j, a).mean();
      na_e[3 * j + a] = st.msd_nonaffine(j, a).stderr_mean();
      tot[3 * j + a] = st.msd_total(j, a).mean();
      tot_e[3 * j + a] = st.msd_total(j, a).stderr_mean();
    }
    c1[j] = st.c1(j).mean();
    c1e[j] = st.c1(j).stderr_mean();
    c2[j] = st.c2(j).mean();
    c2e[j] = st.c2(j).stderr_mean();
  }
  // Lag times in the run's time unit (as max_lag was given); MSDs stay in a^2 and the
  // diffusivities in D0 = a^2/(a^2/D0) whatever that unit, so they compare across Pe.
  write_vector(out, r + "lag_time", t, time_unit_, "lag times, in the run's time unit (" + time_unit_ + ")");
  out.write_attribute("results/diffusion", "time_unit", time_unit_);
  out.write_attribute("results/diffusion", "time_scale",
                      number_text(time_scale_) + " a^2/D0 per " + time_unit_);
  out.write_array(r + "msd_nonaffine", {L, 3}, na.data(), "a^2", "shear-corrected MSD per axis (x, y, z)");
  out.write_array(r + "msd_nonaffine_stderr", {L, 3}, na_e.data(), "a^2", "SE by blocking over origins");
  out.write_array(r + "msd_total", {L, 3}, tot.data(), "a^2", "MSD of the total displacement per axis");
  out.write_array(r + "msd_total_stderr", {L, 3}, tot_e.data(), "a^2", "SE by blocking over origins");
  const char* axes = "xyz";
  for (int a = 0; a < 3; ++a) {
    write_blocked(out, r + "D_short_" + axes[a], st.d_short(a), "D0",
                  "short-time self-diffusivity MSD/(2t) at the first lag, shear-corrected");
    if (L > 1)
      write_blocked(out, r + "D_long_" + axes[a], st.d_long(a), "D0",
                    "long-time self-diffusivity, half the MSD slope over the upper half of the lags");
  }
  if (anisotropic_) {
    write_vector(out, r + "C1", c1, "1", "<n(t).n(0)>");
    write_vector(out, r + "C1_stderr", c1e, "1", "SE by blocking over origins");
    write_vector(out, r + "C2", c2, "1", "<P2(n(t).n(0))>");
    write_vector(out, r + "C2_stderr", c2e, "1", "SE by blocking over origins");
    const BlockAverage d1 = st.d_rot(1), d2 = st.d_rot(2);
    if (d1.count() > 0)
      write_blocked(out, r + "D_r", d1, "D0/a^2", "rotational diffusivity from C1 = exp(-2 D_r t)");
    if (d2.count() > 0)
      write_blocked(out, r + "D_r_P2", d2, "D0/a^2", "rotational diffusivity from C2 = exp(-6 D_r t)");
  }
}

std::vector<double> DiffusionObserver::save_state() const {
  StateWriter w;
  w.put(stats_ ? 1.0 : 0.0);
  if (stats_) stats_->save(w);
  return w.take();
}

void DiffusionObserver::restore_state(const std::vector<double>& state) {
  StateReader r(state, "diffusion");
  const bool had = r.get() != 0.0;
  if (had != bool(stats_))
    throw Error("checkpoint state of observer diffusion does not match this run (was it skipped then?)");
  if (stats_) stats_->restore(r);
  r.finish();
}

}  // namespace fldsim::observers
