#include "ScreenedRepulsion.hpp"

#include <algorithm>
#include <cmath>

#include "fldsim-sdk/forces/ForceRate.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim {

void ScreenedRepulsion::describe(ParamSchema& s) {
  s.number("strength", 100.0, "",
           "A*, in units of 6 pi mu a^2 rate (see `unit`): F = A exp(-kappa h) at gap h")
      .at_least(0.0);
  s.number("kappa", 100.0, "1/a", "inverse screening length kappa").greater(0.0);
  s.number("cutoff", 2.5, "a", "centre-to-centre distance beyond which the force is zero (per node pair)")
      .greater(0.0);
  s.choice("unit", "paper", {"paper", "diffusive", "shear"},
           "rate in A = A* 6 pi mu a^2 rate: paper = D0/a^2 for Pe < 1 and gammadot for Pe >= 1 (as "
           "`repulsion`), diffusive = D0/a^2, shear = gammadot (LAMMPS's documented FLD example)");
}

ScreenedRepulsion::ScreenedRepulsion(const Params& p)
    : strength_star_(p.number("strength")),
      kappa_(p.number("kappa")),
      cutoff_(p.number("cutoff")),
      unit_(p.text("unit")) {}

double ScreenedRepulsion::range(const System& system) const {
  double rmax = 0.0;
  for (const auto& n : system.shape().nodes()) rmax = std::max(rmax, n.radius);
  // The node pairs the neighbour list must hold: centre distance below the cutoff.
  return std::max(cutoff_, 2.0 * rmax);
}

double ScreenedRepulsion::amplitude(const System& system) const {
  const Physics& ph = system.physics();
  return strength_star_ * 6.0 * M_PI * ph.viscosity * force_rate(ph, unit_);  // a = 1
}

double ScreenedRepulsion::pair_energy(const System& system, const NodePair& pair) const {
  if (pair.distance >= cutoff_) return 0.0;
  const double gap = pair.distance - system.node_radius(pair.node_a) - system.node_radius(pair.node_b);
  return amplitude(system) / kappa_ * std::exp(-kappa_ * gap);
}

void ScreenedRepulsion::add(const System& system, const NodePairList& pairs, double* wrench,
                            Eigen::Matrix3d* virial) const {
  const double A = amplitude(system);
  if (A == 0.0) return;
  const auto& off = system.node_offsets();
  const std::size_t m = system.nodes_per_body();
  const auto& nodes = system.shape().nodes();  // once: node_radius() calls into the shape plugin
  for (const NodePair& p : pairs.pairs()) {
    if (p.distance >= cutoff_) continue;
    const double gap = p.distance - nodes[p.node_a].radius - nodes[p.node_b].radius;
    const Vec3 fj = A * std::exp(-kappa_ * gap) * (p.r / p.distance);  // pushes j away from i
    add_node_wrench(wrench + 6 * p.body_j, off[p.body_j * m + p.node_b], fj, Vec3::Zero());
    add_node_wrench(wrench + 6 * p.body_i, off[p.body_i * m + p.node_a], -fj, Vec3::Zero());
    // Molecular virial: the bodies' centre separation R = r - d_jb + d_ia (force.hpp).
    if (virial)
      *virial += (p.r - off[p.body_j * m + p.node_b] + off[p.body_i * m + p.node_a]) * fj.transpose();
  }
}

}  // namespace fldsim
