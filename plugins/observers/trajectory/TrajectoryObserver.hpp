// Writes the configuration as an H5MD trajectory (H5MD 1.1, particles group "bodies"; paths in
// fldsim/trajectory_layout.hpp):
//   box          attributes dimension = 3, boundary = periodic x3; `edges` time series of the
//                3x3 cell matrix whose second row carries the Lees-Edwards shift as a tilt, so
//                readers that know only H5MD (MDAnalysis) get the right periodic images
//   position     wrapped body centres, value [frames][N][3], unit "a"
//   orientation  unit quaternion scalar-first (w, x, y, z), value [frames][N][4]: H5MD draft
//                proposal 104 (not part of H5MD 1.1, so an attribute says so)
//   lees_edwards/offset, lees_edwards/strain   the continuous image shift strain * L and the
//                unwrapped strain (no H5MD element exists for them; ESPResSo uses the names)
//   shape/node_positions, shape/node_radii     the body in its own frame (for renderers)
// and, with `nodes: true`, the world-frame sphere nodes in a second particles group "nodes"
// (position [frames][N m][3] of intact bodies, fixed `radius` [N m]) for visualisation.
// Only the public API is used (fldsim/*.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "fldsim/observer.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

class TrajectoryObserver : public Observer {
 public:
  struct Options {
    bool nodes = false;
  };
  static void describe(ParamSchema& s);
  explicit TrajectoryObserver(const Params& p) : TrajectoryObserver(Options{p.flag("nodes")}) {}
  explicit TrajectoryObserver(Options options) : options_(options) {}

  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;

 private:
  void write_box_description(const char* box_path, ResultSink& out) const;
  void write_frame(const System& system, ResultSink& out);

  Options options_;
  // Frame buffers and sample shapes, sized in begin() so that a frame allocates nothing.
  std::vector<double> position_, orientation_, node_position_;
  std::vector<std::size_t> position_shape_, orientation_shape_, node_shape_;
  const std::vector<std::size_t> edge_shape_{3, 3}, scalar_shape_{};
  std::int64_t last_step_ = -1;
  bool has_frame_ = false;
};

}  // namespace fldsim
