// Free-pair functions of two equal unit spheres computed through a hydro plugin (the real option
// parsing, assembly and solve), for comparison with the exact two-sphere hydrodynamics of
// tests/data/two_sphere_exact.csv (bench/twobody/free_pair.py defines the same quantities):
//   G, H    relative mobility along / across the line of centres for forces F2 = -F1, torque-free:
//           U2 - U1 = F.[G dd + H (I - dd)]/(3 pi mu a)               (Batchelor 1976);
//   A, B    relative velocity of a force- and torque-free pair in a pure strain E:
//           U2 - U1 - E.r = -[A dd + B (I - dd)].E.r                    (Batchelor & Green 1972);
//   C       rotation of each sphere of that pair relative to the fluid: W - Omega_inf = C d x (E.d);
//   Xr, Yr  relative rotation for torques L2 = -L1, force-free:
//           W2 - W1 = L.[Xr dd + Yr (I - dd)]/(4 pi mu a^3).
// The strain is that of the simple shear u = y e_x: the model's velocities relative to the ambient
// flow do not see its rotation, so they are those of the pure strain E = sym(grad u).
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "HydroTestSupport.hpp"
#include "fldsim/hydro.hpp"
#include "plugins/PluginRegistry.hpp"

namespace fldsim::hydro::test {

struct FreePair {
  double G = 0, H = 0, A = 0, B = 0, C = 0, Xr = 0, Yr = 0;
};

using PluginOptions = std::vector<std::pair<std::string, ParamValue>>;

inline Params plugin_params(const PluginInfo& info, const PluginOptions& given) {
  Params p("hydro", "test");
  for (const auto& spec : info.schema.specs())
    if (spec.default_value)
      p.set(spec.name, *spec.default_value, ParamOrigin{"test", "hydro." + spec.name}, false);
  for (const auto& [name, value] : given) p.set(name, value, ParamOrigin{"test", "hydro." + name});
  return p;
}

// Velocities (relative to the ambient flow) of two unit spheres at x0 and x0 + s d under the
// wrench F (12 values), in simple shear of rate `shear_rate`.
inline std::vector<double> pair_velocities(HydroModel& model, double s, const Vec3& d,
                                           const std::vector<double>& F, double shear_rate) {
  const double L = 40.0;
  System sys(sphere_shape(), 2, L, physics(0.0, shear_rate, 0.0));
  sys.positions()[0] = Vec3(0.5 * L, 0.5 * L, 0.5 * L);
  sys.positions()[1] = sys.positions()[0] + s * d;
  sys.update_nodes();
  HydroRequest req;
  req.brownian = false;
  req.shear = shear_rate != 0.0;
  model.configure(sys, req);
  model.assemble(sys, brute_force_pairs(sys, model.pair_range(sys)));
  std::vector<double> dU(12, 0.0);
  model.solve(sys, F.data(), dU.data());
  return dU;
}

inline FreePair free_pair(const PluginRegistry& registry, const std::string& plugin,
                          const PluginOptions& given, double s) {
  PluginOptions options = given;
  options.emplace_back("tolerance", 1e-12);
  const auto model =
      registry.create<HydroModel>("hydro", plugin, plugin_params(registry.find("hydro", plugin), options));
  const double mu = Physics{}.viscosity;
  const Vec3 ex = Vec3::UnitX(), ey = Vec3::UnitY();
  FreePair out;
  auto wrench = [](int offset, const Vec3& v) {
    std::vector<double> F(12, 0.0);
    for (int k = 0; k < 3; ++k) {
      F[offset + k] = -v[k];
      F[6 + offset + k] = v[k];
    }
    return F;
  };
  auto rel = [](const std::vector<double>& dU, int offset, const Vec3& axis) {
    return (Eigen::Map<const Vec3>(dU.data() + 6 + offset) - Eigen::Map<const Vec3>(dU.data() + offset))
        .dot(axis);
  };
  out.G = rel(pair_velocities(*model, s, ex, wrench(0, ex), 0.0), 0, ex) * 3.0 * kPi * mu;
  out.H = rel(pair_velocities(*model, s, ex, wrench(0, ey), 0.0), 0, ey) * 3.0 * kPi * mu;
  out.Xr = rel(pair_velocities(*model, s, ex, wrench(3, ex), 0.0), 3, ex) * 4.0 * kPi * mu;
  out.Yr = rel(pair_velocities(*model, s, ex, wrench(3, ey), 0.0), 3, ey) * 4.0 * kPi * mu;
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(0, 1) = E(1, 0) = 0.5;
  const std::vector<double> none(12, 0.0);
  {
    const Vec3 d = Vec3(1, 1, 0).normalized();  // E.d = d/2: extension along the line of centres
    const Vec3 Er = E * (s * d);
    const auto dU = pair_velocities(*model, s, d, none, 1.0);
    const Vec3 v = Eigen::Map<const Vec3>(dU.data() + 6) - Eigen::Map<const Vec3>(dU.data());
    out.A = -v.dot(Er) / Er.squaredNorm();
  }
  {
    const Vec3 d = ex;  // E.d = e_y/2, perpendicular to d
    const Vec3 Er = E * (s * d);
    const auto dU = pair_velocities(*model, s, d, none, 1.0);
    const Vec3 v = Eigen::Map<const Vec3>(dU.data() + 6) - Eigen::Map<const Vec3>(dU.data());
    out.B = -v.dot(Er) / Er.squaredNorm();
    const Vec3 axis = d.cross(E * d);
    out.C = Eigen::Map<const Vec3>(dU.data() + 3).dot(axis) / axis.squaredNorm();
  }
  return out;
}

}  // namespace fldsim::hydro::test
