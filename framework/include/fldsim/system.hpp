// The state of a suspension of N identical rigid bodies: centre positions and unit quaternions,
// the Lees–Edwards box, the physical parameters, and world-frame node positions derived from
// them. Internal units: node radius a = 1, kT = 1 for Brownian runs, viscosity mu = 1/(6 pi)
// so that 6 pi mu a = 1 and the time unit is a^2/D0 (D0 = kT/(6 pi mu a)); then Pe = gammadot.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "fldsim/box.hpp"
#include "fldsim/shape.hpp"

namespace fldsim {

using Quat = Eigen::Quaterniond;

struct Physics {
  double kT = 1.0;                               // 0 for a deterministic (non-Brownian) run
  double viscosity = 1.0 / (6.0 * 3.14159265358979323846);  // mu, so that 6 pi mu a = 1
  double shear_rate = 0.0;                       // gammadot, in 1/time
  double volume_fraction = 0.0;                  // true phi = N V_body / V_box
};

class FLDSIM_VISIBLE System {
 public:
  System() = default;
  System(std::shared_ptr<const Shape> shape, std::size_t n_bodies, double box_edge, Physics physics);

  std::size_t size() const { return positions_.size(); }
  const Shape& shape() const { return *shape_; }
  std::shared_ptr<const Shape> shape_ptr() const { return shape_; }
  std::size_t nodes_per_body() const { return shape_->nodes().size(); }
  std::size_t node_count() const { return size() * nodes_per_body(); }

  const LeesEdwardsBox& box() const { return box_; }
  LeesEdwardsBox& box() { return box_; }
  const Physics& physics() const { return physics_; }
  Physics& physics() { return physics_; }

  // Body state (centre = volume centroid).
  std::vector<Vec3>& positions() { return positions_; }
  const std::vector<Vec3>& positions() const { return positions_; }
  std::vector<Quat>& orientations() { return orientations_; }
  const std::vector<Quat>& orientations() const { return orientations_; }

  // Integral of U dt and of (U - U_inf(x)) dt since the start: unwrapped and non-affine
  // ("shear-corrected") displacements, kept by the integrator for diffusion measurements.
  std::vector<Vec3>& displacement() { return displacement_; }
  const std::vector<Vec3>& displacement() const { return displacement_; }
  std::vector<Vec3>& nonaffine_displacement() { return nonaffine_; }
  const std::vector<Vec3>& nonaffine_displacement() const { return nonaffine_; }

  double time() const { return time_; }
  void set_time(double t) { time_ = t; }
  std::int64_t step() const { return step_; }
  void set_step(std::int64_t s) { step_ = s; }

  // World-frame node data, valid after update_nodes(). Node k of body i is index i*m + k.
  void update_nodes();
  const std::vector<Vec3>& node_positions() const { return node_pos_; }
  // Node offset from its body centre in the world frame (R(q) r_body).
  const std::vector<Vec3>& node_offsets() const { return node_off_; }
  double node_radius(std::size_t k) const { return shape_->nodes()[k].radius; }
  // World-frame director of body i.
  Vec3 director(std::size_t i) const { return orientations_[i] * shape_->director(); }

  // Undisturbed flow u = gammadot*y*x at a point, and the body-level U_inf (6 per body:
  // velocity then angular velocity Omega_inf = -gammadot/2 z).
  Vec3 flow_velocity(const Vec3& x) const { return Vec3(physics_.shear_rate * x.y(), 0.0, 0.0); }
  Vec3 flow_vorticity() const { return Vec3(0.0, 0.0, -0.5 * physics_.shear_rate); }

 private:
  std::shared_ptr<const Shape> shape_;
  LeesEdwardsBox box_;
  Physics physics_;
  std::vector<Vec3> positions_;
  std::vector<Quat> orientations_;
  std::vector<Vec3> displacement_;
  std::vector<Vec3> nonaffine_;
  std::vector<Vec3> node_pos_;
  std::vector<Vec3> node_off_;
  double time_ = 0.0;
  std::int64_t step_ = 0;
};

}  // namespace fldsim
