#include "fldsim-sdk/geometry/SphereUnion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace fldsim::shapes {
namespace {

constexpr double pi = std::numbers::pi;

double ball_volume(double r) {
  return 4.0 / 3.0 * pi * r * r * r;
}

// Spherical cap of height t on a ball of radius r: volume pi t^2 (3r - t)/3, centroid at
// 3(2r - t)^2 / (4(3r - t)) from the ball's centre (standard results for a spherical cap).
double cap_volume(double r, double t) {
  return pi * t * t * (3.0 * r - t) / 3.0;
}
double cap_centroid(double r, double t) {
  return 3.0 * (2.0 * r - t) * (2.0 * r - t) / (4.0 * (3.0 * r - t));
}

bool overlap(const Ball& p, const Ball& q) {
  return (p.centre - q.centre).norm() < p.radius + q.radius;
}

bool inside(const Ball& inner, const Ball& outer) {
  return (inner.centre - outer.centre).norm() + inner.radius <= outer.radius;
}

// The lens is two caps cut by the radical plane at distance h = (d^2 + a^2 - b^2)/(2d) from A:
// the cap of A beyond the plane (height a - h) and the cap of B before it (height b - (d - h)).
struct Lens {
  double volume, offset;
};
Lens lens(double a, double b, double d) {
  const double h = (d * d + a * a - b * b) / (2.0 * d);
  const double ta = a - h, tb = b - (d - h);
  const double va = cap_volume(a, ta), vb = cap_volume(b, tb);
  const double za = cap_centroid(a, ta), zb = d - cap_centroid(b, tb);
  return {va + vb, (va * za + vb * zb) / (va + vb)};
}

}  // namespace

double lens_volume(double a, double b, double d) {
  if (d >= a + b) return 0.0;
  if (d <= std::abs(a - b)) return ball_volume(std::min(a, b));
  return lens(a, b, d).volume;
}

double lens_centroid_offset(double a, double b, double d) {
  if (d >= a + b) return 0.0;
  if (d <= std::abs(a - b)) return a <= b ? 0.0 : d;
  return lens(a, b, d).offset;
}

bool triples_may_overlap(const std::vector<Ball>& balls) {
  const std::size_t n = balls.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!overlap(balls[i], balls[j])) continue;
      for (std::size_t k = j + 1; k < n; ++k)
        if (overlap(balls[i], balls[k]) && overlap(balls[j], balls[k])) return true;
    }
  return false;
}

VolumeAndCentroid union_volume_centroid(const std::vector<Ball>& all) {
  // Drop balls contained in another (keep the first of identical ones): they add nothing.
  std::vector<Ball> balls;
  for (std::size_t i = 0; i < all.size(); ++i) {
    bool covered = false;
    for (std::size_t j = 0; j < all.size() && !covered; ++j) {
      if (i == j || !inside(all[i], all[j])) continue;
      covered = !inside(all[j], all[i]) || j < i;  // identical balls: keep the first
    }
    if (!covered) balls.push_back(all[i]);
  }
  if (triples_may_overlap(balls)) return integrate_union(balls);

  VolumeAndCentroid out;
  Vec3 moment = Vec3::Zero();
  for (const auto& b : balls) {
    const double v = ball_volume(b.radius);
    out.volume += v;
    moment += v * b.centre;
  }
  for (std::size_t i = 0; i < balls.size(); ++i)
    for (std::size_t j = i + 1; j < balls.size(); ++j) {
      const Vec3 axis = balls[j].centre - balls[i].centre;
      const double d = axis.norm();
      if (d >= balls[i].radius + balls[j].radius) continue;
      const Lens l = lens(balls[i].radius, balls[j].radius, d);
      out.volume -= l.volume;
      moment -= l.volume * (balls[i].centre + axis * (l.offset / d));
    }
  out.centroid = moment / out.volume;
  return out;
}

namespace {

struct Moments {
  double volume;
  Vec3 moment;
};

// Midpoint rule over an n x n grid of x lines; along each line the union of chords is exact.
Moments line_integral(const std::vector<Ball>& balls, int n, const Vec3& lo, const Vec3& hi) {
  const double hy = (hi.y() - lo.y()) / n, hz = (hi.z() - lo.z()) / n;
  double volume = 0.0;
  Vec3 moment = Vec3::Zero();
  std::vector<std::pair<double, double>> chords;
  chords.reserve(balls.size());
  for (int iy = 0; iy < n; ++iy) {
    const double y = lo.y() + (iy + 0.5) * hy;
    for (int iz = 0; iz < n; ++iz) {
      const double z = lo.z() + (iz + 0.5) * hz;
      chords.clear();
      for (const auto& b : balls) {
        const double q = b.radius * b.radius - (y - b.centre.y()) * (y - b.centre.y()) -
                         (z - b.centre.z()) * (z - b.centre.z());
        if (q > 0.0) chords.emplace_back(b.centre.x() - std::sqrt(q), b.centre.x() + std::sqrt(q));
      }
      if (chords.empty()) continue;
      std::sort(chords.begin(), chords.end());
      double length = 0.0, xmoment = 0.0;
      double s = chords[0].first, e = chords[0].second;
      auto flush = [&] {
        length += e - s;
        xmoment += 0.5 * (e * e - s * s);
      };
      for (std::size_t k = 1; k < chords.size(); ++k) {
        if (chords[k].first > e) {
          flush();
          s = chords[k].first;
          e = chords[k].second;
        } else {
          e = std::max(e, chords[k].second);
        }
      }
      flush();
      volume += length;
      moment += Vec3(xmoment, y * length, z * length);
    }
  }
  return {volume * hy * hz, moment * hy * hz};
}

}  // namespace

VolumeAndCentroid integrate_union(const std::vector<Ball>& balls, int n) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& b : balls) {
    lo = lo.cwiseMin(b.centre - Vec3::Constant(b.radius));
    hi = hi.cwiseMax(b.centre + Vec3::Constant(b.radius));
  }
  const Moments fine = line_integral(balls, n, lo, hi);
  const Moments coarse = line_integral(balls, n / 2, lo, hi);
  VolumeAndCentroid out;
  out.volume = fine.volume;
  out.centroid = fine.moment / fine.volume;
  out.exact = false;
  out.error_bound = std::abs(fine.volume - coarse.volume);
  return out;
}

}  // namespace fldsim::shapes
