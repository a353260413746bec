// The trajectory observer writes an H5MD particles group: box attributes and the 3x3 cell with
// the Lees-Edwards tilt, wrapped centres under Lees–Edwards, scalar-first quaternions, the
// continuous Lees–Edwards offset and the strain, the body shape, and optionally node positions.
// Expected values are worked out by hand below.
#include <gtest/gtest.h>

#include <cmath>

#include "IoTestSupport.hpp"
#include "TinyDimer.hpp"
#include "TrajectoryObserver.hpp"
#include "io/Hdf5ResultSink.hpp"

namespace fldsim {
namespace {

using test::dims_of;
using test::read_all;

constexpr double kTol = 1e-12;  // round-off of the wrap and of one rotation

// Three bodies in a box of edge 10 at strain 0.25 (Lees–Edwards offset 2.5).
System make_system() {
  System s = test::tiny_system(3, 10.0);
  s.box().set_strain(0.25);
  s.positions()[0] = Vec3(1, 2, 3);      // inside: unchanged
  s.positions()[1] = Vec3(3, 12, 4);     // one period up in y: y -> 2, x -> 3 - 2.5 = 0.5
  s.positions()[2] = Vec3(-1, 5, 10.5);  // x -> 9, z -> 0.5
  // Body 1 rotated by 90 degrees about x: q = (cos 45, sin 45, 0, 0); node (0,0,h) -> (0,-h,0).
  s.orientations()[1] = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  s.update_nodes();
  return s;
}

void run_two_frames(System& s, TrajectoryObserver& obs, Hdf5ResultSink& sink) {
  RunInfo run;
  run.total_steps = 10;
  NodePairList pairs;
  obs.begin(s, run, sink);  // step 0 is due: frame 0
  const StepView at_start{s, pairs, run, nullptr, nullptr, nullptr, {}, 1.0};
  obs.sample(at_start, sink);  // same step again: must not duplicate the frame
  s.set_step(10);
  s.set_time(0.01);
  s.box().set_strain(1.5);  // offset (1.5 mod 1) * 10 = 5
  obs.sample(at_start, sink);
}

TEST(TrajectoryObserver, WritesH5mdParticlesGroup) {
  test::ScratchDir dir;
  const std::string path = dir.file("traj.h5");
  System s = make_system();
  {
    Hdf5ResultSink sink(path, false);
    TrajectoryObserver obs(TrajectoryObserver::Options{false});
    run_two_frames(s, obs, sink);
    sink.commit();
  }
  H5::H5File f(path, H5F_ACC_RDONLY);
  // H5MD 1.1 box: dimension (integer) and boundary (string array).
  H5::Group box = f.openGroup("/particles/bodies/box");
  EXPECT_EQ(test::int_attr(box, "dimension"), (std::vector<long long>{3}));
  EXPECT_EQ(box.openAttribute("dimension").getSpace().getSimpleExtentType(), H5S_SCALAR);  // H5MD: an integer
  EXPECT_EQ(test::string_list_attr(box, "boundary"),
            (std::vector<std::string>{"periodic", "periodic", "periodic"}));
  // Cell rows (L,0,0), (s,L,0), (0,0,L) with s = L (strain - round(strain)): 2.5 at strain 0.25,
  // -5 at strain 1.5 (the shift 15 less one box length 10, then -5 = 5 - 10 as the smaller).
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/box/edges/value")),
            (std::vector<double>{10, 0, 0, 2.5, 10, 0, 0, 0, 10, 10, 0, 0, -5, 10, 0, 0, 0, 10}));

  H5::DataSet pos = f.openDataSet("/particles/bodies/position/value");
  ASSERT_EQ(dims_of(pos), (std::vector<hsize_t>{2, 3, 3}));
  // The position element's units sit on its group (MDAnalysis 2.4 refuses "a" on the datasets).
  EXPECT_FALSE(pos.attrExists("unit"));
  EXPECT_EQ(test::string_attr(f.openGroup("/particles/bodies/position"), "unit"), "a");
  EXPECT_EQ(test::string_attr(f.openGroup("/particles/bodies/position"), "time_unit"), "a+2 D0-1");
  EXPECT_EQ(test::string_attr(f.openDataSet("/particles/bodies/orientation/time"), "unit"), "a+2 D0-1");
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/position/step")), (std::vector<double>{0, 10}));
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/position/time")), (std::vector<double>{0, 0.01}));
  const std::vector<double> p = read_all(pos);
  const double frame0[9] = {1, 2, 3, 0.5, 2, 4, 9, 5, 0.5};
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(p[k], frame0[k], kTol) << k;
  // Frame 1 at offset 5: body 1 -> x = 3 - 5 = -2 -> 8.
  EXPECT_NEAR(p[9 + 3], 8.0, kTol);

  H5::DataSet q = f.openDataSet("/particles/bodies/orientation/value");
  ASSERT_EQ(dims_of(q), (std::vector<hsize_t>{2, 3, 4}));
  const std::vector<double> qv = read_all(q);
  EXPECT_NEAR(qv[0], 1.0, kTol);  // identity, w first
  EXPECT_NEAR(qv[4], std::sqrt(0.5), kTol);
  EXPECT_NEAR(qv[5], std::sqrt(0.5), kTol);
  EXPECT_NEAR(qv[6], 0.0, kTol);
  EXPECT_NE(
      test::string_attr(f.openGroup("/particles/bodies/orientation"), "convention").find("proposal 104"),
      std::string::npos);

  EXPECT_EQ(dims_of(f.openDataSet("/particles/bodies/lees_edwards/offset/value")), (std::vector<hsize_t>{2}));
  const std::vector<double> offset = read_all(f.openDataSet("/particles/bodies/lees_edwards/offset/value"));
  EXPECT_NEAR(offset[0], 2.5, kTol);
  EXPECT_NEAR(offset[1], 15.0, kTol);  // strain 1.5 times L: continuous, not reduced mod L
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/lees_edwards/strain/value")),
            (std::vector<double>{0.25, 1.5}));
  // Dimer nodes at (0, 0, +/-0.5), radius 1 (TinyDimer.hpp), in the body frame.
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/shape/node_positions")),
            (std::vector<double>{0, 0, 0.5, 0, 0, -0.5}));
  EXPECT_EQ(read_all(f.openDataSet("/particles/bodies/shape/node_radii")), (std::vector<double>{1, 1}));
  EXPECT_FALSE(H5Lexists(f.getId(), "/particles/nodes", H5P_DEFAULT) > 0);
}

TEST(TrajectoryObserver, OptionallyWritesIntactBodiesOfNodes) {
  test::ScratchDir dir;
  const std::string path = dir.file("nodes.h5");
  System s = make_system();
  {
    Hdf5ResultSink sink(path, false);
    TrajectoryObserver obs(TrajectoryObserver::Options{true});
    run_two_frames(s, obs, sink);
    sink.commit();
  }
  H5::H5File f(path, H5F_ACC_RDONLY);
  H5::DataSet pos = f.openDataSet("/particles/nodes/position/value");
  ASSERT_EQ(dims_of(pos), (std::vector<hsize_t>{2, 6, 3}));
  const std::vector<double> p = read_all(pos);
  // Body 0 (identity): nodes at centre (1,2,3) +- (0,0,0.5).
  EXPECT_NEAR(p[2], 3.5, kTol);
  EXPECT_NEAR(p[5], 2.5, kTol);
  // Body 1 (90 degrees about x) at wrapped centre (0.5,2,4): node 0 -> (0.5, 1.5, 4), node 1 -> (0.5, 2.5,
  // 4).
  EXPECT_NEAR(p[6], 0.5, kTol);
  EXPECT_NEAR(p[7], 1.5, kTol);
  EXPECT_NEAR(p[8], 4.0, kTol);
  EXPECT_NEAR(p[10], 2.5, kTol);
  // Body 2 at z = 0.5: node 1 at z = 0, i.e. the body is not split across the boundary.
  EXPECT_NEAR(p[17], 0.0, kTol);
  EXPECT_EQ(read_all(f.openDataSet("/particles/nodes/radius")), (std::vector<double>(6, 1.0)));
  EXPECT_EQ(test::int_attr(f.openGroup("/particles/nodes/box"), "dimension"), (std::vector<long long>{3}));
}

}  // namespace
}  // namespace fldsim
