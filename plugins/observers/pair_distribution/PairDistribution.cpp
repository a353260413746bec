#include "PairDistribution.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fldsim/number_text.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fldsim::observers {

const char* projection_name(Projection p) {
  switch (p) {
    case Projection::XY:
      return "xy";
    case Projection::XZ:
      return "xz";
    case Projection::YZ:
      return "yz";
  }
  return "?";
}

namespace {
// In-plane axes and the slab axis of each projection.
constexpr int kAxes[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};
}  // namespace

PairDistribution::PairDistribution(PairDistributionConfig config)
    : config_(std::move(config)), radial_bins_(std::max(1, config_.bins / 2)) {
#ifdef _OPENMP
  threads_ = omp_get_max_threads();
#else
  threads_ = 1;
#endif
  const std::size_t cells = static_cast<std::size_t>(config_.bins) * config_.bins;
  radial_.assign(radial_bins_, 0.0);
  for (Projection p : config_.projections) maps_[static_cast<int>(p)].assign(cells, 0.0);
  thread_radial_.assign(threads_, std::vector<double>(radial_bins_, 0.0));
  thread_maps_.resize(threads_);
  for (auto& tm : thread_maps_)
    for (int p = 0; p < 3; ++p)
      if (!maps_[p].empty()) tm[p].assign(cells, 0.0);
}

void PairDistribution::check_box(const LeesEdwardsBox& box) const {
  if (config_.range > 0.5 * box.edge() + 1e-12 || config_.slab_half > 0.5 * box.edge() + 1e-12)
    throw std::invalid_argument("pair_distribution: range " + number_text(config_.range) + " and slab " +
                                number_text(config_.slab_half) + " must not exceed half the box edge " +
                                number_text(0.5 * box.edge()));
}

void PairDistribution::add_sample(const std::vector<Vec3>& positions, const LeesEdwardsBox& box) {
  const long n = static_cast<long>(positions.size());
  if (n < 2) return;
  const double range = config_.range, h = config_.slab_half, cell = map_cell(), dr = radial_width();
  const int nb = config_.bins;

#pragma omp parallel num_threads(threads_)
  {
#ifdef _OPENMP
    const int tid = omp_get_thread_num();
#else
    const int tid = 0;
#endif
    auto& rad = thread_radial_[tid];
    auto& maps = thread_maps_[tid];
#pragma omp for schedule(dynamic, 16)
    for (long i = 0; i < n; ++i) {
      for (long j = i + 1; j < n; ++j) {
        const Vec3 r = box.minimum_image(positions[j] - positions[i]);
        const double d = r.norm();
        if (d < range) rad[static_cast<int>(d / dr)] += 2.0;  // ordered pairs i->j and j->i
        for (int p = 0; p < 3; ++p) {
          if (maps[p].empty()) continue;
          const double u = r[kAxes[p][0]], v = r[kAxes[p][1]], w = r[kAxes[p][2]];
          if (std::abs(w) >= h || std::abs(u) >= range || std::abs(v) >= range) continue;
          const int bu = std::min(nb - 1, static_cast<int>((u + range) / cell));
          const int bv = std::min(nb - 1, static_cast<int>((v + range) / cell));
          const int cu = std::min(nb - 1, static_cast<int>((-u + range) / cell));
          const int cv = std::min(nb - 1, static_cast<int>((-v + range) / cell));
          maps[p][static_cast<std::size_t>(bu) * nb + bv] += 1.0;  // seen from i
          maps[p][static_cast<std::size_t>(cu) * nb + cv] += 1.0;  // seen from j
        }
      }
    }
  }
  // Reduce in thread order and clear the partial histograms for the next sample.
  for (int t = 0; t < threads_; ++t) {
    for (int b = 0; b < radial_bins_; ++b) {
      radial_[b] += thread_radial_[t][b];
      thread_radial_[t][b] = 0.0;
    }
    for (int p = 0; p < 3; ++p)
      for (std::size_t k = 0; k < maps_[p].size(); ++k) {
        maps_[p][k] += thread_maps_[t][p][k];
        thread_maps_[t][p][k] = 0.0;
      }
  }
  ++samples_;
  norm_density_volume_ += static_cast<double>(n) * static_cast<double>(n - 1) / box.volume();
}

double PairDistribution::radial_norm(int b) const {
  const double r0 = b * radial_width(), r1 = (b + 1) * radial_width();
  return norm_density_volume_ * 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 - r0 * r0 * r0);
}

double PairDistribution::map_norm() const {
  return norm_density_volume_ * map_cell() * map_cell() * 2.0 * config_.slab_half;
}

std::vector<double> PairDistribution::g_r() const {
  std::vector<double> g(radial_bins_);
  for (int b = 0; b < radial_bins_; ++b) g[b] = radial_[b] / radial_norm(b);
  return g;
}

std::vector<double> PairDistribution::g_r_stderr() const {
  std::vector<double> e(radial_bins_);
  // Each unordered pair adds 2 to the count: Var(count) = 4 * pairs = 2 * count (Poisson pairs).
  for (int b = 0; b < radial_bins_; ++b) e[b] = std::sqrt(2.0 * radial_[b]) / radial_norm(b);
  return e;
}

std::vector<double> PairDistribution::r_centres() const {
  std::vector<double> r(radial_bins_);
  for (int b = 0; b < radial_bins_; ++b) r[b] = (b + 0.5) * radial_width();
  return r;
}

std::vector<double> PairDistribution::g_map(Projection p) const {
  std::vector<double> g(maps_[static_cast<int>(p)]);
  const double norm = map_norm();
  for (double& v : g) v /= norm;
  return g;
}

std::vector<double> PairDistribution::g_map_stderr(Projection p) const {
  std::vector<double> g(maps_[static_cast<int>(p)]);
  const double norm = map_norm();
  for (double& v : g) v = std::sqrt(v) / norm;
  return g;
}

void PairDistribution::save(StateWriter& w) const {
  w.put(radial_);
  for (const auto& m : maps_) w.put(m);
  w.put(double(samples_)).put(norm_density_volume_);
}

void PairDistribution::restore(StateReader& r) {
  r.get_into(radial_);
  for (auto& m : maps_) r.get_into(m);
  samples_ = std::size_t(r.get());
  norm_density_volume_ = r.get();
}

}  // namespace fldsim::observers
