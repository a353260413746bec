// Inter-visibility of node pairs between two homonuclear dicolloids (unit nodes, c = node
// separation), Kumar & Higdon §2.1.1. Expected answers are worked out geometrically in the
// comments: a pair is hidden when the exit point of the centre-to-centre segment from a node lies
// inside the other node of the same body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// The smooth visibility weight (Visibility.hpp). Geometry: body i a c = 0.2 dicolloid along x at the
// origin, a single-node probe of body j on a circle of radius 2.2 about node 1 of i, angle t from
// +x. The exit point from node 1 at angle t is (0.1 + cos t, sin t); its depth outside node 0 is
// d(t) = sqrt((0.2 + cos t)^2 + sin^2 t) - 1 = sqrt(1.04 + 0.4 cos t) - 1, zero at cos t = -0.1
// (t* = 1.6710 rad): the sharp rule switches there, from visible (t < t*) to hidden.
namespace {

double probe_weight(double t, double width) {
  const Vec3 off_i[2] = {Vec3(-0.1, 0, 0), Vec3(0.1, 0, 0)};
  const Vec3 off_j[2] = {Vec3::Zero(), Vec3(0, 0, 50)};  // j's second node far away: never in the way
  const double radii[2] = {1.0, 1.0};
  const Vec3 r = 2.2 * Vec3(std::cos(t), std::sin(t), 0.0);
  return visibility_weight(off_i, off_j, radii, 2, 1, 0, r, 2.5, width);
}

}  // namespace

TEST(Visibility, SmoothWeightIsTheSharpRuleSpreadOverTheWidth) {
  const double t_star = std::acos(-0.1);
  for (const double t : {0.3, 1.0, 1.6, 1.74, 2.5, 3.0}) {
    // width 0 is the sharp rule exactly
    EXPECT_EQ(probe_weight(t, 0.0), t < t_star ? 1.0 : 0.0) << t;
    // away from the switch (|depth| > width / 2) the smooth weight is the sharp one
    const double depth = std::sqrt(1.04 + 0.4 * std::cos(t)) - 1.0;
    if (std::fabs(depth) > 0.05) {
      EXPECT_EQ(probe_weight(t, 0.1), probe_weight(t, 0.0)) << t;
    }
  }
  // at the switch, half: W(1/2) = 1/2
  EXPECT_NEAR(probe_weight(t_star, 0.1), 0.5, 1e-12);
}

TEST(Visibility, SmoothWeightIsContinuouslyDifferentiableWhereTheSharpOneJumps) {
  // Scan t across the switch: the sharp weight jumps by 1 between two neighbouring samples; the
  // smooth one changes by at most its largest slope times the step, and its slope (difference
  // quotient) changes by O(step), i.e. no kink: the largest change of the quotient between
  // neighbouring samples is below 1 % of its largest value.
  const double t_star = std::acos(-0.1), h = 1e-4;
  double largest_jump_sharp = 0.0, largest_step = 0.0, largest_slope = 0.0, largest_slope_change = 0.0;
  double previous_slope = 0.0;
  for (double t = t_star - 0.2; t < t_star + 0.2; t += h) {
    largest_jump_sharp =
        std::max(largest_jump_sharp, std::fabs(probe_weight(t + h, 0.0) - probe_weight(t, 0.0)));
    const double step = probe_weight(t + h, 0.1) - probe_weight(t, 0.1);
    const double slope = step / h;
    largest_step = std::max(largest_step, std::fabs(step));
    largest_slope = std::max(largest_slope, std::fabs(slope));
    if (t > t_star - 0.2)
      largest_slope_change = std::max(largest_slope_change, std::fabs(slope - previous_slope));
    previous_slope = slope;
  }
  EXPECT_EQ(largest_jump_sharp, 1.0);
  // dW/dt <= (15/8) / width * |dd/dt|, |dd/dt| <= 0.2 here: slope <= 3.75
  EXPECT_LE(largest_slope, 3.75);
  EXPECT_GT(largest_slope, 1.0);
  EXPECT_LT(largest_slope_change, 0.01 * largest_slope);
}

TEST(Visibility, SpheresAreAlwaysFullyVisible) {
  const Vec3 off[1] = {Vec3::Zero()};
  const double unit[1] = {1.0};
  EXPECT_EQ(visibility_weight(off, off, unit, 1, 0, 0, Vec3(2.1, 0.3, 0), 2.5, 0.1), 1.0);
  EXPECT_EQ(visibility_weight(off, off, unit, 1, 0, 0, Vec3(2.6, 0, 0), 2.5, 0.1), 0.0);
}
