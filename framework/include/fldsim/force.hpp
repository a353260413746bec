// A force law between nodes of different bodies (e.g. the paper's short-range repulsion).
#pragma once

#include <Eigen/Core>

#include "fldsim/neighbours.hpp"
#include "fldsim/plugin_base.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

class FLDSIM_VISIBLE ForceLaw : public Component {
 public:
  // Largest node centre distance at which the law acts (the core's pair list covers it).
  virtual double range(const System& system) const = 0;
  // Add body forces and torques (6 per body: F then T) of all pairs in `pairs` to `wrench`.
  // If `virial` is not null, also add sum over node pairs of r (x) f_j, where r = x_j - x_i and
  // f_j is the force on node j; the interparticle stress is -virial / V.
  virtual void add(const System& system, const NodePairList& pairs, double* wrench,
                   Eigen::Matrix3d* virial) const = 0;
};

}  // namespace fldsim
