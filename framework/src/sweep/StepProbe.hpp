// `fldsim sweep --timed K`: each point's cost from K timed frames of the point itself, instead of
// the cost model. Every point still to run is started as its own short `fldsim run` (the point's
// experiment with run.duration = K frames, observers from the start, no checkpoints, output in a scratch directory that is
// removed afterwards); its loop time per frame, measured by the run itself, times the point's
// frames is the estimate. It includes what the model cannot know: CG iterations at this phi and
// Pe, the shape's nodes, adaptive steps per frame, this machine and its load now.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sweep/SweepPoints.hpp"

namespace fldsim {

// Times every point that is not Done (one probe at a time, on the point's own thread count) and
// replaces its cost_seconds by frames x measured seconds per frame x threads (timed = true). A
// probe that fails leaves the point's model estimate and is reported on `log`. Returns the
// number of points timed.
std::size_t time_points(const SweepPlan& plan, std::vector<PointState>& points, int frames,
                        const std::string& program, std::ostream& log);

// The loop's milliseconds per frame from a run's log ("done: N steps in T (X ms/step, ..."), or a
// negative value if the log has no such line.
double logged_ms_per_frame(const std::string& log_text);

}  // namespace fldsim
