#include "YukawaForce.hpp"

#include <algorithm>
#include <cmath>
#include <fldsim/rigid.hpp>

namespace yukawa {

void YukawaForce::describe(fldsim::ParamSchema& schema) {
  schema.number("strength", 10.0, "kT", "epsilon: pair energy at contact, U(a_i + a_j)").at_least(0.0);
  schema.number("debye_length", 0.05, "a", "screening length 1/kappa").greater(0.0);
  schema.number("cutoff", 5.0, "Debye lengths", "no force beyond this surface gap, in units of 1/kappa")
      .greater(0.0)
      .at_most(50.0);
}

YukawaForce::YukawaForce(const fldsim::Params& params)
    : strength_(params.number("strength")),
      kappa_(1.0 / params.number("debye_length")),
      cutoff_(params.number("cutoff") * params.number("debye_length")) {}

double YukawaForce::range(const fldsim::System& system) const {
  double largest = 0.0;
  for (const auto& node : system.shape().nodes()) largest = std::max(largest, node.radius);
  return 2.0 * largest + cutoff_;
}

double YukawaForce::energy(double r, double sigma) const {
  return strength_ * (sigma / r) * std::exp(-kappa_ * (r - sigma));
}

double YukawaForce::magnitude(double r, double sigma) const {
  return energy(r, sigma) * (kappa_ + 1.0 / r);
}

double YukawaForce::pair_energy(const fldsim::System& system, const fldsim::NodePair& pair) const {
  const double sigma = system.node_radius(pair.node_a) + system.node_radius(pair.node_b);
  if (pair.distance - sigma >= cutoff_ || pair.distance <= 0.0) return 0.0;
  return energy(pair.distance, sigma) - energy(sigma + cutoff_, sigma);  // shifted: zero at the cut
}

void YukawaForce::add(const fldsim::System& system, const fldsim::NodePairList& pairs, double* wrench,
                      Eigen::Matrix3d* virial) const {
  if (strength_ == 0.0) return;
  const std::size_t m = system.nodes_per_body();
  const auto& offsets = system.node_offsets();
  // The core's list holds every pair closer than range() and possibly more: filter by gap.
  for (const fldsim::NodePair& p : pairs.pairs()) {
    const double sigma = system.node_radius(p.node_a) + system.node_radius(p.node_b);
    if (p.distance - sigma >= cutoff_ || p.distance <= 0.0) continue;
    const fldsim::Vec3 fj = magnitude(p.distance, sigma) / p.distance * p.r;  // pushes j away from i
    fldsim::add_node_wrench(wrench + 6 * p.body_j, offsets[p.body_j * m + p.node_b], fj,
                            fldsim::Vec3::Zero());
    fldsim::add_node_wrench(wrench + 6 * p.body_i, offsets[p.body_i * m + p.node_a], -fj,
                            fldsim::Vec3::Zero());
    // The molecular virial (fldsim API 3): the separation of the two bodies' centres R = X_j - X_i,
    // i.e. the node separation r less the node offsets, times the force on node j.
    if (virial)
      *virial += (p.r - offsets[p.body_j * m + p.node_b] + offsets[p.body_i * m + p.node_a]) * fj.transpose();
  }
}

}  // namespace yukawa
