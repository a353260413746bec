#include "geometry/CellNeighbourList.hpp"

#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "fldsim/parallel_loop.hpp"

namespace fldsim::geometry {

void CellNeighbourList::configure(double range, double skin) {
  range_ = range;
  skin_ = skin;
  built_ = false;
  target_updates_ = 0;
  list_.set_range(range);
}

void CellNeighbourList::adapt_skin(double min_skin, double max_skin, int target_updates) {
  min_skin_ = min_skin;
  max_skin_ = max_skin;
  target_updates_ = target_updates;
}

void CellNeighbourList::choose_skin(const System& s) {
  const double k = double(std::max<std::int64_t>(updates_since_rebuild_, 1));
  const double factor = std::clamp(std::sqrt(double(target_updates_) / k), 0.5, 2.0);
  const double L = s.box().edge();
  // Three cells per side keep the cell grid (LeesEdwardsCellGrid::configure); a box too small for
  // that lists all pairs whatever the skin, and then only range + skin < L/2 binds (RunCheck).
  const double three_cells = L / 3.0 - range_, half_box = 0.5 * L - range_;
  const double upper = std::min(max_skin_, 0.999999 * (skin_ <= three_cells ? three_cells : half_box));
  skin_ = std::clamp(skin_ * factor, std::min(min_skin_, upper), upper);
}

// A pair enters the range only if its separation changed by more than the skin. Writing each
// node's displacement since the rebuild as the affine part of simple shear plus a rest,
// d_k = dgamma y_k e_x + a_k, the separation of any image changes by
//   r(t) - r(0) = a_j - a_i + dgamma r_y(0) e_x,
// where the Lees-Edwards offset change is already in the dgamma r_y term (the image above moves
// by dgamma L). A pair that can enter the range has |r_y(0)| <= range + |a_i| + |a_j|, so with a1,
// a2 the two largest |a_k| the list is valid while a1 + a2 + |dgamma| (range + a1 + a2) <= skin.
// Measuring the rest against the affine flow (instead of the raw displacement) keeps the list
// through the large affine motion of bodies far from y = 0 at high Pe.
bool CellNeighbourList::needs_rebuild(const System& s) const {
  if (!built_ || s.node_count() != reference_nodes_ || s.box().edge() != reference_edge_) return true;
  const auto& box = s.box();
  const auto& x = s.node_positions();
  const double dgamma = box.strain() - reference_strain_;
  double first = 0.0, second = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    Vec3 d = box.minimum_image(x[k] - reference_positions_[k]);
    d.x() -= dgamma * reference_positions_[k].y();
    const double a = d.norm();
    if (a > first) {
      second = first;
      first = a;
    } else if (a > second) {
      second = a;
    }
  }
  return first + second + std::abs(dgamma) * (range_ + first + second) > skin_;
}

bool CellNeighbourList::update(const System& s) {
  ++updates_since_rebuild_;
  // An adaptive skin is also re-chosen (halved) when a list outlives four targets: displacements
  // slowed down, and a thinner shell is cheaper to refresh.
  const bool rebuilt = needs_rebuild(s) || (target_updates_ > 0 && skin_ > min_skin_ &&
                                            updates_since_rebuild_ > 4 * std::int64_t(target_updates_));
  if (rebuilt) {
    if (target_updates_ > 0 && built_) choose_skin(s);
    rebuild(s);
    updates_since_rebuild_ = 0;
  } else if (s.box().strain() == updated_strain_ && updated_positions_.size() == s.node_count())
    refresh_moved(s);
  else
    refresh(s);
  remember_positions(s);
  return rebuilt;
}

void CellNeighbourList::remember_positions(const System& s) {
  const auto& x = s.node_positions();
  updated_positions_.resize(x.size());  // allocates only when the node count grows
  std::copy(x.begin(), x.end(), updated_positions_.begin());
  updated_strain_ = s.box().strain();
}

void CellNeighbourList::add_pair(const System& s, std::size_t p, std::size_t q, const Vec3& r) {
  const std::size_t m = s.nodes_per_body();
  const std::size_t bp = p / m, bq = q / m;
  if (bp < bq)
    list_.pairs().push_back(
        {std::uint32_t(bp), std::uint32_t(bq), std::uint16_t(p % m), std::uint16_t(q % m), r, r.norm()});
  else
    list_.pairs().push_back({std::uint32_t(bq), std::uint32_t(bp), std::uint16_t(q % m), std::uint16_t(p % m),
                             Vec3(-r), r.norm()});
}

void CellNeighbourList::rebuild(const System& s) {
  const auto& box = s.box();
  const auto& x = s.node_positions();
  const std::size_t n = x.size(), m = s.nodes_per_body();
  const double cutoff = range_ + skin_;
  auto& pairs = list_.pairs();
  pairs.clear();

  if (grid_.configure(box, cutoff)) {
    wrapped_.resize(n);
    cell_head_.assign(grid_.cell_count(), -1);
    cell_next_.assign(n, -1);
    for (std::size_t k = 0; k < n; ++k) {
      wrapped_[k] = x[k];
      box.wrap(wrapped_[k]);
      const int c = grid_.cell_of(wrapped_[k]);
      cell_next_[k] = cell_head_[c];
      cell_head_[c] = int(k);
    }
    std::array<int, LeesEdwardsCellGrid::max_neighbour_cells> cells;
    for (std::size_t p = 0; p < n; ++p) {
      const int count = grid_.neighbour_cells(grid_.cell_of(wrapped_[p]), cells);
      for (int c = 0; c < count; ++c)
        for (int q = cell_head_[cells[c]]; q >= 0; q = cell_next_[q]) {
          // Each unordered pair once: from the node of the lower body.
          if (std::size_t(q) / m <= p / m) continue;
          const Vec3 r = box.minimum_image(x[q] - x[p]);
          if (r.squaredNorm() < cutoff * cutoff) add_pair(s, p, q, r);
        }
    }
  } else {
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = (p / m + 1) * m; q < n; ++q) {
        const Vec3 r = box.minimum_image(x[q] - x[p]);
        if (r.squaredNorm() < cutoff * cutoff) add_pair(s, p, q, r);
      }
  }
  std::sort(pairs.begin(), pairs.end(), [](const NodePair& u, const NodePair& v) {
    return std::tie(u.body_i, u.node_a, u.body_j, u.node_b) <
           std::tie(v.body_i, v.node_a, v.body_j, v.node_b);
  });

  reference_positions_.assign(x.begin(), x.end());
  reference_strain_ = box.strain();
  reference_edge_ = box.edge();
  reference_nodes_ = n;
  built_ = true;
  ++rebuilds_;
}

namespace {
// LeesEdwardsBox::minimum_image with the box's reciprocal edge and image offset computed once
// per pass, and rounding without a libm call, instead of a division and a std::round per
// component and a floor per pair. For a listed pair whose minimum image is shorter than L/2 (every
// pair when at least three cells fit per side, L >= 3 (range + skin)), r/L lies away from a
// half-integer: r * (1/L) rounds to the same integer as r / L, no tie arises (where
// round-half-even and std::round differ), and the result is bitwise minimum_image's. Only in the
// all-pairs fallback of small boxes can a listed pair reach L/2, where the two images are equally
// near and either is a minimum image.
struct ListedPairImage {
  double L, inverse_L, offset;
  explicit ListedPairImage(const LeesEdwardsBox& box)
      : L(box.edge()), inverse_L(1.0 / box.edge()), offset(box.offset()) {}
  // Nearest integer of |v| < 2^51: adding and removing 1.5 * 2^52 drops the fraction bits.
  static constexpr double shift = 6755399441055744.0;
  static double nearest(double v) { return (v + shift) - shift; }
  Vec3 operator()(Vec3 r) const {
    const double ny = nearest(r.y() * inverse_L);
    r.y() -= ny * L;
    r.x() -= ny * offset;
    r.x() -= nearest(r.x() * inverse_L) * L;
    r.z() -= nearest(r.z() * inverse_L) * L;
    return r;
  }
  // One pair from the node positions x (m nodes per body): the scalar form of refresh's lanes.
  void refresh(NodePair& pr, const std::vector<Vec3>& x, std::size_t m) const {
    pr.r = (*this)(x[pr.body_j * m + pr.node_b] - x[pr.body_i * m + pr.node_a]);
    pr.distance = pr.r.norm();
  }
};
}  // namespace

void CellNeighbourList::refresh(const System& s) {
  const ListedPairImage image(s.box());
  const auto& x = s.node_positions();
  const std::size_t m = s.nodes_per_body();
  auto& pairs = list_.pairs();
  const std::ptrdiff_t count = std::ptrdiff_t(pairs.size());
  // Two pairs per iteration in SSE2 lanes, r and |r| from registers: 4.3x faster than the scalar
  // loop over Vec3 (BM_NeighbourRefresh, 3134 sphere pairs: 0.068 -> 0.016 ms with the rebuild
  // check; bench/README.md), which ran at about 15 ns a pair for ~40 operations. The lanes do each
  // pair's operations in the scalar order ((x^2 + y^2) + z^2 as Vec3::norm, no fused products), so
  // r and distance are bitwise the scalar ones (CellNeighbourListTest: another summation order
  // fails it).
  const std::ptrdiff_t halves = count / 2;
  parallel_for(halves, [&](std::ptrdiff_t h) {
    NodePair& p = pairs[2 * h];
    NodePair& q = pairs[2 * h + 1];
    const Vec3 dp = x[p.body_j * m + p.node_b] - x[p.body_i * m + p.node_a];
    const Vec3 dq = x[q.body_j * m + q.node_b] - x[q.body_i * m + q.node_a];
    __m128d rx = _mm_setr_pd(dp.x(), dq.x()), ry = _mm_setr_pd(dp.y(), dq.y()),
            rz = _mm_setr_pd(dp.z(), dq.z());
    const __m128d L = _mm_set1_pd(image.L), inverse_L = _mm_set1_pd(image.inverse_L),
                  offset = _mm_set1_pd(image.offset), shift = _mm_set1_pd(ListedPairImage::shift);
    auto nearest = [&](__m128d v) { return _mm_sub_pd(_mm_add_pd(v, shift), shift); };
    const __m128d ny = nearest(_mm_mul_pd(ry, inverse_L));
    ry = _mm_sub_pd(ry, _mm_mul_pd(ny, L));
    rx = _mm_sub_pd(rx, _mm_mul_pd(ny, offset));
    rx = _mm_sub_pd(rx, _mm_mul_pd(nearest(_mm_mul_pd(rx, inverse_L)), L));
    rz = _mm_sub_pd(rz, _mm_mul_pd(nearest(_mm_mul_pd(rz, inverse_L)), L));
    const __m128d r2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(rx, rx), _mm_mul_pd(ry, ry)), _mm_mul_pd(rz, rz));
    alignas(16) double ox[2], oy[2], oz[2], od[2];
    _mm_store_pd(ox, rx);
    _mm_store_pd(oy, ry);
    _mm_store_pd(oz, rz);
    _mm_store_pd(od, _mm_sqrt_pd(r2));
    p.r = Vec3(ox[0], oy[0], oz[0]);
    p.distance = od[0];
    q.r = Vec3(ox[1], oy[1], oz[1]);
    q.distance = od[1];
  });
  if (count % 2 != 0) image.refresh(pairs[count - 1], x, m);
}

// Same strain as the last update: a pair of unmoved nodes keeps its r exactly. Typically only
// the few bodies wrapped through a face at the end of a step have moved.
void CellNeighbourList::refresh_moved(const System& s) {
  const auto& x = s.node_positions();
  const std::size_t n = x.size(), m = s.nodes_per_body();
  moved_.resize(n);
  std::size_t moved = 0;
  for (std::size_t k = 0; k < n; ++k) {
    moved_[k] = x[k] != updated_positions_[k];
    moved += moved_[k];
  }
  if (moved == 0) return;
  if (8 * moved > n) {  // most pairs would be recomputed anyway
    refresh(s);
    return;
  }
  const ListedPairImage image(s.box());
  for (NodePair& pr : list_.pairs())
    if (moved_[pr.body_i * m + pr.node_a] || moved_[pr.body_j * m + pr.node_b]) image.refresh(pr, x, m);
}

double CellNeighbourList::min_gap(const System& s) const {
  double gap = std::numeric_limits<double>::infinity();
  const auto& nodes = s.shape().nodes();  // once: node_radius() calls into the shape plugin
  for (const auto& pr : list_.pairs())
    gap = std::min(gap, pr.distance - nodes[pr.node_a].radius - nodes[pr.node_b].radius);
  return gap;
}

}  // namespace fldsim::geometry
