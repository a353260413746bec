#include "ClusterShape.hpp"

namespace fldsim::shapes {

void ClusterShape::describe(ParamSchema& s) {
  s.table("spheres", std::nullopt, "a", "one row [x, y, z, r] per sphere (body frame)").length(4);
  s.numbers("director", std::vector<double>{}, "",
            "body-frame director [x, y, z]; empty = principal axis of the node layout");
}

namespace {
std::vector<Ball> balls_from(const Params& p) {
  std::vector<Ball> out;
  for (const auto& row : p.table("spheres")) {
    if (!(row[3] > 0.0)) p.fail("spheres", "every sphere radius r must be > 0");
    out.push_back({Vec3(row[0], row[1], row[2]), row[3]});
  }
  if (out.empty()) p.fail("spheres", "at least one sphere is needed");
  return out;
}
std::optional<Vec3> director_from(const Params& p) {
  const auto& d = p.numbers("director");
  if (d.empty()) return std::nullopt;
  if (d.size() != 3) p.fail("director", "expected 3 numbers [x, y, z]");
  const Vec3 v(d[0], d[1], d[2]);
  if (!(v.norm() > 0.0)) p.fail("director", "must be a non-zero vector");
  return v;
}
}  // namespace

ClusterShape::ClusterShape(const Params& p) : ClusterShape(balls_from(p), director_from(p)) {}

}  // namespace fldsim::shapes
