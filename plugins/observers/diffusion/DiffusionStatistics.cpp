#include "DiffusionStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fldsim/error.hpp"

namespace fldsim::observers {

std::vector<std::int64_t> DiffusionStatistics::log_spaced_lags(std::int64_t max_units, int count,
                                                               std::int64_t unit) {
  std::vector<std::int64_t> lags;
  max_units = std::max<std::int64_t>(1, max_units);
  for (int k = 0; k < count; ++k) {
    const double f = count > 1 ? static_cast<double>(k) / (count - 1) : 1.0;
    const auto u = static_cast<std::int64_t>(std::llround(std::pow(static_cast<double>(max_units), f)));
    if (lags.empty() || u * unit > lags.back()) lags.push_back(u * unit);
  }
  return lags;
}

DiffusionStatistics::DiffusionStatistics(std::vector<std::int64_t> lag_steps, std::int64_t origin_spacing,
                                         double dt, std::size_t bodies)
    : lag_steps_(std::move(lag_steps)), spacing_(std::max<std::int64_t>(1, origin_spacing)), dt_(dt) {
  if (lag_steps_.empty() || lag_steps_.front() <= 0 || !std::is_sorted(lag_steps_.begin(), lag_steps_.end()))
    throw std::invalid_argument("diffusion: lags must be positive and increasing");
  const std::size_t slots = static_cast<std::size_t>(lag_steps_.back() / spacing_ + 2);
  origins_.resize(slots);
  // Zeros, not Eigen's uninitialised default: inactive origins are saved in checkpoints too, and
  // garbage there made two checkpoints of the same state differ (found by the resume test).
  for (auto& o : origins_) {
    o.nonaffine.assign(bodies, Vec3::Zero());
    o.total.assign(bodies, Vec3::Zero());
    o.directors.assign(bodies, Vec3::Zero());
    o.values.resize(lag_steps_.size());
  }
  msd_na_.resize(lags());
  msd_tot_.resize(lags());
  c1_.resize(lags());
  c2_.resize(lags());
}

void DiffusionStatistics::add_sample(std::int64_t step, const std::vector<Vec3>& nonaffine,
                                     const std::vector<Vec3>& total, const std::vector<Vec3>& directors) {
  const std::size_t n = nonaffine.size();
  const double inv_n = 1.0 / static_cast<double>(n);
  for (auto& o : origins_) {
    if (!o.active) continue;
    const std::int64_t lag = step - o.step;
    const auto it = std::lower_bound(lag_steps_.begin(), lag_steps_.end(), lag);
    if (it == lag_steps_.end() || *it != lag) continue;
    const std::size_t j = static_cast<std::size_t>(it - lag_steps_.begin());
    std::array<double, 8> v{};
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 dn = nonaffine[i] - o.nonaffine[i];
      const Vec3 dt = total[i] - o.total[i];
      for (int a = 0; a < 3; ++a) {
        v[a] += dn[a] * dn[a];
        v[3 + a] += dt[a] * dt[a];
      }
      const double c = directors[i].dot(o.directors[i]);
      v[6] += c;
      v[7] += 1.5 * c * c - 0.5;
    }
    for (double& x : v) x *= inv_n;
    o.values[j] = v;
    if (j + 1 == lags()) {  // complete: every lag of this origin is known
      for (std::size_t k = 0; k < lags(); ++k) {
        for (int a = 0; a < 3; ++a) {
          msd_na_[k][a].add(o.values[k][a]);
          msd_tot_[k][a].add(o.values[k][3 + a]);
        }
        c1_[k].add(o.values[k][6]);
        c2_[k].add(o.values[k][7]);
      }
      o.active = false;
    }
  }
  if (!any_origin_ || step - last_origin_step_ >= spacing_) {
    for (auto& o : origins_) {
      if (o.active) continue;
      o.active = true;
      o.step = step;
      std::copy(nonaffine.begin(), nonaffine.end(), o.nonaffine.begin());
      std::copy(total.begin(), total.end(), o.total.begin());
      for (std::size_t i = 0; i < n; ++i) o.directors[i] = directors[i].normalized();
      last_origin_step_ = step;
      any_origin_ = true;
      break;
    }
  }
}

BlockAverage DiffusionStatistics::d_short(int axis) const {
  BlockAverage b;
  const double t = lag_time(0);
  for (double m : msd_na_[0][axis].samples()) b.add(m / (2.0 * t));
  return b;
}

std::size_t DiffusionStatistics::long_lag_start() const {
  const double half = 0.5 * lag_time(lags() - 1);
  std::size_t best = 0;
  for (std::size_t j = 0; j + 1 < lags(); ++j)
    if (std::abs(lag_time(j) - half) < std::abs(lag_time(best) - half)) best = j;
  return best;
}

BlockAverage DiffusionStatistics::d_long(int axis) const {
  BlockAverage b;
  const std::size_t j0 = long_lag_start(), j1 = lags() - 1;
  const double dt = lag_time(j1) - lag_time(j0);
  if (j1 == j0) return b;
  const auto& s0 = msd_na_[j0][axis].samples();
  const auto& s1 = msd_na_[j1][axis].samples();
  for (std::size_t k = 0; k < s0.size(); ++k) b.add((s1[k] - s0[k]) / (2.0 * dt));
  return b;
}

BlockAverage DiffusionStatistics::d_rot(int l, double floor) const {
  const auto& c = l == 1 ? c1_ : c2_;
  const double rate = l * (l + 1.0);
  std::vector<std::size_t> use;
  for (std::size_t j = 0; j < lags(); ++j)
    if (c[j].count() > 0 && c[j].mean() > floor) use.push_back(j);
  BlockAverage b;
  if (use.empty()) return b;
  // Per origin: D_r = -sum t ln C / (rate sum t^2), the least-squares slope through the origin.
  for (std::size_t k = 0; k < c[0].count(); ++k) {
    double st = 0.0, stt = 0.0;
    for (std::size_t j : use) {
      const double v = c[j].samples()[k];
      if (v <= 0.0) continue;
      st += lag_time(j) * std::log(v);
      stt += lag_time(j) * lag_time(j);
    }
    if (stt > 0.0) b.add(-st / (rate * stt));
  }
  return b;
}

namespace {
void put_vec3s(StateWriter& w, const std::vector<Vec3>& v) {
  w.put(double(v.size()));
  for (const Vec3& x : v) w.put(x[0]).put(x[1]).put(x[2]);
}
void get_vec3s(StateReader& r, std::vector<Vec3>& v) {
  if (std::size_t(r.get()) != v.size())
    throw Error("checkpoint state of observer diffusion has another body count");
  for (Vec3& x : v)
    for (int c = 0; c < 3; ++c) x[c] = r.get();  // in order (function arguments are not)
}
}  // namespace

void DiffusionStatistics::save(StateWriter& w) const {
  w.put(double(origins_.size())).put(double(lag_steps_.size()));
  for (const Origin& o : origins_) {
    w.put(o.active ? 1.0 : 0.0).put(double(o.step));
    put_vec3s(w, o.nonaffine);
    put_vec3s(w, o.total);
    put_vec3s(w, o.directors);
    for (const auto& v : o.values)
      for (double x : v) w.put(x);
  }
  w.put(double(last_origin_step_)).put(any_origin_ ? 1.0 : 0.0);
  for (std::size_t j = 0; j < lag_steps_.size(); ++j) {
    for (int a = 0; a < 3; ++a) {
      msd_na_[j][a].save(w);
      msd_tot_[j][a].save(w);
    }
    c1_[j].save(w);
    c2_[j].save(w);
  }
}

void DiffusionStatistics::restore(StateReader& r) {
  if (std::size_t(r.get()) != origins_.size() || std::size_t(r.get()) != lag_steps_.size())
    throw Error(
        "checkpoint state of observer diffusion has other lags or origins (were its parameters changed?)");
  for (Origin& o : origins_) {
    o.active = r.get() != 0.0;
    o.step = std::int64_t(r.get());
    get_vec3s(r, o.nonaffine);
    get_vec3s(r, o.total);
    get_vec3s(r, o.directors);
    for (auto& v : o.values)
      for (double& x : v) x = r.get();
  }
  last_origin_step_ = std::int64_t(r.get());
  any_origin_ = r.get() != 0.0;
  for (std::size_t j = 0; j < lag_steps_.size(); ++j) {
    for (int a = 0; a < 3; ++a) {
      msd_na_[j][a].restore(r);
      msd_tot_[j][a].restore(r);
    }
    c1_[j].restore(r);
    c2_[j].restore(r);
  }
}

}  // namespace fldsim::observers
