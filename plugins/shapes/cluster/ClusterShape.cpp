#include "ClusterShape.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "fldsim/error.hpp"

namespace fldsim::shapes {
namespace {

Vec3 principal_axis(const std::vector<Node>& nodes) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const auto& n : nodes) m += std::pow(n.radius, 3) * n.position * n.position.transpose();
  if (m.norm() == 0.0) return Vec3::UnitZ();  // a single sphere or concentric spheres
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  Vec3 axis = eig.eigenvectors().col(2);  // eigenvalues in increasing order
  Eigen::Index k;
  axis.cwiseAbs().maxCoeff(&k);
  return axis[k] < 0.0 ? Vec3(-axis) : axis;
}

}  // namespace

ClusterShape::ClusterShape(const std::vector<Ball>& spheres, std::optional<Vec3> director) {
  if (spheres.empty()) throw Error("cluster: at least one sphere is needed");
  for (const auto& b : spheres)
    if (!(b.radius > 0.0)) throw Error("cluster: every sphere radius must be > 0");
  geometry_ = union_volume_centroid(spheres);
  for (const auto& b : spheres) nodes_.push_back({b.centre - geometry_.centroid, b.radius});
  geometry_.centroid = Vec3::Zero();
  if (director) {
    if (!(director->norm() > 0.0)) throw Error("cluster: director must be a non-zero vector");
    director_ = director->normalized();
  } else {
    director_ = principal_axis(nodes_);
  }
}

}  // namespace fldsim::shapes
