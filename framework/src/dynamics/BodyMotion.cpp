#include "dynamics/BodyMotion.hpp"

#include <cmath>

#include "fldsim/parallel_loop.hpp"

namespace fldsim {

void BodySnapshot::save(const System& s) {
  positions = s.positions();
  orientations = s.orientations();
  strain = s.box().strain();
  time = s.time();
}

void BodySnapshot::restore(System& s) const {
  s.positions() = positions;
  s.orientations() = orientations;
  s.box().set_strain(strain);
  s.set_time(time);
  s.update_nodes();
}

void move_from(System& s, const BodySnapshot& base, const double* U, double h) {
  const std::size_t n = s.size();
  auto& x = s.positions();
  auto& q = s.orientations();
  parallel_for(n, [&](std::size_t i) {
    const double* u = U + 6 * i;
    x[i] = base.positions[i] + h * Vec3(u[0], u[1], u[2]);
    const Vec3 w(u[3], u[4], u[5]);
    // The rotation by h |w| about w / |w|; h may be negative (BrownianStressProbe's backward point).
    const double rate = w.norm();
    Quat dq = Quat::Identity();
    if (rate > 0.0 && h != 0.0) dq = Quat(Eigen::AngleAxisd(h * rate, w / rate));
    q[i] = (dq * base.orientations[i]).normalized();
  });
  s.box().set_strain(base.strain + h * s.physics().shear_rate);
  s.set_time(base.time + h);
  s.update_nodes();
}

void record_displacement(System& s, const double* U, const double* dU, double h) {
  auto& d = s.displacement();
  auto& na = s.nonaffine_displacement();
  for (std::size_t i = 0; i < s.size(); ++i) {
    d[i] += h * Vec3(U[6 * i], U[6 * i + 1], U[6 * i + 2]);
    na[i] += h * Vec3(dU[6 * i], dU[6 * i + 1], dU[6 * i + 2]);
  }
}

void wrap_into_box(System& s) {
  for (auto& x : s.positions()) s.box().wrap(x);
  s.update_nodes();
}

}  // namespace fldsim
