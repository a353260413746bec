// Inter-visibility of node pairs between two homonuclear dicolloids (unit nodes, c = node
// separation), Kumar & Higdon §2.1.1. Expected answers are worked out geometrically in the
// comments: a pair is hidden when the exit point of the centre-to-centre segment from a node lies
// inside the other node of the same body.
#include <gtest/gtest.h>

#include <set>

#include "HydroTestSupport.hpp"
#include "fldsim-sdk/lubrication/Visibility.hpp"

using namespace fldsim;
using namespace fldsim::hydro;

namespace {

using PairSet = std::set<std::pair<int, int>>;

struct Result {
  PairSet within, visible;
};

// Body i: nodes at ci +/- (c/2) ui; body j: nodes at cj +/- (c/2) uj (node 0 = minus end).
Result classify(double c, const Vec3& ci, const Vec3& ui, const Vec3& cj, const Vec3& uj,
                double cutoff = 2.5) {
  const Vec3 off_i[2] = {-0.5 * c * ui, 0.5 * c * ui};
  const Vec3 off_j[2] = {-0.5 * c * uj, 0.5 * c * uj};
  const double radii[2] = {1.0, 1.0};
  Result res;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const Vec3 r = (cj + off_j[b]) - (ci + off_i[a]);
      if (r.norm() < cutoff) res.within.insert({a, b});
      if (nodes_visible(off_i, off_j, radii, 2, a, b, r, cutoff)) res.visible.insert({a, b});
    }
  return res;
}

}  // namespace

TEST(Visibility, EndToEndOnePairWithinCutoff) {
  // c = 0.2 along x; body j's nodes at x = 2.5, 2.7 (centre 2.6): node distances (1,0) 2.4, (0,0) and
  // (1,1) 2.6, (0,1) 2.8: only (1,0) is within 2.5. Its segment leaves node 1 of i at x = 1.1 (i's
  // node 0 covers [-1.1, 0.9]) and node 0 of j at x = 1.5 (j's node 1 covers [1.7, 3.7]): visible.
  const auto r = classify(0.2, Vec3::Zero(), Vec3::UnitX(), Vec3(2.6, 0, 0), Vec3::UnitX());
  EXPECT_EQ(r.within, (PairSet{{1, 0}}));
  EXPECT_EQ(r.visible, (PairSet{{1, 0}}));
}

TEST(Visibility, EndToEndOnlyTheFacingPairOfFour) {
  // c = 0.2 along x, node x-positions -0.1, 0.1 | 2.1, 2.3 (gap 0 between the facing nodes).
  // Distances: (1,0) 2.0, (0,0) 2.2, (1,1) 2.2, (0,1) 2.4: all four within 2.5. Pairs through the
  // far node of a body leave it at x = -0.1 + 1 = 0.9, inside node 1 of body i (|0.9 - 0.1| < 1), or
  // enter body j at x = 2.3 - 1 = 1.3, inside its node 0 (|1.3 - 2.1| < 1): hidden. Only (1,0) counts.
  const auto r = classify(0.2, Vec3::Zero(), Vec3::UnitX(), Vec3(2.2, 0, 0), Vec3::UnitX());
  EXPECT_EQ(r.within.size(), 4u);
  EXPECT_EQ(r.visible, (PairSet{{1, 0}}));
}

TEST(Visibility, TConfigurationTwoOfFour) {
  // Body i along x (nodes (-0.1,0,0), (0.1,0,0)); body j along y above it, nodes (0,2.1,0), (0,2.3,0).
  // Distances: to (0,2.1): sqrt(0.01 + 4.41) = 2.102; to (0,2.3): sqrt(0.01 + 5.29) = 2.302: all four
  // within 2.5. Towards the near node of j: exit from node a of i at (-/+0.1,0) + d, d = (+/-0.1, 2.1)/2.102,
  // distance 1.011 from i's other node: outside; entry into j's near node at (0,2.1) - d, 1.10 from
  // (0,2.3): outside -> visible. Towards j's far node (0,2.3): entry point (0,2.3) - (+/-0.043, 0.999)
  // lies 0.80 from (0,2.1), inside j's near node -> hidden. Visible: (0,0), (1,0).
  const auto r = classify(0.2, Vec3::Zero(), Vec3::UnitX(), Vec3(0, 2.2, 0), Vec3::UnitY());
  EXPECT_EQ(r.within.size(), 4u);
  EXPECT_EQ(r.visible, (PairSet{{0, 0}, {1, 0}}));
}

TEST(Visibility, SideBySideParallelAllFourVisible) {
  // Two c = 0.2 dicolloids along x, side by side at y = 0 and y = 2.1. Same-end pairs: distance 2.1,
  // d = (0,1), exit at (-/+0.1, 1), distance sqrt(0.04 + 1) = 1.02 from the other node: visible. Cross
  // pairs: distance sqrt(0.04 + 4.41) = 2.110, d = (0.2, 2.1)/2.110, exit from node 0 of i at
  // (-0.0052, 0.9955), distance 1.0010 from (0.1, 0): just outside -> visible (and symmetric for j).
  // All four within 2.5 and all four visible: the buried lens is too small to hide a pair here.
  const auto r = classify(0.2, Vec3::Zero(), Vec3::UnitX(), Vec3(0, 2.1, 0), Vec3::UnitX());
  EXPECT_EQ(r.within.size(), 4u);
  EXPECT_EQ(r.visible.size(), 4u);
}

TEST(Visibility, CutoffScalesWithMeanRadius) {
  const Vec3 off[1] = {Vec3::Zero()};
  const double small[1] = {0.5};
  // Two spheres of radius 0.5 at distance 1.3: below 2.5 * 0.5 = 1.25? No (1.3 > 1.25): rejected;
  // at 1.2: accepted.
  EXPECT_FALSE(nodes_visible(off, off, small, 1, 0, 0, Vec3(1.3, 0, 0), 2.5));
  EXPECT_TRUE(nodes_visible(off, off, small, 1, 0, 0, Vec3(1.2, 0, 0), 2.5));
}
