#include "dynamics/PairGapStep.hpp"

#include <algorithm>
#include <cmath>

namespace fldsim {

PairGapSteps near_pair_gap_steps(const System& s, const NodePairList& pairs, const double* relative_velocity,
                                 double dt, double range) {
  PairGapSteps out;
  const auto& nodes = s.shape().nodes();
  const double gammadot = s.physics().shear_rate;
  const Vec3 vorticity = s.flow_vorticity();
  const auto& offsets = s.node_offsets();
  const std::size_t m = nodes.size();
  // Most listed pairs are far beyond the range (the list reaches the lubrication cutoff): skip a
  // pair whose end gap exceeds the range by more than its move can be, |move| <= dt (2 v + gammadot
  // (|r_y| + 3 o)) with v the largest node speed relative to the flow and o the largest offset
  // (|c_j - c_i|_y <= |r_y| + 2 o, |Omega_inf x (o_j - o_i)| <= gammadot o).
  double reach = 0.0, speed = 0.0;
  for (const Node& n : nodes) reach = std::max(reach, n.position.norm());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double* u = relative_velocity + 6 * i;
    speed = std::max(speed, std::hypot(u[0], u[1], u[2]) + reach * std::hypot(u[3], u[4], u[5]));
  }
  const double slack = 1e-12 + 1.01 * dt * 2.0 * speed;  // 1 %: rounding of the bound itself
  const double shear = 1.01 * dt * std::abs(gammadot);
  for (const NodePair& p : pairs.pairs()) {
    const double contact = nodes[p.node_a].radius + nodes[p.node_b].radius;
    if (p.distance - contact - range > slack + shear * (std::abs(p.r.y()) + 3.0 * reach)) continue;
    const Vec3& oi = offsets[std::size_t(p.body_i) * m + p.node_a];
    const Vec3& oj = offsets[std::size_t(p.body_j) * m + p.node_b];
    const double* ui = relative_velocity + 6 * std::size_t(p.body_i);
    const double* uj = relative_velocity + 6 * std::size_t(p.body_j);
    const Vec3 vi(ui[0], ui[1], ui[2]), wi(ui[3], ui[4], ui[5]);
    const Vec3 vj(uj[0], uj[1], uj[2]), wj(uj[3], uj[4], uj[5]);
    const Vec3 centres = p.r - oj + oi;
    const Vec3 move = dt * (Vec3(gammadot * centres.y(), 0.0, 0.0) + vorticity.cross(oj - oi) +
                            (vj + wj.cross(oj)) - (vi + wi.cross(oi)));
    const double start = (p.r - move).norm();
    if (std::min(start, p.distance) - contact >= range) continue;
    const double change = p.distance - start;
    const double flow = dt * gammadot * p.r.x() * p.r.y() / p.distance;
    out.sum_square += change * change;
    out.flow_square += flow * flow;
    ++out.pairs;
  }
  return out;
}

double pair_gap_list_range(const Shape& shape, double range) {
  double largest = 0.0;
  for (const Node& n : shape.nodes()) largest = std::max(largest, n.radius);
  return 2.0 * largest + range;
}

}  // namespace fldsim
