#include "fldsim-sdk/lubrication/BodyResistance.hpp"

#include <cmath>

#include "BlockCorners.hpp"
#include "CrossMatrix.hpp"
#include "VisibilityAt.hpp"
#include "fldsim-sdk/lubrication/Visibility.hpp"
#include "fldsim/parallel_loop.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim::hydro {

namespace {
using Mat3 = Eigen::Matrix3d;

// The body-level Gram blocks of a node pair off its bodies' centres, in closed form. With the node
// velocity U + Omega x x (rigid.hpp node_kinematics), the pair's modes over (U_i, Omega_i, U_j,
// Omega_j) are the squeeze row (-d, -e_a, d, e_b) with e_x = x x d, the shear rows
// (-P, M_a, P, N_b) with M_a = P[a]x + l_i [d]x and N_b = -P[b]x + l_j [d]x, the pump rows
// (0, P, 0, -P) and the twist row (0, d, 0, -d) (LubricationPair::centred_wrench's modes); their
// Gram is sq s^T s + sh T^T T + pu Q^T Q + tw t^T t (dd = d d^T, P = I - dd). Since P [d]x = [d]x,
// M_a = P [c_a]x and N_b = P [c_b]x with the lever points c_a = a + l_i d and c_b = l_j d - b, and
// with [x]x^T [y]x = (x.y) I - y x^T and d^T [c]x = (d x c)^T every block is a sum of outer
// products (s = sq - sh):
//   uu   = sh I + s dd                        (translation, +ii +jj, -ij)
//   ur_a = s d e_a^T - sh [c_a]x              (ii's coupling; ij's lower left is -ur_a^T)
//   ur_b = s d e_b^T + sh [c_b]x              (jj's coupling; ij's upper right is -ur_b)
//   rr_a = s e_a e_a^T - sh c_a c_a^T + (sh |c_a|^2 + pu) I + (tw - pu) dd, rr_b likewise
//   rr_ab = -s e_a e_b^T - sh c_b c_a^T + (sh c_a.c_b - pu) I - (tw - pu) dd
// This is K_a^T G K_b of the node blocks (LubricationPair::centred_gram) in about 130 flops a pair
// (bench/README.md, "Dicolloid node pairs: the Gram blocks as outer products"). The rotation blocks
// of ii and jj are symmetrised so that R is symmetric to the last bit.
//
// The corners go to put_ii / put_jj / put_ij(row, column, value), which assign them to a pair's own
// blocks (the threads' pair pass) or add them to R's (add_to on one thread): the same values
// element for element either way (BlockCorners.hpp; LubricationPair.cpp's centred_corners does the
// same for spheres).
template <class PutII, class PutJJ, class PutIJ>
void offset_corners(const Vec3& d, const LubricationCoefficients& c, double w, const Vec3& a, const Vec3& b,
                    const PutII& put_ii, const PutJJ& put_jj, const PutIJ& put_ij) {
  const double sq = w * c.squeeze, sh = w * c.shear, pu = w * c.pump, tw = w * c.twist;
  const double s = sq - sh;
  const Vec3 ca = a + c.lever_i * d, cb = c.lever_j * d - b;
  const Vec3 ea = a.cross(d), eb = b.cross(d);
  const Mat3 dd = d * d.transpose();
  Mat3 uu = s * dd;
  uu.diagonal().array() += sh;
  const Vec3 sd = s * d;
  const Mat3 ur_a = sd * ea.transpose() - sh * cross_matrix(ca);
  const Mat3 ur_b = sd * eb.transpose() + sh * cross_matrix(cb);
  const Mat3 twist = (tw - pu) * dd;
  const Vec3 sea = s * ea, shca = sh * ca;
  Mat3 r = sea * ea.transpose() - shca * ca.transpose() + twist;
  r.diagonal().array() += sh * ca.squaredNorm() + pu;
  put_ii(0, 0, uu);
  put_ii(0, 3, ur_a);
  put_ii(3, 0, ur_a.transpose());
  put_ii(3, 3, 0.5 * (r + r.transpose()));
  r = s * eb * eb.transpose() - sh * cb * cb.transpose() + twist;
  r.diagonal().array() += sh * cb.squaredNorm() + pu;
  put_jj(0, 0, uu);
  put_jj(0, 3, ur_b);
  put_jj(3, 0, ur_b.transpose());
  put_jj(3, 3, 0.5 * (r + r.transpose()));
  put_ij(0, 0, -uu);
  put_ij(0, 3, -ur_b);
  put_ij(3, 0, -ur_a.transpose());
  r = -sea * eb.transpose() - cb * shca.transpose() - twist;
  r.diagonal().array() += ca.dot(cb) * sh - pu;
  put_ij(3, 3, r);
}

// K^T of a node wrench (f, t) -> body wrench (f, t + x x f), for both nodes of a pair wrench, in
// place (a copy in and out by value was 8 % of a dicolloid assembly).
void carry(Eigen::Matrix<double, 12, 1>& w, const Vec3& xa, const Vec3& xb) {
  w.segment<3>(3) += xa.cross(Vec3(w.segment<3>(0)));
  w.segment<3>(9) += xb.cross(Vec3(w.segment<3>(6)));
}

// K of a body velocity (U, Omega) -> node velocity (U + Omega x x, Omega).
Vec6 node_motion(const Eigen::Map<const Vec6>& body, const Vec3& x) {
  Vec6 v = body;
  v.head<3>() += Vec3(body.tail<3>()).cross(x);
  return v;
}
}  // namespace

Vec3 BodyResistance::strain_arm(const Vec3& separation, const Vec3& centre_separation, double dist,
                                double a_a, double a_b) const {
  if (options_.strain_arm == StrainArm::Centre) return centre_separation;
  // The centre arm shortened by the node pair's gap: (a_a + a_b) d for spheres (LAMMPS), and for
  // nodes off their body's centre the bodies' relative motion except the gap's own closing. A
  // plain (a_a + a_b) d there ignores the offsets: node pairs of fused dumbbells at Pe = 1000 then
  // approach at O(gammadot a) at contact and overlapped by 0.74 a within 4 strains.
  return centre_separation - (dist - a_a - a_b) / dist * separation;
}

bool BodyResistance::update(const System& system, const NodePairList& pairs) {
  const std::size_t m = system.nodes_per_body();
  bodies_ = system.size();
  radii_.resize(m);
  for (std::size_t k = 0; k < m; ++k) radii_[k] = system.node_radius(k);
  const auto& offsets = system.node_offsets();

  candidates_.clear();
  for (const NodePair& p : pairs.pairs()) {
    const Vec3* off_i = offsets.data() + std::size_t(p.body_i) * m;
    const Vec3* off_j = offsets.data() + std::size_t(p.body_j) * m;
    const double a_a = radii_[p.node_a], a_b = radii_[p.node_b];
    const double dist = p.distance;  // |r|, from the neighbour list
    // The cutoff first (visibility_weight's own first test, on the same distance): most candidates
    // of the list's skin end here. With one node per body (spheres) no sibling can hide a node.
    if (dist >= options_.cutoff * 0.5 * (a_a + a_b)) continue;
    const double w = m == 1 ? 1.0
                            : visibility_weight_at(off_i, off_j, radii_.data(), m, p.node_a, p.node_b, p.r,
                                                   dist, options_.cutoff, options_.visibility_width);
    if (w == 0.0) continue;
    const Vec3 centres = p.r - off_j[p.node_b] + off_i[p.node_a];
    candidates_.push_back(
        {p.body_i, p.body_j, p.node_a, p.node_b, p.r, dist, strain_arm(p.r, centres, dist, a_a, a_b), w});
  }
  const bool changed = !(candidates_ == accepted_);
  if (changed) {
    accepted_.swap(candidates_);
    const std::size_t n = accepted_.size();
    block_ii_.resize(n);
    block_jj_.resize(n);
    block_ij_.resize(n);
    closed_.resize(n);
    pair_force_.resize(n);
  } else {
    for (std::size_t k = 0; k < accepted_.size(); ++k) {
      accepted_[k].separation = candidates_[k].separation;
      accepted_[k].distance = candidates_[k].distance;
      accepted_[k].arm = candidates_[k].arm;
      accepted_[k].weight = candidates_[k].weight;
    }
  }

  rows_.resize(closed_forms_ ? 0 : accepted_.size());  // the general path only

  const double mu = system.physics().viscosity;
  blocks_in_pair_pass_ = !single_thread();
  parallel_for(std::int64_t(accepted_.size()), [&](std::int64_t k) {
    const Accepted& p = accepted_[k];
    LubricationCoefficients c;
    const Vec3& xa = offsets[std::size_t(p.body_i) * m + p.node_a];
    const Vec3& xb = offsets[std::size_t(p.body_j) * m + p.node_b];
    if (closed_forms_) {
      // The pair is its direction and coefficients: its node-level Gram blocks, strain force,
      // Brownian force and stresslet follow in closed form (LubricationPair::centred_*), cheaper
      // than forming and streaming the 8 x 12 rows. Nodes at their bodies' centres (spheres) take
      // their Gram blocks in add_to; off-centre nodes (dicolloids) get their body blocks in closed
      // form (offset_corners()): here when threads share this pass, else in add_to, where the three
      // 6 x 6 blocks go straight into R instead of through 864 bytes a pair of memory (the same
      // function of the same numbers: the same bits either way).
      c = LubricationPair::coefficients(radii_[p.node_a], radii_[p.node_b], p.distance, mu, options_);
      const bool offset = !(xa.isZero(0.0) && xb.isZero(0.0));
      closed_[k] = {p.separation / p.distance, c, p.weight, xa, xb, true, offset};
      if (offset && blocks_in_pair_pass_)
        offset_corners(closed_[k].d, c, p.weight, xa, xb, assigning(block_ii_[k]), assigning(block_jj_[k]),
                       assigning(block_ij_[k]));
      return;
    }
    // The general path (set_closed_forms(false), the tests' reference): body rows and Gram products.
    closed_[k].on = false;
    PairRows S;
    LubricationPair::rows(radii_[p.node_a], radii_[p.node_b], p.separation, mu, options_, S, c);
    BodyRows& B = rows_[k];
    B = body_rows(S, xa, xb, p.weight);
    // Gram blocks, symmetrised so that R is symmetric to the last bit.
    const Mat6 ii = B.leftCols<6>().transpose().lazyProduct(B.leftCols<6>());
    const Mat6 jj = B.rightCols<6>().transpose().lazyProduct(B.rightCols<6>());
    block_ii_[k] = 0.5 * (ii + ii.transpose());
    block_jj_[k] = 0.5 * (jj + jj.transpose());
    block_ij_[k] = B.leftCols<6>().transpose().lazyProduct(B.rightCols<6>());
  });
  return changed;
}

BodyResistance::BodyRows BodyResistance::body_rows(const PairRows& S, const Vec3& xa, const Vec3& xb,
                                                   double weight) {
  // B = S K per node, with K = [I -[x]x; 0 I] (node_kinematics): the translational columns are
  // S's, the rotational ones S_w + S_u (-[x]x), 72 multiply-adds instead of the 288 of the full
  // 8x6 by 6x6 product. Lazy (coefficient) products: Eigen 3.4 otherwise sends these small
  // shapes to its general blocked kernel.
  BodyRows B = S;
  if (!xa.isZero(0.0))
    B.middleCols<3>(3).noalias() += S.leftCols<3>().lazyProduct(node_kinematics(xa).topRightCorner<3, 3>());
  if (!xb.isZero(0.0))
    B.rightCols<3>().noalias() += S.middleCols<3>(6).lazyProduct(node_kinematics(xb).topRightCorner<3, 3>());
  if (weight != 1.0) B *= std::sqrt(weight);
  return B;
}

void BodyResistance::body_pairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const {
  out.clear();
  for (const Accepted& p : accepted_) out.emplace_back(p.body_i, p.body_j);
}

void BodyResistance::bind(const BlockSparseMatrix& A) {
  // With headroom: a new largest pattern would otherwise reallocate inside the time step.
  if (opened_.capacity() < A.col().size()) opened_.reserve(A.col().size() + A.col().size() / 4 + 16);
  opened_.assign(A.col().size(), 0);
  for (Accepted& p : accepted_) {
    p.upper = A.find(p.body_i, p.body_j);
    p.opens_block = p.upper >= 0 && !opened_[std::size_t(p.upper)];
    if (p.opens_block) opened_[std::size_t(p.upper)] = 1;
  }
}

void BodyResistance::add_to(BlockSparseMatrix& A) const {
  // Serial, in pair order: every block receives its terms in a fixed order; a block's first pair
  // assigns its off-diagonal term (so R needs no zeroing), later pairs add theirs.
  for (std::size_t k = 0; k < accepted_.size(); ++k) {
    const Accepted& p = accepted_[k];
    const auto add = [&](const Mat6& ii, const Mat6& jj, const Mat6& ij) {
      A.diagonal(p.body_i) += ii;
      A.diagonal(p.body_j) += jj;
      if (p.opens_block)
        A.upper(p.upper) = ij;
      else
        A.upper(p.upper) += ij;
    };
    if (const ClosedForm& c = closed_[k]; c.on && !c.offset) {
      LubricationPair::add_centred_gram(c.d, c.c, c.weight, A.diagonal(p.body_i), A.diagonal(p.body_j),
                                        A.upper(p.upper), p.opens_block);
    } else if (c.on && !blocks_in_pair_pass_) {
      Mat6 &Rii = A.diagonal(p.body_i), &Rjj = A.diagonal(p.body_j), &Rij = A.upper(p.upper);
      if (p.opens_block)
        offset_corners(c.d, c.c, c.weight, c.xa, c.xb, adding(Rii), adding(Rjj), assigning(Rij));
      else
        offset_corners(c.d, c.c, c.weight, c.xa, c.xb, adding(Rii), adding(Rjj), adding(Rij));
    } else {
      add(block_ii_[k], block_jj_[k], block_ij_[k]);
    }
  }
}

void BodyResistance::sum_per_body(double* out) const {
  for (std::size_t k = 0; k < accepted_.size(); ++k) {
    const Accepted& p = accepted_[k];
    Eigen::Map<Vec6>(out + 6 * std::size_t(p.body_i)) += pair_force_[k].head<6>();
    Eigen::Map<Vec6>(out + 6 * std::size_t(p.body_j)) += pair_force_[k].tail<6>();
  }
}

BodyResistance::BodyRows BodyResistance::rows(std::size_t k) const {
  const ClosedForm& c = closed_[k];
  if (!c.on) return rows_[k];
  PairRows S;
  LubricationPair::rows(c.d, c.c, S);
  return body_rows(S, c.xa, c.xb, c.weight);
}

void BodyResistance::add_strain_force(const Eigen::Matrix3d& E, double* rhs) {
  parallel_for(std::int64_t(accepted_.size()), [&](std::int64_t k) {
    // Mode velocities of the ambient flow: only the relative velocity E L_ij of node j enters
    // (the rigid part Omega_inf cancels in every mode).
    if (const ClosedForm& c = closed_[k]; c.on) {
      pair_force_[k] = LubricationPair::centred_strain_wrench(c.d, c.c, c.weight, E * accepted_[k].arm);
      if (c.offset) carry(pair_force_[k], c.xa, c.xb);
      return;
    }
    const Eigen::Matrix<double, LubricationPair::kRows, 1> e =
        rows_[k].middleCols<3>(6).lazyProduct(E * accepted_[k].arm);
    pair_force_[k] = -(rows_[k].transpose().lazyProduct(e));
  });
  sum_per_body(rhs);
}

void BodyResistance::add_brownian(const RandomStream& noise, std::size_t nodes_per_body, double scale,
                                  double* FB) {
  parallel_for(std::int64_t(accepted_.size()), [&](std::int64_t k) {
    const Accepted& p = accepted_[k];
    // The draw depends only on the pair's identity: object (body_i, body_j), normals from index
    // 16 (node_a m + node_b), in the pair-noise stream (separate from the bodies' R_0 noise).
    const std::uint64_t object = (std::uint64_t(p.body_i) << 32) | p.body_j;
    const std::uint32_t base = 8u * std::uint32_t(p.node_a * nodes_per_body + p.node_b);
    Eigen::Matrix<double, LubricationPair::kRows, 1> beta;
    for (int q = 0; q < LubricationPair::kRows / 2; ++q) {
      const auto g = noise.normal2(object, base + std::uint32_t(q));
      beta[2 * q] = g[0];
      beta[2 * q + 1] = g[1];
    }
    if (const ClosedForm& c = closed_[k]; c.on) {
      pair_force_[k] = LubricationPair::centred_noise(c.d, c.c, c.weight, beta);
      if (c.offset) carry(pair_force_[k], c.xa, c.xb);
      pair_force_[k] *= scale;
      return;
    }
    pair_force_[k] = scale * rows_[k].transpose().lazyProduct(beta);
  });
  sum_per_body(FB);
}

Eigen::Matrix3d BodyResistance::stresslet_sum(const Eigen::Matrix3d& E, const double* dU) const {
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < accepted_.size(); ++k) {
    const Accepted& p = accepted_[k];
    const Eigen::Map<const Vec6> dUi(dU + 6 * std::size_t(p.body_i)), dUj(dU + 6 * std::size_t(p.body_j));
    // Hydrodynamic force of the pair on node j (f = -S^T S v, translational rows of node j).
    Vec3 Fj;
    if (const ClosedForm& c = closed_[k]; c.on) {
      Eigen::Matrix<double, 12, 1> v;
      if (c.offset)
        v << node_motion(dUi, c.xa), node_motion(dUj, c.xb);
      else
        v << dUi, dUj;
      v.segment<3>(6) += E * p.arm;
      // The force on node j is the force on body j (K^T leaves forces alone).
      Fj = LubricationPair::centred_force_j(c.d, c.c, c.weight, v);
    } else {
      const BodyRows& B = rows_[k];
      const Eigen::Matrix<double, LubricationPair::kRows, 1> y = B.leftCols<6>().lazyProduct(dUi) +
                                                                 B.rightCols<6>().lazyProduct(dUj) +
                                                                 B.middleCols<3>(6).lazyProduct(E * p.arm);
      Fj = -(B.middleCols<3>(6).transpose().lazyProduct(y));
    }
    // Moment of the equal and opposite pair forces: -L_ij (x) F_j, with the same arm as the strain
    // forcing so that R_SU = R_FE^T (about the two body centres for the Centre arm).
    // Sign: sigma = -p I + 2 mu E + (1/V) sum S; two bodies approaching along the compressional
    // axis d = (1,-1,0)/sqrt(2) are pushed apart (F_j along +d), giving S_xy > 0.
    const Eigen::Matrix3d M = -p.arm * Fj.transpose();
    S += 0.5 * (M + M.transpose());
  }
  return S;
}

}  // namespace fldsim::hydro
