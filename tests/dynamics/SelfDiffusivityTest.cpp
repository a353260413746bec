// Short-time self-diffusivity of FLD sphere suspensions against the fit to simulation data
// d_s = 1 - 1.8315 phi (1 + 0.12 phi - 0.70 phi^2) (Riest et al., Soft Matter 2015; Abade et
// al. 2012; physics-reference-values.md section 1b): 0.47 +- 0.05 at phi = 0.3 and 0.25 +- 0.04
// at phi = 0.45 — the tolerances are those of the issue (the fit's spread plus FLD's model error).
// Estimator: one Brownian solve gives U = M F_B with <F_B F_B> = 2kT/dt R, so
// <U U^T> = (2kT/dt) M and D_s = kT <M_ii>/3 = <|U_i|^2> dt / 6, averaged over bodies, draws
// and hard-sphere Monte Carlo configurations. The rotational analogue is compared with
// D_r0 = kT/(8 pi mu a^3); it must lie above the translational one (Cichocki et al. 1999).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "Scene.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"

namespace fldsim::testing {
namespace {

struct Diffusivities {
  double translational, rotational;
};

// A hard-sphere Monte Carlo configuration of n spheres at phi with the fld model's defaults
// (CG tolerance 1e-8), the scene both estimators below start from.
std::unique_ptr<Scene> fld_spheres(double phi, std::size_t n, std::uint64_t seed, Physics ph,
                                   HydroRequest request) {
  ph.volume_fraction = phi;
  auto shape = make<Shape>("shape", "sphere");
  const double edge = std::cbrt(double(n) * shape->volume() / phi);
  auto scene = std::make_unique<Scene>(shape, n, edge, ph);
  geometry::MonteCarloOptions opt;
  opt.seed = seed;
  geometry::initialise_monte_carlo(*scene->system, opt);
  scene->finish(make<HydroModel>("hydro", "fld", "{tolerance: 1e-8}"), {}, request);
  return scene;
}

Diffusivities measure(double phi, std::size_t n, int configurations, int draws) {
  double sum_t = 0, sum_r = 0;
  std::int64_t count = 0;
  for (int c = 0; c < configurations; ++c) {
    Physics ph;
    ph.kT = 1.0;
    const auto owned = fld_spheres(phi, n, 100 + std::uint64_t(c), ph, HydroRequest{true, false, false});
    Scene& scene = *owned;
    const double dt = 1.0;  // any: U scales as 1/sqrt(dt)
    scene.evaluator->prepare(*scene.system, false);
    for (int d = 0; d < draws; ++d) {
      scene.evaluator->draw_brownian(*scene.system,
                                     RandomStream(7, RandomPurpose::BodyNoise, std::uint64_t(d)), dt);
      scene.evaluator->solve(*scene.system, true);
      const double* dU = scene.evaluator->relative_velocity();
      for (std::size_t i = 0; i < n; ++i) {
        sum_t += (dU[6 * i] * dU[6 * i] + dU[6 * i + 1] * dU[6 * i + 1] + dU[6 * i + 2] * dU[6 * i + 2]) *
                 dt / 6.0;
        sum_r +=
            (dU[6 * i + 3] * dU[6 * i + 3] + dU[6 * i + 4] * dU[6 * i + 4] + dU[6 * i + 5] * dU[6 * i + 5]) *
            dt / 6.0;
        ++count;
      }
    }
  }
  const double D0 = 1.0, Dr0 = 1.0 / (8.0 * M_PI * (1.0 / (6.0 * M_PI)));  // kT/(8 pi mu a^3) = 3/4
  return {sum_t / double(count) / D0, sum_r / double(count) / Dr0};
}

double riest_fit(double phi) {
  return 1.0 - 1.8315 * phi * (1.0 + 0.12 * phi - 0.70 * phi * phi);
}

// fldsim's R_0(phi) was fitted to this reference (tests/calibration/FitIsotropicResistance.cpp,
// other Monte Carlo seeds and draws); the fit reproduces it within 0.01 at phi = 0.1 ... 0.5. The
// tolerance is the reference's own uncertainty, +-0.02 absolute (reference notes §1b), plus that
// 0.01 fit residual; the estimate's statistical error here is ~0.004 (8000 body samples).
TEST(SelfDiffusivity, FldSpheresAtPhi030) {
  const auto d = measure(0.30, 500, 2, 8);
  RecordProperty("d_s", std::to_string(d.translational));
  RecordProperty("d_r", std::to_string(d.rotational));
  std::cout << "phi 0.30: d_s = " << d.translational << " (fit " << riest_fit(0.30)
            << "), d_r = " << d.rotational << "\n";
  EXPECT_NEAR(d.translational, riest_fit(0.30), 0.03);
  EXPECT_GT(d.rotational, d.translational);
}

TEST(SelfDiffusivity, FldSpheresAtPhi045) {
  const auto d = measure(0.45, 500, 2, 8);
  std::cout << "phi 0.45: d_s = " << d.translational << " (fit " << riest_fit(0.45)
            << "), d_r = " << d.rotational << "\n";
  EXPECT_NEAR(d.translational, riest_fit(0.45), 0.03);
  EXPECT_GT(d.rotational, d.translational);
}

// Rotation is much less hindered than translation in concentrated suspensions (Cichocki,
// Ekiel-Jezewska & Wajnryb 1999; at phi = 0.45 d_r ~ 0.57 against d_t ~ 0.25).
TEST(SelfDiffusivity, FldRotationalAboveTranslationalAtPhi030And045) {
  for (double phi : {0.30, 0.45}) {
    const auto d = measure(phi, 343, 1, 4);
    EXPECT_GT(d.rotational, d.translational) << "phi " << phi;
  }
}

// High-frequency viscosity eta'_inf: the hydrodynamic stress of hard-sphere configurations under a
// sudden shear (no Brownian or interparticle stress), eta'_inf/eta = 1 + <S^H_xy>/(V mu gammadot),
// against the fit of Riest et al. (Soft Matter 2015) to accelerated-SD data,
// 1 + 2.5 phi (1 + S)/(1 - phi (1 + S)), S = phi (1 + 0.95 phi - 2.15 phi^2): 2.654 at phi = 0.3,
// 5.661 at 0.45. fld's stresslet factor f_s was fitted to it (docs/fld-r0-fit.md; the cubic's
// residual < 1 % at these phi); the tolerance is the 5 %, which also covers the spread
// between Monte Carlo configurations of 500 spheres (~1 %, the fit's validation on fresh ones).
// Broken variant: Kumar & Higdon's f_s (the model before the refit) gives 3.08 and 7.20 (+16 %,
// +27 %, issue 11) and fails.
double high_frequency_viscosity(double phi, std::size_t n, int configurations) {
  double sum = 0.0;
  for (int c = 0; c < configurations; ++c) {
    Physics ph;
    ph.kT = 0.0;
    ph.shear_rate = 1.0;
    const auto owned = fld_spheres(phi, n, 300 + std::uint64_t(c), ph, HydroRequest{false, true, true});
    Scene& scene = *owned;
    HydroModel& hydro = *scene.hydro;
    hydro.assemble(*scene.system, scene.list.pairs());
    std::vector<double> F(6 * n, 0.0), dU(6 * n, 0.0);
    hydro.solve(*scene.system, F.data(), dU.data());
    const Eigen::Matrix3d S = hydro.stresslet_sum(*scene.system, scene.list.pairs(), dU.data());
    sum += 1.0 + S(0, 1) / (scene.system->box().volume() * ph.viscosity * ph.shear_rate);
  }
  return sum / double(configurations);
}

double riest_viscosity(double phi) {
  const double S = phi * (1.0 + 0.95 * phi - 2.15 * phi * phi);
  return 1.0 + 2.5 * phi * (1.0 + S) / (1.0 - phi * (1.0 + S));
}

TEST(HighFrequencyViscosity, FldSpheresAtPhi030And045MatchRiest) {
  for (double phi : {0.30, 0.45}) {
    const double eta = high_frequency_viscosity(phi, 500, 2);
    std::cout << "phi " << phi << ": eta'_inf = " << eta << " (Riest " << riest_viscosity(phi) << ")\n";
    EXPECT_NEAR(eta / riest_viscosity(phi), 1.0, 0.05) << "phi " << phi;
  }
}

}  // namespace
}  // namespace fldsim::testing
