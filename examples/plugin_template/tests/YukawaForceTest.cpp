// Checks the built plugin file the way fldsim uses it: open it with Boost.DLL, read the plain
// descriptor, get the schema and make the object through the exported entry points, then
// compare the force between two nodes with the closed form
//   F(r) = epsilon (sigma / r) exp(-kappa (r - sigma)) (kappa + 1/r).
// Tolerance 1e-12 relative: the plugin evaluates the same closed form, so only round-off differs.
#include <gtest/gtest.h>

#include <boost/dll/shared_library.hpp>
#include <cmath>
#include <fldsim/api.hpp>
#include <fldsim/force.hpp>
#include <fldsim/plugin.hpp>
#include <memory>
#include <vector>

namespace {

using fldsim::Vec3;

// A body of one sphere node of radius 1 at `offset` from the centre (offset != 0 only to test
// torques).
class OneNode : public fldsim::Shape {
 public:
  explicit OneNode(Vec3 offset) : nodes_{{offset, 1.0}} {}
  const std::vector<fldsim::Node>& nodes() const override { return nodes_; }
  double volume() const override { return 4.0 * M_PI / 3.0; }

 private:
  std::vector<fldsim::Node> nodes_;
};

class YukawaPlugin : public ::testing::Test {
 protected:
  void SetUp() override { library_.load(YUKAWA_PLUGIN_FILE, boost::dll::load_mode::rtld_now); }

  // The object the plugin makes for these parameters (defaults for the others), as a ForceLaw.
  std::unique_ptr<fldsim::ForceLaw> make(double strength, double debye_length, double cutoff) {
    fldsim::ParamSchema schema;
    library_.get_alias<fldsim::PluginDescribeFn>("fldsim_describe")(schema);
    fldsim::Params params("forces[0]", "yukawa_test");
    for (const auto& spec : schema.specs())
      params.set(spec.name, *spec.default_value, {"yukawa_test", "forces[0]." + spec.name}, false);
    params.set("strength", strength, {"yukawa_test", "forces[0].strength"});
    params.set("debye_length", debye_length, {"yukawa_test", "forces[0].debye_length"});
    params.set("cutoff", cutoff, {"yukawa_test", "forces[0].cutoff"});
    fldsim::Component* made = library_.get_alias<fldsim::PluginCreateFn>("fldsim_create")(params);
    auto* law = dynamic_cast<fldsim::ForceLaw*>(made);
    if (!law) delete made;
    return std::unique_ptr<fldsim::ForceLaw>(law);
  }

  // Two bodies on the x axis at centre distance r; returns the 12 wrench components and the virial.
  static std::vector<double> wrench_at(const fldsim::ForceLaw& law, double r, Vec3 node_offset,
                                       Eigen::Matrix3d* virial) {
    fldsim::System system(std::make_shared<OneNode>(node_offset), 2, 50.0, fldsim::Physics{});
    system.positions()[0] = Vec3(10.0, 10.0, 10.0);
    system.positions()[1] = Vec3(10.0 + r, 10.0, 10.0);
    system.update_nodes();
    fldsim::NodePairList pairs;
    pairs.pairs().push_back({0, 1, 0, 0, Vec3(r, 0.0, 0.0), r});
    std::vector<double> wrench(12, 0.0);
    law.add(system, pairs, wrench.data(), virial);
    return wrench;
  }

  boost::dll::shared_library library_;  // declared first: outlives the objects the tests make
};

TEST_F(YukawaPlugin, DescriptorMatchesThisFldsim) {
  const auto& d = library_.get<const fldsim_plugin_descriptor_t>("fldsim_plugin_descriptor");
  EXPECT_EQ(d.api_major, unsigned(FLDSIM_API_MAJOR));
  EXPECT_LE(d.api_minor, unsigned(FLDSIM_API_MINOR));
  EXPECT_STREQ(d.kind, "force");
  EXPECT_STREQ(d.name, "yukawa");
  EXPECT_STREQ(d.build_tag, FLDSIM_BUILD_TAG);
}

TEST_F(YukawaPlugin, ForceBetweenTwoSpheresIsTheClosedForm) {
  const double epsilon = 10.0, debye = 0.1, r = 2.05, sigma = 2.0, kappa = 1.0 / debye;
  const auto law = make(epsilon, debye, 5.0);
  ASSERT_TRUE(law);
  Eigen::Matrix3d virial = Eigen::Matrix3d::Zero();
  const auto w = wrench_at(*law, r, Vec3::Zero(), &virial);

  const double expected = epsilon * sigma / r * std::exp(-kappa * (r - sigma)) * (kappa + 1.0 / r);
  EXPECT_NEAR(expected, 62.06024596702746, 1e-12 * expected);  // the same value worked by hand
  EXPECT_NEAR(w[6], expected, 1e-12 * expected);               // body 1 pushed along +x
  EXPECT_NEAR(w[0], -expected, 1e-12 * expected);              // Newton's third law
  for (int k : {1, 2, 3, 4, 5, 7, 8, 9, 10, 11}) EXPECT_EQ(w[k], 0.0) << "component " << k;
  EXPECT_NEAR(virial(0, 0), r * expected, 1e-12 * r * expected);  // sum R (x) f_j, R = X_j - X_i
}

TEST_F(YukawaPlugin, OffCentreNodeGivesTorqueRCrossF) {
  const auto law = make(10.0, 0.1, 5.0);
  ASSERT_TRUE(law);
  const double r = 2.05, f = 62.06024596702746;
  const auto w = wrench_at(*law, r, Vec3(0.0, 0.0, 0.5), nullptr);
  // T = (0, 0, 0.5) x (+-f, 0, 0) = (0, +-0.5 f, 0).
  EXPECT_NEAR(w[10], 0.5 * f, 1e-12 * f);
  EXPECT_NEAR(w[4], -0.5 * f, 1e-12 * f);
}

TEST_F(YukawaPlugin, NoForceBeyondTheCutoff) {
  const double debye = 0.1, cutoff = 5.0;
  const auto law = make(10.0, debye, cutoff);
  ASSERT_TRUE(law);
  fldsim::System system(std::make_shared<OneNode>(Vec3::Zero()), 2, 50.0, fldsim::Physics{});
  EXPECT_DOUBLE_EQ(law->range(system), 2.0 + cutoff * debye);
  EXPECT_GT(wrench_at(*law, 2.0 + 0.999 * cutoff * debye, Vec3::Zero(), nullptr)[6], 0.0);
  EXPECT_EQ(wrench_at(*law, 2.0 + 1.001 * cutoff * debye, Vec3::Zero(), nullptr)[6], 0.0);
}

// The energy the oracle samples is the potential of the force: F = -dU/dr by central differences
// (h = 1e-6 a: error (h^2/6) U''' ~ 1e-9 relative), and zero at the cut (shifted, not truncated).
TEST_F(YukawaPlugin, EnergyIsThePotentialOfTheForce) {
  const auto law = make(10.0, 0.1, 5.0);
  ASSERT_TRUE(law);
  const fldsim::PairEnergy* energy = fldsim::pair_energy_of(*law);
  ASSERT_NE(energy, nullptr) << "yukawa declares no pair energy";
  fldsim::System system(std::make_shared<OneNode>(Vec3::Zero()), 2, 50.0, fldsim::Physics{});
  auto u = [&](double r) { return energy->pair_energy(system, {0, 1, 0, 0, Vec3(r, 0.0, 0.0), r}); };
  const double h = 1e-6;
  for (double r : {2.001, 2.05, 2.2, 2.4, 2.49}) {
    const double f = wrench_at(*law, r, Vec3::Zero(), nullptr)[6];
    EXPECT_NEAR(-(u(r + h) - u(r - h)) / (2 * h), f, 1e-6 * f) << "r = " << r;
  }
  EXPECT_NEAR(u(2.5 - 1e-12), 0.0, 1e-9);  // continuous at the cut r_c = 2 + 5 x 0.1
  EXPECT_EQ(u(2.5 + 1e-9), 0.0);
}

}  // namespace
