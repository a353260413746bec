// [x]x, the cross-product matrix ([x]x v = x x v), for the lubrication sources. Core-private to the
// SDK library (not installed).
#pragma once

#include <Eigen/Core>

#include "fldsim/rigid.hpp"

namespace fldsim::hydro {

inline Eigen::Matrix3d cross_matrix(const Vec3& x) {
  Eigen::Matrix3d m;
  m << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return m;
}

}  // namespace fldsim::hydro
