#include "oracle/MetropolisSampler.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fldsim/error.hpp"
#include "fldsim/random.hpp"
#include "oracle/PeriodicDifference.hpp"

namespace fldsim::oracle {
namespace {

Vec3 uniform_unit_vector(double u1, double u2) {
  const double z = 2.0 * u1 - 1.0, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * std::numbers::pi * u2;
  return Vec3(rho * std::cos(phi), rho * std::sin(phi), z);
}

}  // namespace

double metropolis_acceptance(double beta_dU) {
  return beta_dU <= 0.0 ? 1.0 : std::exp(-beta_dU);
}

MetropolisSampler::MetropolisSampler(System& s, std::vector<const PairEnergy*> energies, double range,
                                     std::uint64_t seed, AcceptanceRule rule)
    : s_(s),
      energies_(std::move(energies)),
      range_(range),
      beta_(s.physics().kT > 0.0 ? 1.0 / s.physics().kT : 0.0),
      seed_(seed),
      rule_(rule),
      m_(s.nodes_per_body()) {
  if (!(s.physics().kT > 0.0)) throw Error("Monte Carlo oracle: needs kT > 0 (a Brownian system)");
  if (s.box().strain() != 0.0) s_.box().set_strain(0.0);  // equilibrium: no Lees-Edwards offset
  if (2.0 * range_ >= s.box().edge())
    throw Error("Monte Carlo oracle: the box edge " + std::to_string(s.box().edge()) +
                " a must exceed twice the energy range " + std::to_string(range_) + " a");
  for (auto& x : s_.positions()) s_.box().wrap(x);
  s_.update_nodes();
  old_x_.resize(m_);
  trial_x_.resize(m_);
  rebuild_cells();
}

void MetropolisSampler::rebuild_cells() {
  const auto& box = s_.box();
  node_x_ = s_.node_positions();
  for (auto& x : node_x_) box.wrap(x);
  use_cells_ = grid_.configure(box, range_);
  if (!use_cells_) return;
  cells_.assign(std::size_t(grid_.cell_count()), {});
  neighbours_.resize(cells_.size());
  neighbour_count_.resize(cells_.size());
  for (std::size_t c = 0; c < cells_.size(); ++c)
    neighbour_count_[c] = grid_.neighbour_cells(int(c), neighbours_[c]);
  node_cell_.resize(node_x_.size());
  for (std::size_t k = 0; k < node_x_.size(); ++k) {
    node_cell_[k] = grid_.cell_of(node_x_[k]);
    cells_[std::size_t(node_cell_[k])].push_back(int(k));
  }
}

double MetropolisSampler::pair_energy(std::size_t body, std::size_t k, const Vec3& xk, std::size_t q) const {
  const std::size_t other = q / m_;
  if (other == body) return 0.0;
  const Vec3 r = periodic_difference(node_x_[q] - xk, s_.box().edge());  // both wrapped, no offset
  const double d = r.norm();
  if (hard_core_ && d < s_.node_radius(k) + s_.node_radius(q % m_)) return INFINITY;
  if (d >= range_) return 0.0;
  // The plugins see the same NodePair as in add(): body_i < body_j, r = x_j - x_i.
  NodePair p;
  if (body < other) {
    p = {std::uint32_t(body), std::uint32_t(other), std::uint16_t(k), std::uint16_t(q % m_), r, d};
  } else {
    p = {std::uint32_t(other), std::uint32_t(body), std::uint16_t(q % m_), std::uint16_t(k), Vec3(-r), d};
  }
  double u = 0.0;
  for (const PairEnergy* e : energies_) u += e->pair_energy(s_, p);
  return u;
}

double MetropolisSampler::body_energy(std::size_t body, const Vec3* x) const {
  double u = 0.0;
  for (std::size_t k = 0; k < m_; ++k) {
    if (!use_cells_) {
      for (std::size_t q = 0; q < node_x_.size(); ++q) u += pair_energy(body, k, x[k], q);
      continue;
    }
    const auto cell = std::size_t(grid_.cell_of(x[k]));
    const auto& cells = neighbours_[cell];
    for (int c = 0; c < neighbour_count_[cell]; ++c)
      for (int q : cells_[std::size_t(cells[std::size_t(c)])])
        u += pair_energy(body, k, x[k], std::size_t(q));
  }
  return beta_ * u;
}

double MetropolisSampler::total_energy() const {
  double u = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) u += body_energy(i, &node_x_[i * m_]);
  return 0.5 * u;  // every pair was counted from both bodies
}

void MetropolisSampler::move_node(std::size_t k, const Vec3& x) {
  node_x_[k] = x;
  if (!use_cells_) return;
  const int c = grid_.cell_of(x);
  if (c == node_cell_[k]) return;
  auto& old_cell = cells_[std::size_t(node_cell_[k])];
  *std::find(old_cell.begin(), old_cell.end(), int(k)) = old_cell.back();
  old_cell.pop_back();
  cells_[std::size_t(c)].push_back(int(k));
  node_cell_[k] = c;
}

std::int64_t MetropolisSampler::sweep() {
  const RandomStream rng(seed_, RandomPurpose::MonteCarlo, std::uint64_t(sweep_count_), 2);
  const auto& box = s_.box();
  const auto& nodes = s_.shape().nodes();
  const bool rotate = s_.shape().anisotropic();
  auto& pos = s_.positions();
  auto& ori = s_.orientations();
  const auto t0 = tried_t_, a0 = accepted_t_, r0 = tried_r_, b0 = accepted_r_;
  std::int64_t accepted = 0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const auto u01 = rng.uniform2(i, 0), u23 = rng.uniform2(i, 1), u45 = rng.uniform2(i, 2);
    const double u_accept = rng.uniform(i, 3);
    const bool is_rotation = rotate && u01[0] < 0.5;
    Vec3 x = pos[i];
    Quat q = ori[i];
    if (is_rotation) {
      const double angle = dtheta_ * (2.0 * u23[1] - 1.0);
      q = (Eigen::AngleAxisd(angle, uniform_unit_vector(u45[0], u45[1])) * q).normalized();
      ++tried_r_;
    } else {
      x += dx_ * Vec3(2.0 * u01[1] - 1.0, 2.0 * u23[0] - 1.0, 2.0 * u23[1] - 1.0);
      box.wrap(x);
      ++tried_t_;
    }
    const Eigen::Matrix3d R = q.toRotationMatrix();
    for (std::size_t k = 0; k < m_; ++k) {
      old_x_[k] = node_x_[i * m_ + k];
      trial_x_[k] = x + R * nodes[k].position;
      box.wrap(trial_x_[k]);
    }
    const double beta_dU = body_energy(i, trial_x_.data()) - body_energy(i, old_x_.data());
    if (!(u_accept < rule_(beta_dU))) continue;
    pos[i] = x;
    ori[i] = q;
    for (std::size_t k = 0; k < m_; ++k) move_node(i * m_ + k, trial_x_[k]);
    ++accepted;
    ++(is_rotation ? accepted_r_ : accepted_t_);
  }
  last_tried_t_ = tried_t_ - t0;
  last_accepted_t_ = accepted_t_ - a0;
  last_tried_r_ = tried_r_ - r0;
  last_accepted_r_ = accepted_r_ - b0;
  ++sweep_count_;
  s_.update_nodes();
  return accepted;
}

void MetropolisSampler::adapt_steps(double target) {
  auto adjust = [target](double& step, std::int64_t tried, std::int64_t accepted, double cap) {
    if (tried == 0) return;
    step *= double(accepted) / double(tried) > target ? 1.05 : 0.95;
    step = std::min(step, cap);
  };
  adjust(dx_, last_tried_t_, last_accepted_t_, 0.25 * s_.box().edge());
  adjust(dtheta_, last_tried_r_, last_accepted_r_, std::numbers::pi);
}

}  // namespace fldsim::oracle
