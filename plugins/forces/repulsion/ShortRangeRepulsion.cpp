#include "ShortRangeRepulsion.hpp"

#include <algorithm>
#include <cmath>

#include "fldsim-sdk/forces/ForceRate.hpp"
#include "fldsim/rigid.hpp"

namespace fldsim {

void ShortRangeRepulsion::describe(ParamSchema& s) {
  s.number("prefactor", 10.0, "", "C_p*, in units of 8 pi mu a^2 rate (see `unit`); the paper uses 10")
      .at_least(0.0);
  s.number("delta_min", 1e-3, "a", "range of the force: acts for surface gaps below delta_min").greater(0.0);
  s.number("delta_num", 1e-5, "a", "gaps 0 <= gap < delta_num are evaluated at delta_num (the paper's clamp)")
      .greater(0.0);
  s.choice("overlap", "plateau", {"plateau", "wall"},
           "overlapping nodes (gap < 0): plateau = the constant F(delta_num), as for 0 <= gap < delta_num; "
           "wall = F(delta_num) (1 + overlap / wall_length), at most wall_factor F(delta_num) "
           "(docs/time_steps.md, \"The repulsion's force cap\": what it costs)");
  s.number("wall_length", 1e-4, "a", "overlap over which the wall's force grows by F(delta_num)")
      .greater(0.0);
  s.number("wall_factor", 10.0, "", "the wall's largest force, in units of F(delta_num)").at_least(1.0);
  s.choice("unit", "paper", {"paper", "diffusive", "shear"},
           "rate in C_p = C_p* 8 pi mu a^2 rate: paper = D0/a^2 for Pe < 1 and gammadot for Pe >= 1; "
           "diffusive = D0/a^2; shear = gammadot");
}

ShortRangeRepulsion::ShortRangeRepulsion(const Params& p)
    : prefactor_star_(p.number("prefactor")),
      delta_min_(p.number("delta_min")),
      delta_num_(p.number("delta_num")),
      wall_length_(p.number("wall_length")),
      wall_factor_(p.text("overlap") == "plateau" ? 1.0 : p.number("wall_factor")),
      unit_(p.text("unit")) {
  if (delta_num_ >= delta_min_) p.fail("delta_num", "expected a number < delta_min");
}

double ShortRangeRepulsion::range(const System& system) const {
  double rmax = 0.0;
  for (const auto& n : system.shape().nodes()) rmax = std::max(rmax, n.radius);
  return 2.0 * rmax + delta_min_;
}

double ShortRangeRepulsion::prefactor(const System& system) const {
  const Physics& ph = system.physics();
  return prefactor_star_ * 8.0 * M_PI * ph.viscosity * force_rate(ph, unit_);  // a = 1
}

double ShortRangeRepulsion::magnitude(double gap, double prefactor, double delta_min, double delta_num,
                                      const Wall& wall) {
  if (gap >= delta_min) return 0.0;
  const double delta = std::max(gap, delta_num);
  const double eta = 1.0 - delta / delta_min;
  const double g = eta - 0.5 * eta * eta;
  const double f = prefactor * (delta_min / delta) * g * g * g;
  if (gap >= 0.0) return f;
  return f * std::min(1.0 - gap / wall.length, wall.factor);  // the wall (factor 1: the plateau)
}

double ShortRangeRepulsion::energy(double gap, double prefactor, double delta_min, double delta_num,
                                   const Wall& wall) {
  if (gap >= delta_min) return 0.0;
  const double x = std::max(gap, delta_num) / delta_min, x2 = x * x;
  const double u =
      prefactor * delta_min / 8.0 * (-std::log(x) - 11.0 / 12.0 + x2 * (1.5 + x2 * (-0.75 + x2 / 6.0)));
  if (gap >= delta_num) return u;
  const double f = magnitude(delta_num, prefactor, delta_min, delta_num, wall);
  if (gap >= 0.0) return u + f * (delta_num - gap);
  // Overlap d = -gap: F = f (1 + d / length) up to d_c = (factor - 1) length, then f factor.
  const double d = -gap, dc = (wall.factor - 1.0) * wall.length;
  if (d <= dc) return u + f * (delta_num + d + 0.5 * d * d / wall.length);
  return u + f * (delta_num + dc + 0.5 * dc * dc / wall.length + wall.factor * (d - dc));
}

double ShortRangeRepulsion::pair_energy(const System& system, const NodePair& pair) const {
  const double gap = pair.distance - system.node_radius(pair.node_a) - system.node_radius(pair.node_b);
  if (gap >= delta_min_) return 0.0;
  return energy(gap, prefactor(system), delta_min_, delta_num_, {wall_length_, wall_factor_});
}

void ShortRangeRepulsion::add(const System& system, const NodePairList& pairs, double* wrench,
                              Eigen::Matrix3d* virial) const {
  const double cp = prefactor(system);
  if (cp == 0.0) return;
  const std::size_t m = system.nodes_per_body();
  const auto& off = system.node_offsets();
  // Serial: the pairs inside delta_min are few, and a fixed order keeps sums reproducible.
  const auto& nodes = system.shape().nodes();  // once: node_radius() calls into the shape plugin
  for (const NodePair& p : pairs.pairs()) {
    const double gap = p.distance - nodes[p.node_a].radius - nodes[p.node_b].radius;
    const double f = magnitude(gap, cp, delta_min_, delta_num_, {wall_length_, wall_factor_});
    if (f == 0.0) continue;
    const Vec3 d = p.r / p.distance;
    const Vec3 fj = f * d;  // pushes j away from i
    add_node_wrench(wrench + 6 * p.body_j, off[p.body_j * m + p.node_b], fj, Vec3::Zero());
    add_node_wrench(wrench + 6 * p.body_i, off[p.body_i * m + p.node_a], -fj, Vec3::Zero());
    // Molecular virial: the bodies' centre separation R = r - d_jb + d_ia (force.hpp).
    if (virial)
      *virial += (p.r - off[p.body_j * m + p.node_b] + off[p.body_i * m + p.node_a]) * fj.transpose();
  }
}

}  // namespace fldsim
