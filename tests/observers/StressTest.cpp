// Bulk stress: Einstein viscosity from dilute stresslets, the virial of a hand-built pair, and
// the observer's output through the sink.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "BulkStress.hpp"
#include "FakeSink.hpp"
#include "StressObserver.hpp"

using namespace fldsim;
using namespace fldsim::observers;

namespace {

constexpr double kPi = std::numbers::pi;
const double kMu = 1.0 / (6.0 * kPi);

class SphereShape : public Shape {
 public:
  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override { return 4.0 / 3.0 * kPi; }

 private:
  std::vector<Node> nodes_{{Vec3::Zero(), 1.0}};
};

// Stresslet of a free sphere in a straining flow: S = (20/3) pi mu a^3 E (Batchelor 1970).
StressPieces dilute_spheres(int n, double shear_rate) {
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  e(0, 1) = e(1, 0) = 0.5 * shear_rate;
  StressPieces p;
  p.hydrodynamic = n * (20.0 / 3.0) * kPi * kMu * e;
  return p;
}

}  // namespace

TEST(BulkStress, EinsteinViscosityOfDiluteSpheres) {
  const int n = 100;
  const double V = 1.0e5, gd = 0.7;
  const double phi = n * 4.0 / 3.0 * kPi / V;
  const BulkStress bulk(V, kMu, gd);
  const StressPieces p = dilute_spheres(n, gd);
  // Einstein (1906): eta_r = 1 + 5/2 phi.
  EXPECT_NEAR(bulk.relative_viscosity(p), 1.0 + 2.5 * phi, 1e-12);
  Eigen::Matrix3d parts[4];
  bulk.particle_stress(p, parts);
  const Rheology r = BulkStress::rheology(parts[kParticleTotal]);
  EXPECT_NEAR(r.shear / (kMu * gd), 2.5 * phi, 1e-12);
  EXPECT_NEAR(r.n1, 0.0, 1e-15);
  EXPECT_NEAR(r.n2, 0.0, 1e-15);
  EXPECT_NEAR(r.pressure, 0.0, 1e-15);
}

TEST(BulkStress, InterparticleStressOfAPairIsMinusRFOverV) {
  // Two bodies, repulsive central force F = 3 along r = x_j - x_i on body j (and -F on i).
  // The pieces hold -sum R (x) f_j (observer.hpp), as the core builds them (R = X_j - X_i).
  const Vec3 r(1.5, 0.8, 0.3);
  const Vec3 f = 3.0 * r.normalized();
  StressPieces p;
  p.interparticle = -r * f.transpose();
  const double V = 50.0;
  const BulkStress bulk(V, kMu, 1.0);
  Eigen::Matrix3d parts[4];
  bulk.particle_stress(p, parts);
  const Eigen::Matrix3d expected = -r * f.transpose() / V;
  EXPECT_LT((parts[kInterparticle] - expected).norm(), 1e-15);
  // Central forces carry no torque: the stress is symmetric (angular momentum balance).
  EXPECT_LT((parts[kInterparticle] - parts[kInterparticle].transpose()).norm(), 1e-15);
  // Virial pressure (Irving–Kirkwood / Clausius): Pi = r.F / (3V) > 0 for repulsion.
  EXPECT_NEAR(BulkStress::rheology(parts[kInterparticle]).pressure, r.dot(f) / (3.0 * V), 1e-15);
  // Repulsion between a pair aligned in the compressional quadrant (r_x r_y < 0) raises the
  // shear stress: sigma_xy = -r_x F_y / V > 0.
  const Vec3 rc(-1.0, 1.0, 0.0);
  p.interparticle = -rc * (2.0 * rc.normalized()).transpose();
  bulk.particle_stress(p, parts);
  EXPECT_GT(BulkStress::rheology(parts[kInterparticle]).shear, 0.0);
}

TEST(StressObserver, WritesEinsteinViscosityAndParts) {
  const int n = 64;
  const double L = 40.0, gd = 2.0;
  Physics ph;
  ph.shear_rate = gd;
  System sys(std::make_shared<SphereShape>(), n, L, ph);
  RunInfo run;
  run.total_steps = 100;
  run.dt = 1e-3;
  NodePairList pairs;
  StressObserver obs;
  EXPECT_TRUE(obs.needs().stress);
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  StressPieces p = dilute_spheres(n, gd);
  const Vec3 r(1.0, -1.0, 0.0), f = 4.0 * r.normalized();
  p.interparticle = -r * f.transpose();
  for (int s = 0; s < 8; ++s) {
    sys.set_step(s);
    StepView view{sys, pairs, run, nullptr, nullptr, &p, {}, 0.0};
    obs.sample(view, sink);
  }
  obs.finish(run, sink);
  const double V = L * L * L, phi = n * 4.0 / 3.0 * kPi / V;
  const double eta_p = -r.x() * f.y() / V / (kMu * gd);
  EXPECT_NEAR(sink.scalar("results/stress/eta_r").value, 1.0 + 2.5 * phi + eta_p, 1e-12);
  EXPECT_NEAR(sink.scalar("results/stress/eta_hydrodynamic").value, 2.5 * phi, 1e-12);
  EXPECT_NEAR(sink.scalar("results/stress/eta_interparticle").value, eta_p, 1e-12);
  EXPECT_NEAR(sink.scalar("results/stress/Pi_interparticle").value, r.dot(f) / (3.0 * V) / (kMu * gd), 1e-12);
  // kT = 1: the same pressure in kT/a^3 is the raw stress.
  EXPECT_NEAR(sink.scalar("results/stress/Pi_interparticle_kT").value, r.dot(f) / (3.0 * V), 1e-15);
  // Z = 1 + Pi_P/(n kT) with n = N/V, kT = 1: 1 + r.f/(3 N).
  EXPECT_NEAR(sink.scalar("results/stress/Z").value, 1.0 + r.dot(f) / (3.0 * n), 1e-12);
  EXPECT_EQ(sink.scalar("results/stress/Z").unit, "1");
  // Particle shear stress in kT/a^3 (kT = 1): the raw sigma_xy.
  EXPECT_NEAR(sink.scalar("results/stress/shear_stress_kT").value, (2.5 * phi + eta_p) * kMu * gd, 1e-15);
  // No Brownian stress was provided: it is reported absent, not as a measured zero.
  EXPECT_EQ(sink.scalars.count("results/stress/eta_brownian"), 0u);
  EXPECT_EQ(sink.arrays.count("results/stress/sigma_brownian"), 0u);
  // A constant series has zero standard error.
  EXPECT_NEAR(sink.scalar("results/stress/eta_r").stderr_value, 0.0, 1e-15);
  // The written mean tensor is symmetric.
  const auto& t = sink.arrays.at("results/stress/sigma_particle").data;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(t[3 * i + j], t[3 * j + i], 1e-15);
  EXPECT_EQ(sink.series.at("timeseries/stress/eta_r").steps.size(), 8u);
  // Units: viscosity ratios are dimensionless, N1/N2/Pi are stresses in mu*gammadot, raw
  // stresses are in kT/a^3 (Brownian internal units: a = 1, kT = 1).
  EXPECT_EQ(sink.scalar("results/stress/eta_r").unit, "1");
  EXPECT_EQ(sink.scalar("results/stress/eta_hydrodynamic").unit, "1");
  EXPECT_EQ(sink.scalar("results/stress/N1").unit, "mu*gammadot");
  EXPECT_EQ(sink.scalar("results/stress/Pi_interparticle_kT").unit, "kT/a^3");
  EXPECT_EQ(sink.arrays.at("results/stress/sigma_particle").unit, "kT/a^3");
}

TEST(StressObserver, NonBrownianStressUnitIsSixPiMuGammadot) {
  // kT = 0: internal time is 1/gammadot (gammadot = 1), so raw stresses are in 6 pi mu gammadot.
  Physics ph;
  ph.kT = 0.0;
  ph.shear_rate = 1.0;
  System sys(std::make_shared<SphereShape>(), 8, 40.0, ph);
  RunInfo run;
  run.total_steps = 10;
  run.dt = 1e-3;
  NodePairList pairs;
  StressObserver obs;
  test::FakeSink sink;
  obs.begin(sys, run, sink);
  StressPieces p = dilute_spheres(8, 1.0);
  for (int s = 0; s < 4; ++s) {
    sys.set_step(s);
    StepView view{sys, pairs, run, nullptr, nullptr, &p, {}, 0.0};
    obs.sample(view, sink);
  }
  obs.finish(run, sink);
  EXPECT_EQ(sink.arrays.at("results/stress/sigma_particle").unit, "6*pi*mu*gammadot");
  EXPECT_EQ(sink.scalar("results/stress/eta_r").unit, "1");
  EXPECT_EQ(sink.scalars.count("results/stress/shear_stress_kT"), 0u);
}
