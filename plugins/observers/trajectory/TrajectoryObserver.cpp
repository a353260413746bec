#include "TrajectoryObserver.hpp"

#include <cmath>

#include "fldsim/trajectory_layout.hpp"

namespace fldsim {

namespace {
constexpr const char* kNodesBox = "/particles/nodes/box";
constexpr const char* kNodesBoxEdges = "/particles/nodes/box/edges";
constexpr const char* kNodesPosition = "/particles/nodes/position";
constexpr const char* kNodesRadius = "/particles/nodes/radius";
}  // namespace

void TrajectoryObserver::describe(ParamSchema& s) {
  s.flag("nodes", false, "also write the world-frame sphere nodes of every body (/particles/nodes)");
}

void TrajectoryObserver::write_box_description(const char* box_path, ResultSink& out) const {
  out.write_int_attribute(box_path, "dimension", {3});
  out.write_string_list_attribute(box_path, "boundary", {"periodic", "periodic", "periodic"});
  out.write_attribute(
      box_path, "lees_edwards",
      "shear flow u = gammadot y x: the image at y + L is shifted by lees_edwards/offset in x");
}

void TrajectoryObserver::begin(const System& system, const RunInfo& run, ResultSink& out) {
  (void)run;
  const std::size_t n = system.size();
  position_.assign(3 * n, 0.0);
  orientation_.assign(4 * n, 0.0);
  position_shape_ = {n, 3};
  orientation_shape_ = {n, 4};
  write_box_description(trajectory::kBox, out);
  out.write_attribute(trajectory::kOrientation, "convention",
                      "unit quaternion, scalar first (w, x, y, z), body frame to lab frame; "
                      "H5MD draft proposal 104 (particles quaternion), not part of H5MD 1.1");
  out.write_attribute(trajectory::kBoxEdges, "description",
                      "rows: cell vectors (L,0,0), (s,L,0), (0,0,L); s = Lees-Edwards shift of the image "
                      "above, reduced to [-L/2, L/2)");
  out.write_attribute(
      trajectory::kOffset, "description",
      "x shift of the periodic image above (y + L): strain * L, continuous (not reduced mod L)");
  out.write_attribute(trajectory::kStrain, "description", "accumulated shear strain gammadot t (unwrapped)");
  {
    const auto& nodes = system.shape().nodes();
    std::vector<double> centres, radii;
    for (const auto& node : nodes) {
      centres.insert(centres.end(), {node.position.x(), node.position.y(), node.position.z()});
      radii.push_back(node.radius);
    }
    out.write_array(trajectory::kShapeNodes, {nodes.size(), 3}, centres.data(), "a",
                    "sphere node centres in the body frame (rotate by orientation, add position)");
    out.write_array(trajectory::kShapeRadii, {nodes.size()}, radii.data(), "a", "sphere node radii");
  }
  if (options_.nodes) {
    const std::size_t m = system.nodes_per_body();
    node_position_.assign(3 * n * m, 0.0);
    node_shape_ = {n * m, 3};
    write_box_description(kNodesBox, out);
    std::vector<double> radius(n * m);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < m; ++k) radius[i * m + k] = system.node_radius(k);
    out.write_array(kNodesRadius, {n * m}, radius.data(), "a", "sphere node radii, in the order of position");
  }
  if (due(system.step(), system.time())) write_frame(system, out);
}

void TrajectoryObserver::sample(const StepView& view, ResultSink& out) {
  write_frame(view.system, out);
}

void TrajectoryObserver::write_frame(const System& system, ResultSink& out) {
  // One frame per step, even if the core calls both begin() and sample() at the same step.
  if (has_frame_ && system.step() == last_step_) return;
  const std::size_t n = system.size();
  const auto& box = system.box();
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 x = system.positions()[i];
    box.wrap(x);
    for (int d = 0; d < 3; ++d) position_[3 * i + d] = x[d];
    const Quat& q = system.orientations()[i];
    orientation_[4 * i] = q.w();
    orientation_[4 * i + 1] = q.x();
    orientation_[4 * i + 2] = q.y();
    orientation_[4 * i + 3] = q.z();
  }
  const std::int64_t step = system.step();
  const double time = system.time();
  // Lees-Edwards as a triclinic cell: the image above is shifted by s = strain * L; any shift
  // that differs by a multiple of L describes the same images, and the smallest is clearest.
  const double L = box.edge();
  const double offset = box.strain() * L;
  const double tilt = L * (box.strain() - std::floor(box.strain() + 0.5));
  const double cell[9] = {L, 0.0, 0.0, tilt, L, 0.0, 0.0, 0.0, L};
  const double strain = box.strain();
  out.append_sample(trajectory::kBoxEdges, step, time, edge_shape_, cell, "a");
  out.append_sample(trajectory::kPosition, step, time, position_shape_, position_.data(), "a");
  out.append_sample(trajectory::kOrientation, step, time, orientation_shape_, orientation_.data(), "");
  out.append_sample(trajectory::kOffset, step, time, scalar_shape_, &offset, "a");
  out.append_sample(trajectory::kStrain, step, time, scalar_shape_, &strain, "");
  if (options_.nodes) {
    // Nodes of a body stay together around its wrapped centre (not wrapped one by one).
    const std::size_t m = system.nodes_per_body();
    const auto& off = system.node_offsets();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < m; ++k)
        for (int d = 0; d < 3; ++d)
          node_position_[3 * (i * m + k) + d] = position_[3 * i + d] + off[i * m + k][d];
    out.append_sample(kNodesBoxEdges, step, time, edge_shape_, cell, "a");
    out.append_sample(kNodesPosition, step, time, node_shape_, node_position_.data(), "a");
  }
  last_step_ = step;
  has_frame_ = true;
}

}  // namespace fldsim
