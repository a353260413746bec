// Rigid-body kinematics between body level (6 per body: U, Omega) and node level
// (6 per node: u, omega): u = U + Omega x r, omega = Omega; and the transpose, which sums node
// forces into body force F = sum f and torque T = sum (r x f + l).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // Vec3::cross

#include "fldsim/box.hpp"

namespace fldsim {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// 6x6 map K from body (U, Omega) to node (u, omega) for a node at offset r from the centre.
inline Mat6 node_kinematics(const Vec3& r) {
  Mat6 K = Mat6::Identity();
  // u = U - r x Omega  => block [0:3, 3:6] = -[r]_x
  K(0, 4) = r.z();
  K(0, 5) = -r.y();
  K(1, 3) = -r.z();
  K(1, 5) = r.x();
  K(2, 3) = r.y();
  K(2, 4) = -r.x();
  return K;
}

inline Vec3 node_velocity(const Vec3& U, const Vec3& Omega, const Vec3& r) {
  return U + Omega.cross(r);
}

// Add the wrench of a node force f and torque l applied at offset r to a body's (F, T).
inline void add_node_wrench(double* body6, const Vec3& r, const Vec3& f, const Vec3& l) {
  const Vec3 t = r.cross(f) + l;
  for (int k = 0; k < 3; ++k) {
    body6[k] += f[k];
    body6[3 + k] += t[k];
  }
}

}  // namespace fldsim
