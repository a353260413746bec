// Periodic cubic box with Lees–Edwards boundary conditions for simple shear u = gammadot*y*x
// (x velocity, y gradient, z vorticity). The image of the box above (y + L) is displaced in x by
// the offset s = strain * L (mod L); crossing a y face changes x by -/+s and the x velocity by
// -/+gammadot*L (Lees & Edwards, J. Phys. C 5, 1921 (1972)).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace fldsim {

using Vec3 = Eigen::Vector3d;

class LeesEdwardsBox {
 public:
  LeesEdwardsBox() = default;
  explicit LeesEdwardsBox(double edge) : L_(edge) {}

  double edge() const { return L_; }
  double volume() const { return L_ * L_ * L_; }
  // Accumulated shear strain gammadot*t; only strain mod 1 matters for the geometry.
  double strain() const { return strain_; }
  void set_strain(double s) { strain_ = s; }
  // x displacement of the image above, in [0, L).
  double offset() const {
    double f = strain_ - std::floor(strain_);
    return f * L_;
  }

  // Minimum-image separation vector for r = x_j - x_i: remove whole periods in y first (which
  // shifts x by the offset), then z and x.
  Vec3 minimum_image(Vec3 r) const {
    const double ny = std::round(r.y() / L_);
    r.y() -= ny * L_;
    r.x() -= ny * offset();
    r.x() -= std::round(r.x() / L_) * L_;
    r.z() -= std::round(r.z() / L_) * L_;
    return r;
  }

  // Map a position into [0, L)^3, applying the Lees–Edwards shift for y crossings.
  // Returns the number of y periods crossed (so callers can correct unwrapped data).
  int wrap(Vec3& x) const {
    const double ny = std::floor(x.y() / L_);
    x.y() -= ny * L_;
    x.x() -= ny * offset();
    x.x() -= std::floor(x.x() / L_) * L_;
    x.z() -= std::floor(x.z() / L_) * L_;
    // Guard round-off that lands exactly on L.
    for (int k = 0; k < 3; ++k)
      if (x[k] >= L_) x[k] -= L_;
    return static_cast<int>(ny);
  }

 private:
  double L_ = 1.0;
  double strain_ = 0.0;
};

}  // namespace fldsim
