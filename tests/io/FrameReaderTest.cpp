// read_last_frame returns the last frame the trajectory observer appended (not the first,
// not an average), so a run can start from an earlier result file.
#include <gtest/gtest.h>

#include <cmath>

#include "IoTestSupport.hpp"
#include "TinyDimer.hpp"
#include "TrajectoryObserver.hpp"
#include "fldsim/error.hpp"
#include "io/FrameReader.hpp"
#include "io/Hdf5ResultSink.hpp"

namespace fldsim {
namespace {

TEST(FrameReader, ReturnsTheLastAppendedFrame) {
  test::ScratchDir dir;
  const std::string path = dir.file("run.h5");
  System s = test::tiny_system(2, 8.0);
  {
    Hdf5ResultSink sink(path, false);
    TrajectoryObserver obs(TrajectoryObserver::Options{false});
    RunInfo run;
    NodePairList pairs;
    obs.begin(s, run, sink);
    const StepView view{s, pairs, run, nullptr, nullptr, nullptr, {}, 1.0};
    for (int frame = 1; frame <= 3; ++frame) {
      s.set_step(100 * frame);
      s.set_time(0.1 * frame);
      s.box().set_strain(0.3 * frame);
      s.positions()[0] = Vec3(1.0 * frame, 2, 3);
      s.positions()[1] = Vec3(4, 5, 0.5 * frame);
      s.orientations()[1] = Quat(Eigen::AngleAxisd(0.2 * frame, Vec3(1, 2, 3).normalized()));
      obs.sample(view, sink);
    }
    sink.commit();
  }
  const Checkpoint c = read_last_frame(path);
  ASSERT_EQ(c.positions.size(), 2u);
  // Frame 3, positions inside the box so wrapping changes nothing; values are stored exactly.
  EXPECT_EQ(c.positions[0], Vec3(3, 2, 3));
  EXPECT_EQ(c.positions[1], Vec3(4, 5, 1.5));
  const Quat q3(Eigen::AngleAxisd(0.2 * 3, Vec3(1, 2, 3).normalized()));  // as written for frame 3
  EXPECT_EQ(c.orientations[1].coeffs(), q3.coeffs());
  EXPECT_EQ(c.orientations[0].coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(c.box_edge, 8.0);
  EXPECT_EQ(c.strain, 0.3 * 3);
  EXPECT_EQ(c.step, 300);
  EXPECT_EQ(c.time, 0.1 * 3);
  ASSERT_EQ(c.displacement.size(), 2u);
  EXPECT_EQ(c.displacement[1], Vec3::Zero());
}

TEST(FrameReader, FileWithoutTrajectoryIsAnError) {
  test::ScratchDir dir;
  const std::string path = dir.file("no_traj.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.write_scalar("/results/x", 1, 0, "", "");
    sink.commit();
  }
  try {
    read_last_frame(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": no trajectory"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_last_frame(dir.file("missing.h5")), Error);
}

}  // namespace
}  // namespace fldsim
