// Equilibrium (Pe = 0, kT = 1) FLD spheres must keep the hard-sphere structure: the Boltzmann
// distribution does not depend on the hydrodynamics. With a configuration-dependent resistance
// this holds only with the thermal drift kT div M (Ermak & McCammon 1978); without it pairs pile
// up at contact, where the mobility falls. Measure: the mean number of neighbours per sphere
// with surface gap below 0.1 a (the contact shell of g(r)), from the Brownian run and from
// hydrodynamics-free hard-sphere Monte Carlo at the same phi; batch means give the errors, and
// the two must agree within 3 combined standard errors.
#include <gtest/gtest.h>

#include <cmath>

#include "Scene.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"

namespace fldsim::testing {
namespace {

double contact_neighbours(const System& s, double shell) {
  std::int64_t count = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double gap = s.box().minimum_image(s.positions()[j] - s.positions()[i]).norm() - 2.0;
      if (gap < shell) ++count;
    }
  return 2.0 * double(count) / double(s.size());
}

const double kPhi = 0.3, kShell = 0.1;
const std::size_t kN = 125;

MeanWithError monte_carlo_reference() {
  std::vector<double> batches;
  for (int b = 0; b < 8; ++b) {
    Physics ph;
    ph.volume_fraction = kPhi;
    auto shape = make<Shape>("shape", "sphere");
    System s(shape, kN, std::cbrt(double(kN) * shape->volume() / kPhi), ph);
    geometry::MonteCarloOptions opt;
    opt.seed = 500 + std::uint64_t(b);
    geometry::initialise_monte_carlo(s, opt);
    geometry::HardBodyMonteCarlo mc(s, 900 + std::uint64_t(b));
    double sum = 0;
    const int samples = 40;
    for (int k = 0; k < samples; ++k) {
      for (int sweep = 0; sweep < 5; ++sweep) mc.sweep();
      sum += contact_neighbours(s, kShell);
    }
    batches.push_back(sum / samples);
  }
  return mean_with_error(batches);
}

MeanWithError brownian_run(DriftScheme drift) {
  std::vector<double> batches;
  for (int b = 0; b < 4; ++b) {
    Physics ph;
    ph.kT = 1.0;
    ph.volume_fraction = kPhi;
    auto shape = make<Shape>("shape", "sphere");
    Scene scene(shape, kN, std::cbrt(double(kN) * shape->volume() / kPhi), ph);
    geometry::MonteCarloOptions opt;
    opt.seed = 700 + std::uint64_t(b);
    geometry::initialise_monte_carlo(*scene.system, opt);
    scene.finish(make<HydroModel>("hydro", "fld"), {make<ForceLaw>("force", "repulsion")},
                 HydroRequest{true, false, false});
    EulerMaruyama em(31 + std::uint64_t(b), true, drift, kN);
    const double dt = 1e-3;
    double sum = 0;
    int samples = 0;
    for (int k = 1; k <= 1500; ++k) {
      em.step(*scene.system, *scene.evaluator, dt, false);
      if (k > 300 && k % 50 == 0) {
        sum += contact_neighbours(*scene.system, kShell);
        ++samples;
      }
    }
    batches.push_back(sum / samples);
  }
  return mean_with_error(batches);
}

TEST(EquilibriumStructure, FldWithMidpointDriftKeepsHardSphereContactShell) {
  const MeanWithError mc = monte_carlo_reference();
  const MeanWithError bd = brownian_run(DriftScheme::Midpoint);
  const MeanWithError nodrift = brownian_run(DriftScheme::None);
  std::cout << "neighbours with gap < " << kShell << " a: MC " << mc.mean << " +- " << mc.se << ", FLD+drift "
            << bd.mean << " +- " << bd.se << ", FLD no drift " << nodrift.mean << " +- " << nodrift.se
            << "\n";
  EXPECT_NEAR(bd.mean, mc.mean, 3.0 * std::hypot(mc.se, bd.se));
}

}  // namespace
}  // namespace fldsim::testing
