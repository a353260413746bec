// Pair distribution: an ideal gas gives g = 1 (also in a sheared Lees–Edwards box), a simple
// cubic lattice gives its shells with coordination numbers 6, 12, 8 and map peaks at the
// lattice vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "FakeSink.hpp"
#include "PairDistribution.hpp"
#include "PairDistributionObserver.hpp"
#include "StatCheck.hpp"

using namespace fldsim;
using namespace fldsim::observers;

namespace {

std::vector<Vec3> ideal_gas(std::size_t n, double L, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, L);
  std::vector<Vec3> x(n);
  for (auto& v : x) v = Vec3(u(rng), u(rng), u(rng));
  return x;
}

// Uncorrelated positions: each unordered pair lands in a cell of volume dV with probability
// dV/V independently of every other pair that shares a body (uniform periodic box), so the
// pair count is binomial and the Poisson SE the distribution reports is exact to O(dV/V).
void check_ideal_gas(double strain) {
  const double L = 20.0;
  LeesEdwardsBox box(L);
  box.set_strain(strain);
  PairDistributionConfig cfg;
  cfg.range = 5.0;
  cfg.bins = 20;
  cfg.projections = {Projection::XY, Projection::XZ, Projection::YZ};
  PairDistribution pd(cfg);
  pd.check_box(box);
  std::mt19937_64 rng(99);
  for (int s = 0; s < 20; ++s) pd.add_sample(ideal_gas(1000, L, rng), box);

  const auto g = pd.g_r(), e = pd.g_r_stderr();
  const auto c = test::check_bins(g, std::vector<double>(g.size(), 1.0), e);
  EXPECT_LT(c.max_abs_z, test::bonferroni_bound(c.bins));
  EXPECT_NEAR(c.chi2, static_cast<double>(c.bins), 3.0 * std::sqrt(2.0 * c.bins));
  for (Projection p : cfg.projections) {
    // A map is point symmetric (each pair enters at r and -r): test the independent half.
    auto gm = pd.g_map(p), em = pd.g_map_stderr(p);
    const std::size_t half = gm.size() / 2;
    gm.resize(half);
    em.resize(half);
    const auto cm = test::check_bins(gm, std::vector<double>(half, 1.0), em);
    EXPECT_LT(cm.max_abs_z, test::bonferroni_bound(cm.bins)) << projection_name(p);
    EXPECT_NEAR(cm.chi2, static_cast<double>(cm.bins), 3.0 * std::sqrt(2.0 * cm.bins)) << projection_name(p);
  }
}

}  // namespace

TEST(PairDistribution, IdealGasIsOne) {
  check_ideal_gas(0.0);
}

TEST(PairDistribution, IdealGasIsOneInShearedLeesEdwardsBox) {
  check_ideal_gas(0.3);
}

TEST(PairDistribution, SimpleCubicLatticeShells) {
  const double s = 2.0;
  const int m = 10;
  const double L = s * m;
  LeesEdwardsBox box(L);
  std::vector<Vec3> x;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) x.emplace_back(s * (i + 0.25), s * (j + 0.25), s * (k + 0.25));
  PairDistributionConfig cfg;
  cfg.range = 4.5;  // map cells of 0.2 centred on multiples of s
  cfg.bins = 45;
  cfg.slab_half = 1.0;  // only the z = 0 layer (next layers at |z| = s = 2)
  PairDistribution pd(cfg);
  pd.add_sample(x, box);
  const double n = static_cast<double>(x.size());

  // Coordination numbers: neighbours per body in a window of +-0.15 around each shell radius.
  const auto& counts = pd.radial_counts();
  const auto r = pd.r_centres();
  auto neighbours = [&](double radius) {
    double sum = 0.0;
    for (std::size_t b = 0; b < counts.size(); ++b)
      if (std::abs(r[b] - radius) < 0.15 + 0.5 * pd.radial_width()) sum += counts[b];
    return sum / n;
  };
  EXPECT_DOUBLE_EQ(neighbours(s), 6.0);
  EXPECT_DOUBLE_EQ(neighbours(s * std::sqrt(2.0)), 12.0);
  EXPECT_DOUBLE_EQ(neighbours(s * std::sqrt(3.0)), 8.0);
  EXPECT_DOUBLE_EQ(neighbours(2.0 * s), 6.0);
  // g(r) vanishes away from the lattice distances s sqrt(k), k = 1, 2, 3, 4.
  for (std::size_t b = 0; b < counts.size(); ++b) {
    bool near_shell = false;
    for (int k = 1; k <= 5; ++k) near_shell |= std::abs(r[b] - s * std::sqrt(k)) < pd.radial_width();
    if (!near_shell) {
      EXPECT_EQ(counts[b], 0.0) << "r = " << r[b];
    }
  }
  // Front view: one neighbour per body at each in-plane lattice vector (i s, j s), |i|,|j| <= 2,
  // nothing elsewhere. The map's normalisation is N n dV, with n dV = (N - 1)/V * cell^2 * 2h.
  const auto g = pd.g_map(Projection::XY);
  const double per_body_norm = (n - 1.0) / box.volume() * pd.map_cell() * pd.map_cell() * 2.0 * cfg.slab_half;
  for (int a = 0; a < cfg.bins; ++a)
    for (int b = 0; b < cfg.bins; ++b) {
      const double u = -cfg.range + (a + 0.5) * pd.map_cell(), v = -cfg.range + (b + 0.5) * pd.map_cell();
      const bool lattice = std::abs(std::remainder(u, s)) < 1e-9 && std::abs(std::remainder(v, s)) < 1e-9 &&
                           !(std::abs(u) < 1e-9 && std::abs(v) < 1e-9);
      EXPECT_NEAR(g[a * cfg.bins + b] * per_body_norm, lattice ? 1.0 : 0.0, 1e-9) << u << ", " << v;
    }
}

TEST(PairDistribution, RejectsRangeBeyondHalfBox) {
  PairDistributionConfig cfg;
  cfg.range = 6.0;
  EXPECT_THROW(PairDistribution(cfg).check_box(LeesEdwardsBox(10.0)), std::invalid_argument);
}

TEST(PairDistributionObserver, WritesNormalisedMapsOfASampledRun) {
  // Two bodies at separation (1.5, 0.5, 0.2) in a box of edge 10: the front-view map holds
  // exactly one neighbour per body at +-(1.5, 0.5); its integral over the map times
  // n 2h = (N - 1)/V 2h is therefore 1 neighbour per body.
  class Dot : public Shape {
   public:
    const std::vector<Node>& nodes() const override { return nodes_; }
    double volume() const override { return 4.0; }

   private:
    std::vector<Node> nodes_{{Vec3::Zero(), 1.0}};
  };
  System sys(std::make_shared<Dot>(), 2, 10.0, Physics{});
  sys.positions()[0] = Vec3(1.0, 1.0, 1.0);
  sys.positions()[1] = Vec3(2.5, 1.5, 1.2);
  PairDistributionConfig cfg;
  cfg.range = 4.0;
  cfg.bins = 16;
  PairDistributionObserver obs(cfg);
  RunInfo run;
  NodePairList pairs;
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  StepView view{sys, pairs, run, nullptr, nullptr, nullptr, {}, 0.0};
  obs.sample(view, sink);
  obs.sample(view, sink);
  obs.finish(run, sink);
  const auto& map = sink.arrays.at("results/pair_distribution/g_xy");
  ASSERT_EQ(map.shape, (std::vector<std::size_t>{16, 16}));
  const double cell = 2.0 * cfg.range / cfg.bins;
  double integral = 0.0;
  for (double v : map.data) integral += v * cell * cell;
  EXPECT_NEAR(integral * (2.0 - 1.0) / 1000.0 * 2.0 * cfg.slab_half, 1.0, 1e-12);
  // The range must fit in half the box.
  PairDistributionConfig big;
  big.range = 6.0;
  PairDistributionObserver too_big(big);
  EXPECT_THROW(too_big.begin(sys, run, sink), std::invalid_argument);
}
