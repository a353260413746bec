#include "geometry/HardBodyMonteCarlo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

#include "fldsim/error.hpp"
#include "fldsim/number_text.hpp"
#include "fldsim/random.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim::geometry {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// Uniform random rotation from three uniforms (Shoemake, Graphics Gems III, 1992).
Quat uniform_quaternion(double u1, double u2, double u3) {
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Quat(b * std::cos(two_pi * u3), a * std::sin(two_pi * u2), a * std::cos(two_pi * u2),
              b * std::sin(two_pi * u3));
}

Vec3 uniform_unit_vector(double u1, double u2) {
  const double z = 2.0 * u1 - 1.0, rho = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = two_pi * u2;
  return Vec3(rho * std::cos(phi), rho * std::sin(phi), z);
}

// Largest f < 1 at which |f R + dr| = sigma (the pair touches when the centres are scaled by f),
// or -inf if the pair never touches for f < 1. Roots of |R|^2 f^2 + 2 (R.dr) f + |dr|^2 - sigma^2.
double touching_factor(const Vec3& R, const Vec3& dr, double sigma) {
  const double a = R.squaredNorm(), b = R.dot(dr), c = dr.squaredNorm() - sigma * sigma;
  const double disc = b * b - a * c;
  if (a == 0.0 || disc < 0.0) return -std::numeric_limits<double>::infinity();
  return std::min((-b + std::sqrt(disc)) / a, 1.0);
}

}  // namespace

HardBodyMonteCarlo::HardBodyMonteCarlo(System& s, std::uint64_t seed)
    : s_(s), seed_(seed), m_(s.nodes_per_body()) {
  double rmax = 0.0;
  for (const auto& n : s.shape().nodes()) rmax = std::max(rmax, n.radius);
  contact_ = 2.0 * rmax;
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) s.box().wrap(s.positions()[i]);
  s.update_nodes();
  displacement_.assign(n, Vec3::Zero());
  director0_.resize(n);
  for (std::size_t i = 0; i < n; ++i) director0_[i] = s.director(i);
  mark();
  rebuild_cells();
}

void HardBodyMonteCarlo::mark() {
  displacement_mark_ = displacement_;
  director_mark_.resize(s_.size());
  for (std::size_t i = 0; i < s_.size(); ++i) director_mark_[i] = s_.director(i);
}

void HardBodyMonteCarlo::rebuild_cells() {
  const auto& box = s_.box();
  node_x_ = s_.node_positions();
  for (auto& x : node_x_) box.wrap(x);
  use_cells_ = grid_.configure(box, contact_);
  if (!use_cells_) return;
  cells_.assign(grid_.cell_count(), {});
  node_cell_.resize(node_x_.size());
  for (std::size_t k = 0; k < node_x_.size(); ++k) {
    node_cell_[k] = grid_.cell_of(node_x_[k]);
    cells_[node_cell_[k]].push_back(int(k));
  }
}

HardBodyMonteCarlo::Overlap HardBodyMonteCarlo::node_overlaps(std::size_t body, const Vec3& x, double radius,
                                                              bool first_only) const {
  const auto& box = s_.box();
  Overlap found;
  auto test = [&](std::size_t q) {
    if (q / m_ == body) return false;
    const double sigma = radius + s_.node_radius(q % m_);
    const double d2 = box.minimum_image(node_x_[q] - x).squaredNorm();
    if (d2 >= sigma * sigma) return false;
    ++found.count;
    found.depth += sigma - std::sqrt(d2);
    return first_only;
  };
  if (!use_cells_) {
    for (std::size_t q = 0; q < node_x_.size(); ++q)
      if (test(q)) return found;
    return found;
  }
  std::array<int, LeesEdwardsCellGrid::max_neighbour_cells> cells;
  const int count = grid_.neighbour_cells(grid_.cell_of(x), cells);
  for (int c = 0; c < count; ++c)
    for (int q : cells_[cells[c]])
      if (test(std::size_t(q))) return found;
  return found;
}

void HardBodyMonteCarlo::move_node(std::size_t k, const Vec3& x) {
  node_x_[k] = x;
  if (!use_cells_) return;
  const int c = grid_.cell_of(x);
  if (c == node_cell_[k]) return;
  auto& old_cell = cells_[node_cell_[k]];
  *std::find(old_cell.begin(), old_cell.end(), int(k)) = old_cell.back();
  old_cell.pop_back();
  cells_[c].push_back(int(k));
  node_cell_[k] = c;
}

std::int64_t HardBodyMonteCarlo::sweep() {
  const RandomStream rng(seed_, RandomPurpose::MonteCarlo, std::uint64_t(sweep_count_), 0);
  const auto& box = s_.box();
  const auto& nodes = s_.shape().nodes();
  const bool rotate = s_.shape().anisotropic();
  auto& pos = s_.positions();
  auto& ori = s_.orientations();
  std::int64_t accepted = 0;
  const auto t0 = tried_t_, a0 = accepted_t_, r0 = tried_r_, b0 = accepted_r_;
  std::array<Vec3, 64> trial_buffer;
  std::vector<Vec3> trial_heap;
  Vec3* trial = trial_buffer.data();
  if (m_ > trial_buffer.size()) {
    trial_heap.resize(m_);
    trial = trial_heap.data();
  }

  for (std::size_t i = 0; i < s_.size(); ++i) {
    const auto u01 = rng.uniform2(i, 0), u23 = rng.uniform2(i, 1), u45 = rng.uniform2(i, 2);
    const bool is_rotation = rotate && u01[0] < 0.5;
    Vec3 x = pos[i];
    Quat q = ori[i];
    Vec3 step = Vec3::Zero();
    if (is_rotation) {
      const double angle = dtheta_ * (2.0 * u23[1] - 1.0);
      q = (Eigen::AngleAxisd(angle, uniform_unit_vector(u45[0], u45[1])) * q).normalized();
      ++tried_r_;
    } else {
      step = dx_ * Vec3(2.0 * u01[1] - 1.0, 2.0 * u23[0] - 1.0, 2.0 * u23[1] - 1.0);
      x += step;
      box.wrap(x);
      ++tried_t_;
    }
    const Eigen::Matrix3d R = q.toRotationMatrix();
    bool accept = true;
    if (overlapping_pairs_ == 0) {
      // Hard bodies: reject at the first overlap.
      for (std::size_t k = 0; k < m_ && accept; ++k) {
        trial[k] = x + R * nodes[k].position;
        box.wrap(trial[k]);
        accept = node_overlaps(i, trial[k], nodes[k].radius, true).count == 0;
      }
    } else {
      // Removing a compression's overlaps: the moved body's summed overlap must not grow (zero
      // stays zero), so the total overlap never grows.
      const double old_depth =
          body_overlap_depth(i, &node_x_[i * m_], std::numeric_limits<double>::infinity());
      for (std::size_t k = 0; k < m_; ++k) {
        trial[k] = x + R * nodes[k].position;
        box.wrap(trial[k]);
      }
      accept = body_overlap_depth(i, trial, old_depth) <= old_depth;
    }
    if (!accept) continue;
    pos[i] = x;
    ori[i] = q;
    displacement_[i] += step;
    for (std::size_t k = 0; k < m_; ++k) move_node(i * m_ + k, trial[k]);
    ++accepted;
    if (is_rotation)
      ++accepted_r_;
    else
      ++accepted_t_;
  }
  last_tried_t_ = tried_t_ - t0;
  last_accepted_t_ = accepted_t_ - a0;
  last_tried_r_ = tried_r_ - r0;
  last_accepted_r_ = accepted_r_ - b0;
  ++sweep_count_;
  s_.update_nodes();
  if (overlapping_pairs_ > 0) overlapping_pairs_ = count_overlaps();
  return accepted;
}

double HardBodyMonteCarlo::body_overlap_depth(std::size_t body, const Vec3* x, double bound) const {
  double depth = 0.0;
  for (std::size_t k = 0; k < m_ && depth <= bound; ++k)
    depth += node_overlaps(body, x[k], s_.node_radius(k), bound == 0.0).depth;
  return depth;
}

void HardBodyMonteCarlo::adapt_steps(double target) {
  auto adjust = [target](double& step, std::int64_t tried, std::int64_t accepted, double cap) {
    if (tried == 0) return;
    step *= double(accepted) / double(tried) > target ? 1.1 : 0.9;
    step = std::min(step, cap);
  };
  adjust(dx_, last_tried_t_, last_accepted_t_, 0.25 * s_.box().edge());
  adjust(dtheta_, last_tried_r_, last_accepted_r_, std::numbers::pi);
}

bool HardBodyMonteCarlo::compress_towards(double edge, double max_step, std::size_t allowed_overlaps) {
  auto& box = s_.box();
  const double L = box.edge();
  if (edge >= L) return true;
  const double f_floor = std::max(edge / L, 1.0 - max_step);
  // Node pairs that can touch for f in [f_floor, 1]: |f R + dr| >= |R + dr| - (1 - f)|R| and
  // |R| <= |R + dr| + 2 * bounding radius, so pairs farther than this cannot reach contact.
  const double rb = s_.shape().bounding_radius();
  const double search = (contact_ + max_step * 2.0 * rb) / (1.0 - max_step);
  CellNeighbourList list;
  list.configure(search, 0.0);
  list.update(s_);
  // The contact factors of the pairs that can touch; the (K+1)-th largest limits the step.
  const auto& off = s_.node_offsets();
  touching_.clear();
  for (const auto& pr : list.pairs().pairs()) {
    const Vec3 dr = off[pr.body_j * m_ + pr.node_b] - off[pr.body_i * m_ + pr.node_a];
    const double sigma = s_.node_radius(pr.node_a) + s_.node_radius(pr.node_b);
    const double f_pair = touching_factor(pr.r - dr, dr, sigma);
    if (f_pair > f_floor) touching_.push_back(f_pair);
  }
  double f_touch = -std::numeric_limits<double>::infinity();
  if (touching_.size() > allowed_overlaps) {
    const auto kth = touching_.begin() + std::ptrdiff_t(allowed_overlaps);
    std::nth_element(touching_.begin(), kth, touching_.end(), std::greater<>());
    f_touch = *kth;
  }
  // Go 90 % of the way to that contact (never exactly to it, so round-off cannot overlap).
  const double f = std::max(f_floor, f_touch + 0.1 * (1.0 - f_touch));
  const bool reached = f == edge / L;
  const double strain = box.strain();
  box = LeesEdwardsBox(reached ? edge : L * f);
  box.set_strain(strain);
  for (auto& x : s_.positions()) {
    x *= f;
    box.wrap(x);
  }
  s_.update_nodes();
  rebuild_cells();
  if (allowed_overlaps > 0) overlapping_pairs_ = count_overlaps();
  return reached;
}

double HardBodyMonteCarlo::acceptance_translation() const {
  return tried_t_ ? double(accepted_t_) / double(tried_t_) : 0.0;
}
double HardBodyMonteCarlo::acceptance_rotation() const {
  return tried_r_ ? double(accepted_r_) / double(tried_r_) : 0.0;
}
void HardBodyMonteCarlo::reset_counters() {
  tried_t_ = accepted_t_ = tried_r_ = accepted_r_ = 0;
}

double HardBodyMonteCarlo::mean_square_displacement_from(const std::vector<Vec3>* origin) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < displacement_.size(); ++i)
    sum += (origin ? displacement_[i] - (*origin)[i] : displacement_[i]).squaredNorm();
  return displacement_.empty() ? 0.0 : sum / double(displacement_.size());
}

double HardBodyMonteCarlo::orientation_p2_against(const std::vector<Vec3>& directors) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double c = s_.director(i).dot(directors[i]);
    sum += 1.5 * c * c - 0.5;
  }
  return s_.size() ? sum / double(s_.size()) : 0.0;
}

double HardBodyMonteCarlo::mean_square_displacement() const {
  return mean_square_displacement_from(nullptr);
}
double HardBodyMonteCarlo::mean_square_displacement_since_mark() const {
  return mean_square_displacement_from(&displacement_mark_);
}
double HardBodyMonteCarlo::orientation_p2() const {
  return orientation_p2_against(director0_);
}
double HardBodyMonteCarlo::orientation_p2_since_mark() const {
  return orientation_p2_against(director_mark_);
}

std::int64_t HardBodyMonteCarlo::count_overlaps() const {
  std::int64_t count = 0;
  for (std::size_t k = 0; k < node_x_.size(); ++k)
    count += node_overlaps(k / m_, node_x_[k], s_.node_radius(k % m_), false).count;
  return count / 2;  // each overlapping pair is seen from both nodes
}

namespace {

// Simple cubic lattice with spacing >= 2 * bounding radius, in a box of volume fraction
// min(phi, 0.3) or looser if the lattice needs it; uniform random orientations.
void place_on_lattice(System& s, std::uint64_t seed, double target_edge) {
  const std::size_t n = s.size();
  const auto side = static_cast<std::size_t>(std::ceil(std::cbrt(double(n)) - 1e-9));
  const double phi = s.physics().volume_fraction;
  const double loose = phi > 0.3 ? target_edge * std::cbrt(phi / 0.3) : target_edge;
  const double lattice = double(side) * 2.0 * s.shape().bounding_radius() * (1.0 + 1e-6);
  const double L = std::max(loose, lattice);
  const double strain = s.box().strain();
  s.box() = LeesEdwardsBox(L);
  s.box().set_strain(strain);
  const double h = L / double(side);
  const RandomStream rng(seed, RandomPurpose::MonteCarlo, 0, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t ix = i % side, iy = (i / side) % side, iz = i / (side * side);
    s.positions()[i] = Vec3((double(ix) + 0.5) * h, (double(iy) + 0.5) * h, (double(iz) + 0.5) * h);
    const auto u = rng.uniform2(i, 0), v = rng.uniform2(i, 1);
    s.orientations()[i] = s.shape().anisotropic() ? uniform_quaternion(u[0], u[1], v[0]) : Quat::Identity();
  }
  s.update_nodes();
}

}  // namespace

MonteCarloReport initialise_monte_carlo(System& s, const MonteCarloOptions& opt,
                                        const std::function<void(const std::string&)>& log) {
  const double target_edge = s.box().edge();
  place_on_lattice(s, opt.seed, target_edge);
  HardBodyMonteCarlo mc(s, opt.seed);
  // True volume fraction in a cubic box of this edge (the current box by default).
  auto volume_fraction = [&](double edge) {
    return double(s.size()) * s.shape().volume() / (edge * edge * edge);
  };
  auto say = [&](const std::string& what) {
    if (!log) return;
    std::ostringstream o;
    o << "monte carlo: " << what << " after " << mc.sweeps_done() << " sweeps (box " << s.box().edge()
      << ", msd " << mc.mean_square_displacement() << ", P2 " << mc.orientation_p2()
      << "; since the target msd " << mc.mean_square_displacement_since_mark() << ", P2 "
      << mc.orientation_p2_since_mark() << ")";
    log(o.str());
  };
  // A dense or large start can take a while (8000 spheres at phi 0.5: 58 s, homonuclear
  // dicolloids equilibrate slowly): a line every 30 s of wall time says where it is (the
  // configuration does not depend on it).
  auto last_line = std::chrono::steady_clock::now();
  auto say_now_and_then = [&](const char* phase) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_line < std::chrono::seconds(30)) return;
    last_line = now;
    std::ostringstream o;
    o << phase << ", volume fraction " << std::setprecision(4) << volume_fraction(s.box().edge()) << " of "
      << std::setprecision(4) << volume_fraction(target_edge);
    say(o.str());
  };
  auto check_stop = [&] {
    if (!opt.stop) return;
    const std::string why = opt.stop();
    if (!why.empty())
      throw Error("monte carlo start stopped by " + why + " after " + std::to_string(mc.sweeps_done()) +
                  " sweeps (volume fraction " +
                  number_text(std::round(1e4 * volume_fraction(s.box().edge())) / 1e4) +
                  "); nothing was run");
  };
  auto check_budget = [&] {
    if (mc.sweeps_done() >= opt.max_sweeps)
      throw Error("monte carlo: no valid configuration after " + std::to_string(opt.max_sweeps) +
                  " sweeps (box edge " + number_text(s.box().edge()) + ", target " +
                  number_text(target_edge) + ")");
  };
  const std::size_t allowed =
      opt.compression_overlaps > 0.0
          ? std::max<std::size_t>(1, std::size_t(opt.compression_overlaps * double(s.size())))
          : 0;
  bool reached = false;
  while (!reached || mc.overlapping_pairs() > 0) {
    mc.sweep();
    mc.adapt_steps(opt.target_acceptance);
    if (!reached && mc.overlapping_pairs() == 0) reached = mc.compress_towards(target_edge, 0.02, allowed);
    check_budget();
    check_stop();
    say_now_and_then("still compressing");
  }
  mc.mark();
  say("reached the target volume fraction");

  // Hard-body MC: adapt the steps briefly, then keep them fixed.
  mc.reset_counters();
  constexpr std::int64_t adapt_sweeps = 20, min_sweeps = 100;
  for (std::int64_t k = 0; k < adapt_sweeps; ++k) {
    mc.sweep();
    mc.adapt_steps(opt.target_acceptance);
  }
  const bool rotate = s.shape().anisotropic();
  auto decorrelated = [&](std::int64_t done) {
    return done >= min_sweeps && mc.mean_square_displacement() > opt.decorrelation_msd &&
           mc.mean_square_displacement_since_mark() > opt.relaxation_msd &&
           (!rotate || (mc.orientation_p2() < opt.decorrelation_p2 &&
                        mc.orientation_p2_since_mark() < opt.relaxation_p2));
  };
  // The configuration is valid from here on: at max_sweeps (a glassy or crystalline volume fraction,
  // whose bodies cannot travel 2 a) the start ends undecorrelated and says so, rather than throw.
  std::int64_t done = adapt_sweeps;
  while (opt.sweeps > 0 ? done < opt.sweeps : !decorrelated(done)) {
    if (mc.sweeps_done() >= opt.max_sweeps) break;
    mc.sweep();
    ++done;
    check_stop();
    say_now_and_then("still equilibrating");
  }
  // A fixed `sweeps` counts as done only if max_sweeps did not cut it short (a long compression
  // can use up most of max_sweeps).
  const bool forgot = opt.sweeps > 0 ? done >= opt.sweeps : decorrelated(done);
  say(forgot           ? "equilibrated"
      : opt.sweeps > 0 ? "stopped at max_sweeps before the requested sweeps were done"
                       : "stopped at max_sweeps without decorrelating");

  MonteCarloReport report;
  report.sweeps = mc.sweeps_done();
  report.acceptance_translation = mc.acceptance_translation();
  report.acceptance_rotation = mc.acceptance_rotation();
  report.final_volume_fraction = volume_fraction(s.box().edge());
  report.overlaps = mc.count_overlaps();
  report.max_displacement = mc.translation_step();
  report.decorrelated = forgot;
  report.sweeps_at_target = done;
  report.msd_since_target = mc.mean_square_displacement_since_mark();
  report.p2_since_target = rotate ? mc.orientation_p2_since_mark() : 0.0;
  return report;
}

void place_explicit(System& s, const std::vector<Vec3>& positions, const std::vector<Quat>& q) {
  if (positions.size() != s.size() || q.size() != s.size())
    throw Error("place_explicit: expected " + std::to_string(s.size()) + " positions and orientations, got " +
                std::to_string(positions.size()) + " and " + std::to_string(q.size()));
  for (std::size_t i = 0; i < s.size(); ++i) {
    s.positions()[i] = positions[i];
    s.orientations()[i] = q[i].normalized();
  }
  s.update_nodes();
  double rmax = 0.0;
  for (const auto& n : s.shape().nodes()) rmax = std::max(rmax, n.radius);
  CellNeighbourList list;
  list.configure(2.0 * rmax, 0.0);
  list.update(s);
  for (const auto& pr : list.pairs().pairs()) {
    const double gap = pr.distance - s.node_radius(pr.node_a) - s.node_radius(pr.node_b);
    if (gap < 0.0) {
      std::ostringstream o;
      o << "place_explicit: bodies " << pr.body_i << " and " << pr.body_j << " overlap (nodes " << pr.node_a
        << " and " << pr.node_b << ", surface gap " << gap << ")";
      throw Error(o.str());
    }
  }
}

void place_explicit(System& s, const std::vector<Vec3>& positions, const std::vector<Vec3>& directors) {
  std::vector<Quat> q;
  q.reserve(directors.size());
  for (const auto& n : directors) {
    if (!(n.norm() > 0.0)) throw Error("place_explicit: a director must be a non-zero vector");
    q.push_back(Quat::FromTwoVectors(s.shape().director(), n.normalized()));
  }
  place_explicit(s, positions, q);
}

}  // namespace fldsim::geometry
