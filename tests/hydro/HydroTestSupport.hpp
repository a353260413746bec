// Helpers for the hydro tests: a shape made of given nodes, a system of N such bodies, random
// non-overlapping configurations and a brute-force node pair list (independent of the core's
// cell list).
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "KershawCycle.hpp"
#include "fldsim/block_sparse.hpp"
#include "fldsim/neighbours.hpp"
#include "fldsim/shape.hpp"
#include "fldsim/system.hpp"

namespace fldsim::hydro::test {

constexpr double kPi = 3.14159265358979323846;

class NodeShape : public Shape {
 public:
  explicit NodeShape(std::vector<Node> nodes) : nodes_(std::move(nodes)) {}
  const std::vector<Node>& nodes() const override { return nodes_; }
  // Union volume of at most two equal overlapping unit-radius nodes (lens removed), reference §6.
  double volume() const override {
    const double sphere = 4.0 / 3.0 * kPi;
    if (nodes_.size() == 1) return sphere;
    const double c = (nodes_[1].position - nodes_[0].position).norm();
    return 2.0 * sphere - kPi * (4.0 + c) * (2.0 - c) * (2.0 - c) / 12.0;
  }
  Vec3 director() const override { return Vec3::UnitZ(); }

 private:
  std::vector<Node> nodes_;
};

inline std::shared_ptr<const Shape> sphere_shape() {
  return std::make_shared<NodeShape>(std::vector<Node>{{Vec3::Zero(), 1.0}});
}
// Homonuclear dicolloid: unit nodes at +/- c/2 along the body z axis (centroid at the middle).
inline std::shared_ptr<const Shape> dicolloid_shape(double c) {
  return std::make_shared<NodeShape>(
      std::vector<Node>{{Vec3(0, 0, -0.5 * c), 1.0}, {Vec3(0, 0, 0.5 * c), 1.0}});
}

inline Physics physics(double kT, double shear_rate, double phi) {
  Physics p;
  p.kT = kT;
  p.shear_rate = shear_rate;
  p.volume_fraction = phi;
  return p;
}

// Every node pair of different bodies with minimum-image distance below `range`.
inline NodePairList brute_force_pairs(const System& s, double range) {
  NodePairList list;
  list.set_range(range);
  const std::size_t m = s.nodes_per_body();
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b) {
          const Vec3 r = s.box().minimum_image(s.node_positions()[j * m + b] - s.node_positions()[i * m + a]);
          const double d = r.norm();
          if (d < range)
            list.pairs().push_back(
                {std::uint32_t(i), std::uint32_t(j), std::uint16_t(a), std::uint16_t(b), r, d});
        }
  return list;
}

// Random positions and orientations with every node-node gap of different bodies above min_gap.
inline void random_configuration(System& s, double min_gap, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const double L = s.box().edge();
  const std::size_t m = s.nodes_per_body();
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (int attempt = 0;; ++attempt) {
      s.positions()[i] = Vec3(u(rng), u(rng), u(rng)) * L;
      s.orientations()[i] = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
      s.update_nodes();
      bool ok = true;
      for (std::size_t j = 0; j < i && ok; ++j)
        for (std::size_t a = 0; a < m && ok; ++a)
          for (std::size_t b = 0; b < m && ok; ++b) {
            const Vec3 r =
                s.box().minimum_image(s.node_positions()[i * m + a] - s.node_positions()[j * m + b]);
            if (r.norm() < s.node_radius(a) + s.node_radius(b) + min_gap) ok = false;
          }
      if (ok) break;
      if (attempt > 100000) throw std::runtime_error("random_configuration: box too dense");
    }
  }
  s.update_nodes();
}

// Four spheres in a row, 2.2 a apart (three lubricated pairs), in a box of 20 a.
inline System four_sphere_chain() {
  System s(sphere_shape(), 4, 20.0, physics(1.0, 0.0, 0.3));
  for (std::size_t i = 0; i < 4; ++i) s.positions()[i] = Vec3(3.0 + 2.2 * double(i), 5.0, 5.0);
  s.update_nodes();
  return s;
}

// A ResistanceModel checkpoint (save_state's format: [-2, n, pairs, (i, j)..., diagonal blocks,
// upper blocks (column-major), 0 numbers of the preconditioner's own state]) whose matrix is the
// 4-cycle kKershawCycle in the rotational rows, the identity in the translational ones (the matrix
// of BlockPCG.FallsBackToDiluWhereIncompleteCholeskyBreaksDown: no block is stiff for the IC
// factor's cluster fill), with body i of the cycle numbered label[i].
inline std::vector<double> four_cycle_checkpoint(const std::array<std::uint32_t, 4>& label) {
  const auto& M = fldsim::hydro::test::kKershawCycle;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> upper;
  std::vector<double> value;
  for (std::uint32_t i = 0; i < 4; ++i)
    for (std::uint32_t j = i + 1; j < 4; ++j)
      if (M[i][j] != 0.0) {
        upper.emplace_back(std::min(label[i], label[j]), std::max(label[i], label[j]));
        value.push_back(M[i][j]);
      }
  std::vector<double> state = {-2.0, 4.0, double(upper.size())};
  for (const auto& [i, j] : upper) state.insert(state.end(), {double(i), double(j)});
  std::array<double, 4> diagonal{};
  for (std::uint32_t i = 0; i < 4; ++i) diagonal[label[i]] = M[i][i];
  auto block = [&](double v, double translational) {
    Mat6 b = Mat6::Zero();
    b.topLeftCorner<3, 3>() = translational * Eigen::Matrix3d::Identity();
    b.bottomRightCorner<3, 3>() = v * Eigen::Matrix3d::Identity();
    state.insert(state.end(), b.data(), b.data() + 36);
  };
  for (double d : diagonal) block(d, 1.0);
  for (double v : value) block(v, 0.0);
  state.push_back(0.0);
  return state;
}

}  // namespace fldsim::hydro::test
