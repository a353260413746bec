// Lubrication at body level: selects the visible node pairs within the cutoff, maps each pair's
// node-level rows S (LubricationPair) to body level with the rigid-body kinematics,
//     S_i = S[:, 0:6] K(x_a),  S_j = S[:, 6:12] K(x_b),
// and from them fills R_delta = sum_p [S_i S_j]^T [S_i S_j] into a BlockSparseMatrix, the
// R_FE:E_inf right-hand side, the pairwise Brownian forces sum_p B_p beta_p (B_p = [S_i S_j]^T)
// and the pair stresslets. Each pair keeps only its direction, coefficients and node offsets and
// takes all of these in closed form (LubricationPair::centred_gram, centred_wrench, centred_noise,
// node-level), carried to the bodies by K where a node is off its body's centre (dicolloids):
// K_a^T G K_b for the Gram blocks (written out from the pair's modes in body coordinates), K^T for
// wrenches, K for velocities. Equal to the row products
// to rounding (tests/hydro/ResistancePropertiesTest.cpp). A pair's visibility weight w scales its rows by
// sqrt(w), hence its resistance and stresslet by w and its Brownian force by sqrt(w) (fluctuation-dissipation
// kept). Pair work is done in parallel into per-pair buffers and then summed per body in pair order, so
// results do not depend on the thread count (on one thread the body blocks of off-centre node pairs
// are evaluated in add_to, straight into R: the same function of the same numbers).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "fldsim-sdk/lubrication/LubricationPair.hpp"
#include "fldsim/block_sparse.hpp"
#include "fldsim/neighbours.hpp"
#include "fldsim/random.hpp"
#include "fldsim/system.hpp"

namespace fldsim::hydro {

class BodyResistance {
 public:
  BodyResistance() = default;
  explicit BodyResistance(LubricationOptions options) : options_(options) {}

  // Select the visible pairs and evaluate their body-level rows. Returns true when the set of
  // accepted pairs differs from the previous call (the matrix pattern must then be rebuilt).
  bool update(const System& system, const NodePairList& pairs);
  // The (i < j) body pairs coupled by accepted node pairs, for BlockSparseMatrix::set_pattern
  // (into out, reusing its storage).
  void body_pairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const;
  // Remember where each pair's off-diagonal block lives in A (after set_pattern).
  void bind(const BlockSparseMatrix& A);
  // Off-diagonal blocks of A = those of R_delta, diagonal blocks += R_delta's (values only; the
  // pattern must be bound). Every off-diagonal block of the bound pattern is written (its first
  // pair's term assigned, later ones added), so A's off-diagonal blocks need no zeroing first.
  void add_to(BlockSparseMatrix& A) const;
  // rhs += R_FE:E_inf of the pairs: -[S_i S_j]^T S_uj E L_ij, with the strain arm L_ij either
  // R_ij = X_j - X_i, the minimum-image centre separation (the relative ambient velocity of the two
  // bodies once their velocities are taken relative to U_inf at the centres), or R_ij less the
  // node pair's gap along d, the contact distance for spheres (LubricationOptions::strain_arm).
  void add_strain_force(const Eigen::Matrix3d& E, double* rhs);
  // FB += scale * sum_p B_p beta_p, beta_p from the pair's own noise stream.
  void add_brownian(const RandomStream& noise, std::size_t nodes_per_body, double scale, double* FB);
  // Sum over pairs of -sym(R_ij (x) F^H_j), F^H_j the pair's hydrodynamic force on body j's node
  // for the velocities dU (relative to U_inf), including the ambient strain.
  Eigen::Matrix3d stresslet_sum(const Eigen::Matrix3d& E, const double* dU) const;

  std::size_t size() const { return accepted_.size(); }
  // For tests and benchmarks: false forms every pair's body rows [S_i S_j] and its Gram blocks by
  // the general products (the closed forms are the default).
  void set_closed_forms(bool on) { closed_forms_ = on; }
  // For tests: body indices and body-level rows [S_i S_j] (8 x 12) of accepted pair k (formed
  // here from the closed form's direction, coefficients and offsets).
  std::pair<std::uint32_t, std::uint32_t> bodies(std::size_t k) const {
    return {accepted_[k].body_i, accepted_[k].body_j};
  }
  Eigen::Matrix<double, LubricationPair::kRows, 12> rows(std::size_t k) const;

 private:
  struct Accepted {
    std::uint32_t body_i, body_j;
    std::uint16_t node_a, node_b;
    Vec3 separation;           // x(j,b) - x(i,a), minimum image
    double distance = 0.0;     // |separation|
    Vec3 arm;                  // strain arm L_ij (see add_strain_force)
    double weight = 1.0;       // visibility weight w (Visibility.hpp): rows scaled by sqrt(w)
    std::int64_t upper = -1;   // index of block (i, j) in the matrix
    bool opens_block = false;  // the first accepted pair of block `upper` (add_to assigns its term)
    bool operator==(const Accepted& o) const {
      return body_i == o.body_i && body_j == o.body_j && node_a == o.node_a && node_b == o.node_b;
    }
  };
  using BodyRows = Eigen::Matrix<double, LubricationPair::kRows, 12>;  // [S_i S_j]

  void sum_per_body(double* out) const;  // out(6N) += sum of pair_force_ in pair order

  // dist = |separation|.
  Vec3 strain_arm(const Vec3& separation, const Vec3& centre_separation, double dist, double a_a,
                  double a_b) const;

  LubricationOptions options_;
  std::size_t bodies_ = 0;
  std::vector<Accepted> accepted_, candidates_;
  std::vector<BodyRows> rows_;  // general path only (set_closed_forms(false))
  // Body-level Gram blocks of pairs with an off-centre node, or of every pair on the general path.
  std::vector<Mat6> block_ii_, block_jj_, block_ij_;
  // A pair in closed form: its direction, coefficients, weight and node offsets; nodes at their
  // bodies' centres (offset false) take their Gram blocks from LubricationPair::centred_gram in add_to.
  struct ClosedForm {
    Vec3 d = Vec3::Zero();  // unit separation
    LubricationCoefficients c;
    double weight = 1.0;
    Vec3 xa = Vec3::Zero(), xb = Vec3::Zero();  // node offsets in bodies i and j (lab frame)
    bool on = false;
    bool offset = false;  // a node off its body's centre
  };
  static BodyRows body_rows(const PairRows& S, const Vec3& xa, const Vec3& xb, double weight);
  std::vector<ClosedForm> closed_;
  std::vector<Eigen::Matrix<double, 12, 1>> pair_force_;  // scratch: per-pair body wrenches
  std::vector<double> radii_;
  std::vector<std::uint8_t> opened_;  // scratch of bind(): blocks that already have a first pair
  bool closed_forms_ = true;
  bool blocks_in_pair_pass_ = false;  // offset pairs' Gram blocks: in update()'s threads, else in add_to
};

}  // namespace fldsim::hydro
