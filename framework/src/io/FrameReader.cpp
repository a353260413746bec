#include "io/FrameReader.hpp"

#include <filesystem>

#include "fldsim/error.hpp"
#include "fldsim/trajectory_layout.hpp"
#include "io/H5Helpers.hpp"
#include "io/IsolatedRead.hpp"

namespace fldsim {

namespace {

// The last sample of a time-dependent element: value[last, ...] flattened, with its shape.
std::vector<double> last_sample(const H5::H5File& file, const std::string& element,
                                std::vector<hsize_t>& shape, std::int64_t* step = nullptr,
                                double* time = nullptr) {
  H5::DataSet value = file.openDataSet(element + "/value");
  H5::DataSpace space = value.getSpace();
  const int rank = space.getSimpleExtentNdims();
  std::vector<hsize_t> dims(rank);
  space.getSimpleExtentDims(dims.data());
  if (rank < 1 || dims[0] == 0) throw H5::DataSetIException("read_last_frame", element + " has no samples");
  const hsize_t last = dims[0] - 1;
  shape.assign(dims.begin() + 1, dims.end());
  std::vector<hsize_t> offset(rank, 0), count = dims;
  offset[0] = last;
  count[0] = 1;
  space.selectHyperslab(H5S_SELECT_SET, count.data(), offset.data());
  hsize_t n = 1;
  for (hsize_t d : shape) n *= d;
  std::vector<double> data(n);
  H5::DataSpace mem(1, &n);
  value.read(data.data(), H5::PredType::NATIVE_DOUBLE, mem, space);

  auto read_at = [&](const char* name, const H5::PredType& type, void* out) {
    H5::DataSet d = file.openDataSet(element + "/" + name);
    H5::DataSpace s = d.getSpace();
    hsize_t len = 0;
    s.getSimpleExtentDims(&len);
    if (len != dims[0])
      throw H5::DataSetIException("read_last_frame", element + "/" + name + " length differs");
    const hsize_t one = 1;
    s.selectHyperslab(H5S_SELECT_SET, &one, &last);
    H5::DataSpace m(1, &one);
    d.read(out, type, m, s);
  };
  if (step) read_at("step", H5::PredType::NATIVE_INT64, step);
  if (time) read_at("time", H5::PredType::NATIVE_DOUBLE, time);
  return data;
}

}  // namespace

namespace {

Checkpoint read_last_frame_in_process(const std::string& result_h5) {
  io::quiet_hdf5();
  if (!std::filesystem::exists(result_h5)) throw Error(result_h5 + ": result file not found");
  Checkpoint c;
  try {
    H5::H5File file(result_h5, H5F_ACC_RDONLY);
    if (!io::path_exists(file.openGroup("/"), trajectory::kPosition))
      throw Error(result_h5 + ": no trajectory (" + trajectory::kPosition +
                  "); add the `trajectory` observer to the run that writes it");
    std::vector<hsize_t> shape;
    const std::vector<double> pos = last_sample(file, trajectory::kPosition, shape, &c.step, &c.time);
    if (shape.size() != 2 || shape[1] != 3) throw Error(result_h5 + ": position frames are not [N][3]");
    const std::size_t n = shape[0];
    c.positions.resize(n);
    for (std::size_t i = 0; i < n; ++i) c.positions[i] = Vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);

    const std::vector<double> q = last_sample(file, trajectory::kOrientation, shape);
    if (shape.size() != 2 || shape[0] != n || shape[1] != 4)
      throw Error(result_h5 + ": orientation frames are not [N][4] with the position's N");
    c.orientations.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      c.orientations[i] = Quat(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);

    const std::vector<double> edges = last_sample(file, trajectory::kBoxEdges, shape);
    // The 3x3 cell matrix (first row (L, 0, 0)), or edge lengths in files written before it.
    if (edges.size() != 3 && edges.size() != 9)
      throw Error(result_h5 + ": box edges are neither 3 lengths nor a 3x3 cell matrix");
    c.box_edge = edges[0];
    c.strain = last_sample(file, trajectory::kStrain, shape).at(0);
    c.displacement.assign(n, Vec3::Zero());
    c.nonaffine.assign(n, Vec3::Zero());
  } catch (const H5::Exception& e) {
    io::fail(result_h5, "cannot read the last trajectory frame", e);
  }
  return c;
}

}  // namespace

Checkpoint read_last_frame(const std::string& result_h5) {
  return io::read_isolated(result_h5, "result file", [&] { return read_last_frame_in_process(result_h5); });
}

}  // namespace fldsim
