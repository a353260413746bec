#include "oracle/PairVirial.hpp"

#include <algorithm>

namespace fldsim::oracle {

PairVirial::PairVirial(const System& s, std::vector<const ForceLaw*> laws) : laws_(std::move(laws)) {
  for (const ForceLaw* law : laws_) range_ = std::max(range_, law->range(s));
  list_.configure(range_, 0.0);
  one_.pairs().resize(1);
  one_.set_range(range_);
  wrench_.assign(6 * s.size(), 0.0);
}

Virials PairVirial::measure(const System& s) {
  Virials v;
  if (laws_.empty()) return v;
  list_.update(s);
  const std::size_t m = s.nodes_per_body();
  const auto& off = s.node_offsets();
  for (const NodePair& p : list_.pairs().pairs()) {
    if (p.distance >= range_) continue;
    one_.pairs()[0] = p;
    for (const ForceLaw* law : laws_) law->add(s, one_, wrench_.data(), nullptr);
    double* wi = wrench_.data() + 6 * p.body_i;
    double* wj = wrench_.data() + 6 * p.body_j;
    const Vec3 fj(wj[0], wj[1], wj[2]);
    const Vec3 R = p.r - off[p.body_j * m + p.node_b] + off[p.body_i * m + p.node_a];
    v.body += R * fj.transpose();
    v.node += p.r * fj.transpose();
    std::fill(wi, wi + 6, 0.0);
    std::fill(wj, wj + 6, 0.0);
  }
  return v;
}

}  // namespace fldsim::oracle
