// Node pairs of *different* bodies whose centre distance is below the largest range any
// plugin asked for. The core's cell list keeps a padded (skin) list and refreshes the
// separations every time the configuration changes, so consumers read `r` and `distance`
// directly and filter by their own range.
#pragma once

#include <cstdint>
#include <vector>

#include "fldsim/box.hpp"

namespace fldsim {

struct NodePair {
  std::uint32_t body_i, body_j;  // body_i < body_j
  std::uint16_t node_a, node_b;  // node index within body i and body j
  Vec3 r;                        // x(j,b) - x(i,a), minimum image under Lees–Edwards
  double distance;               // |r|
};

class NodePairList {
 public:
  const std::vector<NodePair>& pairs() const { return pairs_; }
  std::vector<NodePair>& pairs() { return pairs_; }
  // Every pair with distance < range() is in the list (and possibly some beyond it).
  double range() const { return range_; }
  void set_range(double r) { range_ = r; }

 private:
  std::vector<NodePair> pairs_;
  double range_ = 0.0;
};

}  // namespace fldsim
