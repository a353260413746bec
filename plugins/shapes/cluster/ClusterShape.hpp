// Any rigid union of spheres given as rows [x, y, z, r]. Nodes are shifted so that the volume
// centroid of the union is the origin. Volume and centroid are exact when no point lies in three
// spheres (pairwise lens formulas), otherwise computed by the line integration of SphereUnion.hpp
// with its estimated error bound. The director is the given one or the principal axis of the
// node layout: the eigenvector with the largest eigenvalue of sum_k r_k^3 (p_k - c)(p_k - c)^T
// (node positions weighted by node volume), sign chosen so its largest component is positive.
#pragma once

#include <optional>

#include "fldsim-sdk/geometry/SphereUnion.hpp"
#include "fldsim/params.hpp"
#include "fldsim/shape.hpp"

namespace fldsim::shapes {

class ClusterShape : public Shape {
 public:
  explicit ClusterShape(const std::vector<Ball>& spheres, std::optional<Vec3> director = std::nullopt);
  explicit ClusterShape(const Params& p);
  static void describe(ParamSchema& s);

  const std::vector<Node>& nodes() const override { return nodes_; }
  double volume() const override { return geometry_.volume; }
  Vec3 director() const override { return director_; }
  // Whether volume and centroid are exact, and the estimated volume error otherwise.
  const VolumeAndCentroid& geometry() const { return geometry_; }

 private:
  std::vector<Node> nodes_;
  VolumeAndCentroid geometry_;
  Vec3 director_ = Vec3::UnitZ();
};

}  // namespace fldsim::shapes
