// The pair-gap bound's measure (run.gap_step, dynamics/PairGapStep.hpp):
//  - PairGapStep: the gap change it reports for a node pair of two rotating dicolloids whose
//    minimum image crosses the sheared box's y face equals the exact change of the pair's
//    minimum-image distance between the start and the end of the step (start state rebuilt from
//    the end state, the velocities and the box's strain), to the O(dt^2) of a first-order move;
//    beside it the imposed flow's normal displacement gammadot dt r_x r_y / |r|; and it counts a
//    pair when its gap at the start or at the end is below the range.
//  - The bound in a run: an ideal gas (free draining, Pe 0) of spheres on a lattice whose
//    nearest neighbours are within the range: the relative displacement of two bodies has
//    variance 2 x 2 h per direction, so the mean square gap change is 4 h (O(h^2 / r^2) from
//    sliding: 5e-4 relative here), and the frames settle on the fewest equal pieces with
//    4 h <= l^2 (l^2 = 4 x 0.4 frame: thirds).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "Scene.hpp"
#include "dynamics/PairGapStep.hpp"
#include "observers/FakeSink.hpp"
#include "run/StepLoop.hpp"

namespace fldsim::testing {
namespace {

struct Geometry {
  Vec3 a, b;  // node a of body 0, node b of body 1 (wrapped)
};

// Exact minimum-image distance of node a of body 0 and node b of body 1 for the given centres,
// orientations and box strain.
double distance(const System& s, const std::vector<Vec3>& c, const std::vector<Quat>& q, double strain,
                int na, int nb) {
  LeesEdwardsBox box(s.box().edge());
  box.set_strain(strain);
  const Vec3 xa = c[0] + q[0] * s.shape().nodes()[std::size_t(na)].position;
  const Vec3 xb = c[1] + q[1] * s.shape().nodes()[std::size_t(nb)].position;
  return box.minimum_image(xb - xa).norm();
}

TEST(PairGapStep, FollowsNearPairsThroughTheLeesEdwardsBoundary) {
  Physics ph;
  ph.shear_rate = 2.0;
  auto shape = make<Shape>("shape", "dicolloid", "{a: 1, b: 1, c: 1.8}");  // nodes 0.9 a from the centre
  System s(shape, 2, 10.0, ph);
  const double strain = 0.37;
  s.box().set_strain(strain);
  const auto& nodes = shape->nodes();
  ASSERT_EQ(nodes.size(), 2u);
  // Body 0 just above the bottom face, its node 0 (at -z in the body) below its centre; node 1 of
  // body 1 (at +z) 0.004 a from it, below it, so body 1 itself sits near the top face and the
  // pair's minimum image crosses the face. Both axes along the pair, so the other node pairs are
  // 2-4 a apart; each body turned about its axis too.
  const Vec3 dir = Vec3(0.3, -1.0, 0.2).normalized();
  s.orientations()[0] =
      Quat::FromTwoVectors(Vec3::UnitZ(), -dir) * Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));
  s.orientations()[1] =
      Quat::FromTwoVectors(Vec3::UnitZ(), -dir) * Quat(Eigen::AngleAxisd(-1.1, Vec3::UnitZ()));
  s.positions()[0] = Vec3(5.0, 1.6, 5.0);
  const Vec3 xa = s.positions()[0] + s.orientations()[0] * nodes[0].position;
  Vec3 c1 = xa + (nodes[0].radius + nodes[1].radius + 0.004) * dir - s.orientations()[1] * nodes[1].position;
  s.box().wrap(c1);
  s.positions()[1] = c1;
  ASSERT_GT(c1.y(), 5.0);  // the pair's minimum image does cross the face
  s.update_nodes();

  NodePairList list;
  for (int na = 0; na < 2; ++na)
    for (int nb = 0; nb < 2; ++nb) {
      const Vec3 xi = s.positions()[0] + s.orientations()[0] * nodes[std::size_t(na)].position;
      const Vec3 xj = s.positions()[1] + s.orientations()[1] * nodes[std::size_t(nb)].position;
      const Vec3 r = s.box().minimum_image(xj - xi);
      list.pairs().push_back(NodePair{0, 1, std::uint16_t(na), std::uint16_t(nb), r, r.norm()});
    }
  // U - U_inf of both bodies, O(1); the step is short enough for first order to hold to 1e-3.
  const std::vector<double> dU{0.8, -1.3, 0.4, 1.7, -0.6, 0.9, -0.5, 1.1, 0.7, -1.2, 0.3, 1.4};
  const double dt = 1e-4;

  // The start of the step: each centre moved back by dt (U_inf(c) + dv), each offset rotated
  // back by dt (Omega_inf + dw), the box's strain back by gammadot dt.
  std::vector<Vec3> c0(2);
  std::vector<Quat> q0(2);
  for (int i = 0; i < 2; ++i) {
    const Vec3 dv(dU[6 * i], dU[6 * i + 1], dU[6 * i + 2]);
    const Vec3 w = s.flow_vorticity() + Vec3(dU[6 * i + 3], dU[6 * i + 4], dU[6 * i + 5]);
    c0[i] = s.positions()[i] - dt * (s.flow_velocity(s.positions()[i]) + dv);
    q0[i] = Quat(Eigen::AngleAxisd(-dt * w.norm(), w.normalized())) * s.orientations()[i];
  }
  const double start_strain = strain - ph.shear_rate * dt;

  for (std::size_t k = 0; k < list.pairs().size(); ++k) {
    const NodePair& p = list.pairs()[k];
    const double end = p.distance;
    const double start = distance(s, c0, q0, start_strain, p.node_a, p.node_b);
    ASSERT_NEAR(end, distance(s, s.positions(), s.orientations(), strain, p.node_a, p.node_b), 1e-12);
    NodePairList one;
    one.pairs().push_back(p);
    const PairGapSteps g = near_pair_gap_steps(s, one, dU.data(), dt, 100.0);
    ASSERT_EQ(g.pairs, 1u);
    const double exact = end - start;
    // The imposed flow's normal displacement of the pair, counted beside the gap change.
    const double flow = ph.shear_rate * dt * p.r.x() * p.r.y() / p.distance;
    EXPECT_NEAR(g.flow_square, flow * flow, 1e-15 * flow * flow);
    EXPECT_NEAR(g.mean_square(), g.sum_square + flow * flow, 1e-20);
    std::printf("pair %d-%d: distance %.6f, gap change %.6e against %.6e\n", p.node_a, p.node_b, end,
                std::sqrt(g.sum_square) * (exact < 0 ? -1 : 1), exact);
    // |exact| ~ dt |velocity| ~ 2e-4; the first-order move is off by O(dt^2 |velocity|^2) ~ 1e-7.
    EXPECT_NEAR(std::sqrt(g.sum_square), std::abs(exact), 1e-7);
    EXPECT_GT(std::abs(exact), 1e-5);  // the pair did move: the comparison is not 0 = 0

    // Counted when the gap at the start or at the end is below the range, and only then.
    const double contact = nodes[p.node_a].radius + nodes[p.node_b].radius;
    const double lower = std::min(start, end) - contact, upper = std::max(start, end) - contact;
    EXPECT_EQ(near_pair_gap_steps(s, one, dU.data(), dt, lower - 1e-6).pairs, 0u);
    EXPECT_EQ(near_pair_gap_steps(s, one, dU.data(), dt, lower + 1e-6).pairs, 1u);
    EXPECT_EQ(near_pair_gap_steps(s, one, dU.data(), dt, upper + 1e-6).pairs, 1u);
  }
  // The near pair alone at the default-like range 0.01 a.
  const PairGapSteps near = near_pair_gap_steps(s, list, dU.data(), dt, 0.01);
  EXPECT_EQ(near.pairs, 1u);
}

TEST(PairGapBound, MeasuresTheRelativeDiffusionOfNearPairs) {
  Physics ph;
  ph.kT = 1.0;
  auto shape = make<Shape>("shape", "sphere");
  const std::size_t n = 64;
  const double spacing = 8.0, edge = 4 * spacing;
  Scene scene(shape, n, edge, ph);
  for (std::size_t i = 0; i < n; ++i)
    scene.system->positions()[i] =
        spacing * Vec3(0.5 + double(i % 4), 0.5 + double((i / 4) % 4), 0.5 + double(i / 16));
  scene.finish(make<HydroModel>("hydro", "free_draining"), {}, HydroRequest{true, false, false});
  // Nearest neighbours at 8 a (gap 6 a), the next at 11.3 a: the range, gap 7.6 a, lies 2.5 SD
  // of the pairs' spread by the end (sqrt(4 t), t = 0.11) from both; the list must hold it.
  const double range = 7.6;
  scene.list.configure(2.0 + range + 0.1, 0.3);
  scene.list.update(*scene.system);
  const double frame = 1e-3;
  RunInfo info;
  info.dt = frame;
  StepControlSettings control;
  control.adaptive = true;
  control.error_control = false;
  control.frame = frame;
  control.gap_range = range;
  const double h_star = 0.4 * frame;
  control.gap_step = std::sqrt(4.0 * h_star);
  EulerMaruyama em(91, true, DriftScheme::Midpoint, n);
  std::vector<std::shared_ptr<Observer>> none;
  StepGuard guard;
  guard.max_overlap = INFINITY;  // an ideal gas
  StepLoop loop(*scene.system, em, *scene.evaluator, scene.list, none, info, true, true, control, guard);
  test::FakeSink sink;
  for (int f = 0; f < 10; ++f) loop.step(sink);
  const auto& st = loop.statistics();
  const std::int64_t steps0 = st.accepted_steps();
  const int frames = 100;
  std::vector<double> per_frame;  // mean square gap change per frame: independent draws
  for (int f = 0; f < frames; ++f) {
    const auto [sum0, pairs0] = st.gap_step_state();
    loop.step(sink);
    const auto [sum1, pairs1] = st.gap_step_state();
    ASSERT_GT(pairs1, pairs0);
    per_frame.push_back((sum1 - sum0) / (pairs1 - pairs0));
  }
  EXPECT_EQ(st.accepted_steps() - steps0, 3 * frames);  // every step a third of the frame
  const double h = frame / 3.0;
  EXPECT_EQ(st.max_dt(), h);
  const auto [sum, pairs] = st.gap_step_state();
  const double per_step = pairs / double(st.accepted_steps());
  EXPECT_NEAR(per_step, 3.0 * double(n), 2.0);  // the 192 nearest-neighbour pairs, none else
  const MeanWithError ms = mean_with_error(per_frame);
  std::printf("mean square gap step %.6g against 4 h = %.6g (SE %.2g), %.1f near pairs per step\n", ms.mean,
              4.0 * h, ms.se, per_step);
  EXPECT_NEAR(ms.mean, 4.0 * h, 3.0 * ms.se);
  EXPECT_NEAR(st.rms_gap_step(), std::sqrt(sum / pairs), 1e-15);

  // The checkpoint's step state: the gap steps and the gap step's rate come after the rest, so the
  // states of earlier builds restore: a34c4bc's (no gap rate of its own: its one rate was the
  // active bound's, here the gap bound's) to the same state, and the one before the gap steps
  // (three values shorter) with the gap step's rate and statistics at zero.
  const std::vector<double> state = loop.save_state();
  ASSERT_GT(state.back(), 0.0);             // the gap step's rate
  ASSERT_EQ(state[state.size() - 4], 0.0);  // the node step's: no node bound
  StepLoop copy(*scene.system, em, *scene.evaluator, scene.list, none, info, true, true, control, guard);
  copy.restore_state(state);
  EXPECT_EQ(copy.save_state(), state);
  std::vector<double> a34c4bc(state.begin(), state.end() - 1);
  a34c4bc[a34c4bc.size() - 3] = state.back();
  StepLoop previous(*scene.system, em, *scene.evaluator, scene.list, none, info, true, true, control, guard);
  previous.restore_state(a34c4bc);
  EXPECT_EQ(previous.save_state(), state);
  std::vector<double> earlier(state.begin(), state.end() - 3);
  StepLoop old(*scene.system, em, *scene.evaluator, scene.list, none, info, true, true, control, guard);
  old.restore_state(earlier);
  earlier.insert(earlier.end(), {0.0, 0.0, 0.0});
  EXPECT_EQ(old.save_state(), earlier);
}

}  // namespace
}  // namespace fldsim::testing
