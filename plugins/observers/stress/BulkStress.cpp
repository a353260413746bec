#include "BulkStress.hpp"

namespace fldsim::observers {

void BulkStress::particle_stress(const StressPieces& pieces, Eigen::Matrix3d (&parts)[4]) const {
  const double inv_v = 1.0 / volume_;
  parts[kHydrodynamic] = pieces.hydrodynamic * inv_v;
  parts[kInterparticle] = pieces.interparticle * inv_v;
  parts[kBrownian] = pieces.brownian * inv_v;
  parts[kParticleTotal] = parts[kHydrodynamic] + parts[kInterparticle] + parts[kBrownian];
}

Eigen::Matrix3d BulkStress::strain_rate() const {
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  e(0, 1) = e(1, 0) = 0.5 * shear_rate_;
  return e;
}

Eigen::Matrix3d BulkStress::total(const StressPieces& pieces) const {
  Eigen::Matrix3d parts[4];
  particle_stress(pieces, parts);
  return 2.0 * viscosity_ * strain_rate() + parts[kParticleTotal];
}

Rheology BulkStress::rheology(const Eigen::Matrix3d& s) {
  return {s(0, 1), s(0, 0) - s(1, 1), s(1, 1) - s(2, 2), -s.trace() / 3.0};
}

double BulkStress::relative_viscosity(const StressPieces& pieces) const {
  return total(pieces)(0, 1) / (viscosity_ * shear_rate_);
}

}  // namespace fldsim::observers
