#include "dynamics/StepControl.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "fldsim/error.hpp"

namespace fldsim {

const char* to_string(Rejection r) {
  switch (r) {
    case Rejection::Error:
      return "error";
    case Rejection::Overlap:
      return "overlap";
    case Rejection::NonFinite:
      return "non_finite";
    case Rejection::Solver:
      return "solver";
  }
  return "unknown";
}

StepControl::StepControl(const StepControlSettings& settings) : settings_(settings) {
  if (!(settings_.frame > 0.0)) throw Error("step control: the frame (time step) must be > 0");
  if (settings_.refine < 0 || settings_.refine > NoiseInterval::kMaxDepth)
    throw Error("step control: refine must be in 0.." + std::to_string(NoiseInterval::kMaxDepth));
  if (settings_.dt_min <= 0.0) settings_.dt_min = std::ldexp(settings_.frame, -24);
  settings_.dt_min = std::min(settings_.dt_min, std::ldexp(settings_.frame, -settings_.refine));
  if (!(settings_.displacement >= 0.0) || !std::isfinite(settings_.displacement) ||
      !(settings_.gap_step >= 0.0) || !std::isfinite(settings_.gap_step))
    throw Error("step control: the displacement and gap bounds must be >= 0 and finite");
  if (settings_.adaptive && !settings_.error_control && !bounded())
    throw Error("step control: adaptive steps without error control need a displacement or gap bound");
  if (!(settings_.displacement_order > 0.0)) throw Error("step control: displacement_order must be > 0");
  h_ = settings_.frame;
  hd_ = INFINITY;
  if (settings_.adaptive) {
    const double first = settings_.first_step > 0.0 ? settings_.first_step : settings_.frame / 16.0;
    if (settings_.error_control) h_ = first;
    if (bounded()) hd_ = std::clamp(first, settings_.dt_min, settings_.frame);
  }
  h_ = std::clamp(h_, settings_.dt_min, settings_.frame);
}

void StepControl::restore(double proposal, double displacement_bound, double displacement_rate,
                          double gap_rate) {
  if (!settings_.adaptive) return;
  h_ = std::clamp(proposal, settings_.dt_min, settings_.frame);
  if (bounded() && displacement_bound > 0.0) {
    hd_ = std::clamp(displacement_bound, settings_.dt_min, settings_.frame);
    rate_ = std::max(displacement_rate, 0.0);
    gap_rate_ = std::max(gap_rate, 0.0);
  }
}

void StepControl::begin_frame(std::uint64_t frame_index) {
  done_ = false;
  frame_index_ = frame_index;
  pieces_ = 1;
  piece_ = 0;
  if (equal_pieces()) {
    const double n = std::ceil(settings_.frame / hd_ * (1.0 - 1e-9));
    const double refined = std::ldexp(1.0, settings_.refine);
    pieces_ = std::uint32_t(std::clamp(std::max(n, refined), 1.0, double(kMaxPieces)));
  }
  // Inside a piece, run.refine asks only for what the piece count has not done: piece / 2^r <=
  // frame / 2^refine with r = refine - floor(log2 n).
  refine_depth_ = std::max(0, settings_.refine - (int(std::bit_width(pieces_)) - 1));
  begin_piece();
}

void StepControl::begin_piece() {
  position_ = 0;
  interval_ = NoiseInterval{piece_base(frame_index_, pieces_, piece_), settings_.frame / pieces_, 0, 0, 0};
  settle_depth(0, false);
}

double StepControl::factor(double error_ratio) const {
  if (!(error_ratio > 0.0)) return settings_.grow_max;
  if (!std::isfinite(error_ratio)) return settings_.shrink_min;
  return std::clamp(settings_.safety * std::pow(error_ratio, -1.0 / settings_.order), settings_.shrink_min,
                    settings_.grow_max);
}

// Depth of the next piece: the dyadic length nearest the proposal h (geometrically; after a
// rejection the next shorter one), never coarser than the position allows (a piece starts at a
// multiple of its length), at least `minimum_depth` and run.refine, and not below dt_min unless
// forced by the position or the minimum. Nearest rather than shorter: the error then scatters
// around the tolerance instead of below it (x 2^(+-order/2)), and reject_at leaves room for it.
void StepControl::settle_depth(int minimum_depth, bool shorter) {
  const double H = interval_.length;
  int want = 0;
  if (h_ < H) {
    const double levels = std::log2(H / h_);
    want = shorter ? int(std::ceil(levels - 1e-9)) : int(std::lround(levels));
  }
  // At most hd; equal pieces were cut to it when the frame began, and are split inside the frame
  // only where the bound has since fallen below 4/5 of a piece (the start, a sudden jam), not
  // for the 2-4 % step-to-step scatter of the averaged rate, which would halve every piece cut
  // close to the bound.
  const bool split = bounded() && hd_ < H && (!equal_pieces() || hd_ < 0.8 * H);
  if (split) want = std::max(want, int(std::ceil(std::log2(H / hd_) - 1e-9)));
  const int aligned =
      position_ == 0 ? 0 : NoiseInterval::kMaxDepth - std::countr_zero(position_);  // coarsest boundary
  const int floor = std::max({aligned, minimum_depth, refine_depth_});
  int depth = std::min(std::max(want, floor), NoiseInterval::kMaxDepth);
  while (depth > floor && std::ldexp(H, -depth) < settings_.dt_min * (1.0 - 1e-9)) --depth;
  interval_.depth = depth;
  interval_.index = position_ >> (NoiseInterval::kMaxDepth - depth);
}

void StepControl::accept(double error_ratio, double mean_square_step, double mean_square_gap_step) {
  const double taken = interval_.duration();
  if (settings_.adaptive) {
    // Without error control the proposal only remembers the guard's rejections and grows back.
    const double f = settings_.error_control ? factor(error_ratio) : settings_.grow_max;
    double h = taken * f;
    // A piece cut short by the dyadic grid or the frame does not lower a good proposal.
    if (taken < h_ && f >= 1.0) h = std::max(h, h_);
    h_ = std::clamp(h, settings_.dt_min, settings_.frame);
    if (bounded()) {
      const double p = settings_.displacement_order;
      // Each bound's step from its own averaged rate; the shorter of the two is taken.
      double bound = INFINITY;
      const auto limit = [&](double l, double mean_square, double& rate) {
        if (!(l > 0.0)) return;
        if (mean_square > 0.0 && std::isfinite(mean_square)) {
          const double r = mean_square / std::pow(taken, p);
          rate = rate > 0.0 ? rate + 0.25 * (r - rate) : r;
        }
        bound = std::min(bound, rate > 0.0 ? std::pow(l * l / rate, 1.0 / p) : taken * settings_.grow_max);
      };
      limit(settings_.displacement, mean_square_step, rate_);
      limit(settings_.gap_step, mean_square_gap_step, gap_rate_);
      // Growth relative to the longer of the piece and the bound, so that a piece cut short by the
      // grid or a retry does not drag the bound down.
      const double reach = std::max(taken, std::min(hd_, settings_.frame));
      hd_ = std::clamp(bound, taken * settings_.shrink_min, reach * settings_.grow_max);
      hd_ = std::clamp(hd_, settings_.dt_min, settings_.frame);
    }
  }
  position_ += kWhole >> interval_.depth;
  interval_.attempt++;
  if (position_ == kWhole) {
    done_ = ++piece_ == pieces_;
    if (!done_) begin_piece();
    return;
  }
  settle_depth(0, false);
}

bool StepControl::reject(Rejection why, double error_ratio) {
  const double tried = interval_.duration();
  if (settings_.adaptive) {
    const double f = why == Rejection::Error ? std::min(factor(error_ratio), 0.5) : 0.5;
    h_ = std::max(tried * f, settings_.dt_min);
  }
  const int depth = interval_.depth + 1;
  if (depth > NoiseInterval::kMaxDepth ||
      std::ldexp(interval_.length, -depth) < settings_.dt_min * (1.0 - 1e-9))
    return false;
  interval_.attempt++;
  settle_depth(depth, true);
  return true;
}

}  // namespace fldsim
