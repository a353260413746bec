#include "fldsim/system.hpp"

namespace fldsim {

System::System(std::shared_ptr<const Shape> shape, std::size_t n_bodies, double box_edge, Physics physics)
    : shape_(std::move(shape)),
      box_(box_edge),
      physics_(physics),
      positions_(n_bodies, Vec3::Zero()),
      orientations_(n_bodies, Quat::Identity()),
      displacement_(n_bodies, Vec3::Zero()),
      nonaffine_(n_bodies, Vec3::Zero()) {
  update_nodes();
}

void System::update_nodes() {
  const auto& nodes = shape_->nodes();
  const std::size_t m = nodes.size();
  node_pos_.resize(size() * m);
  node_off_.resize(size() * m);
  for (std::size_t i = 0; i < size(); ++i) {
    const Eigen::Matrix3d R = orientations_[i].toRotationMatrix();
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3 off = R * nodes[k].position;
      node_off_[i * m + k] = off;
      // Node positions are not wrapped: the pair list takes minimum images of node separations.
      node_pos_[i * m + k] = positions_[i] + off;
    }
  }
}

}  // namespace fldsim
