// Which piece of time the next step attempt covers, and what follows an accepted or a rejected
// attempt. The run advances in *frames* (run.dt, or run.dt_max with `dt: auto`): observers,
// checkpoints and the step counter see frames only, so they sample at fixed times whatever the
// steps inside. Frame k is base interval k of the Brownian path (BrownianBridge.hpp), and every
// step is a dyadic piece of it: [i, i+1) dt_frame / 2^d. A rejected attempt is retried on a
// shorter piece of the same frame, so its noise is split by the bridge, never redrawn; and runs
// with the same seed and frame share one Brownian path whatever their steps (a fixed-step run,
// its refinements `run.refine`, and adaptive runs), so their differences are numerical errors.
//  - Fixed step: one piece per frame (2^refine with run.refine), whose noise is exactly that of
//    the fixed-step scheme. Only the stability guard rejects; the retry covers half the piece,
//    and after each accepted piece the step grows back as soon as the position allows (a dyadic
//    piece starts at a multiple of its length), so the step shrinks for that step only.
//  - Adaptive: the controller's proposal h, rounded to the nearest dyadic piece that starts where
//    the last one ended. After an attempt with error ratio e = estimate/tolerance the next proposal is
//    h = h_taken * clamp(safety e^(-1/order), shrink_min, grow_max) (the standard controller,
//    Hairer, Norsett & Wanner, Solving ODEs I, sec. II.4), so steps are chosen from the past and
//    the typical error sits near the tolerance. An attempt is rejected (and retried on at most
//    half its piece) only when e > reject_at (default 10), not when e > 1, because rejecting on
//    the step's own noise selects the Brownian path: the bridge keeps the path's law, but the
//    quadratic variation sum dW^2 over the partition that results is biased low where steps were
//    refined (Gaines & Lyons, SIAM J. Appl. Math. 57, 1455 (1997)), and the midpoint scheme's
//    thermal drift kT div M is made of exactly that sum. With additive noise this is harmless;
//    with a configuration-dependent mobility (FLD) it biases the equilibrium in proportion to
//    the share of rejected attempts (tests/dynamics/AdaptiveStepTest.cpp: a 1-D trap with a
//    position-dependent mobility, reject_at = 1: <x^2> 15 % low at 20 % rejections; 10: exact).
#pragma once

#include <cstdint>

#include "dynamics/BrownianBridge.hpp"

namespace fldsim {

struct StepControlSettings {
  bool adaptive = false;
  double frame = 0.0;       // run.dt, or run.dt_max for `dt: auto` (internal time units)
  double dt_min = 0.0;      // no step below this (0 = frame / 2^24); a run that needs one stops
  int refine = 0;           // every step at most frame / 2^refine
  double tolerance = 1e-3;  // local error target, a (adaptive only): the controller aims at it
  double reject_at = 10.0;  // an attempt whose estimate exceeds reject_at * tolerance is rejected
  double order = 1.5;       // the error estimate scales as h^order: 1.5 Euler-Maruyama/midpoint, 3 RK3
  double safety = 0.9, grow_max = 2.0, shrink_min = 0.2;
  double first_step = 0.0;  // adaptive: the first proposal (0 = frame / 16)
};

enum class Rejection { Error = 0, Overlap = 1, NonFinite = 2, Solver = 3 };
constexpr int kRejectionKinds = 4;
const char* to_string(Rejection r);

class StepControl {
 public:
  explicit StepControl(const StepControlSettings& settings);

  // Start frame `frame_index` (= its base interval of the Brownian path).
  void begin_frame(std::uint64_t frame_index);
  const NoiseInterval& next() const { return interval_; }
  double next_duration() const { return interval_.duration(); }
  // The next attempt ends exactly at the end of the frame.
  bool next_ends_frame() const { return position_ + (kWhole >> interval_.depth) == kWhole; }
  bool frame_done() const { return done_; }

  // error_ratio: estimate / tolerance (ignored in fixed-step mode).
  void accept(double error_ratio);
  // Returns false when the retry would be shorter than dt_min (the run cannot go on).
  bool reject(Rejection why, double error_ratio);

  const StepControlSettings& settings() const { return settings_; }
  // The adaptive proposal carried from frame to frame (the checkpoint keeps it).
  double proposal() const { return h_; }
  void restore(double proposal);

 private:
  static constexpr std::uint64_t kWhole = std::uint64_t(1) << NoiseInterval::kMaxDepth;
  void settle_depth(int minimum_depth, bool shorter);
  double factor(double error_ratio) const;

  StepControlSettings settings_;
  double h_ = 0.0;  // proposal (fixed step: the frame)
  bool done_ = true;
  std::uint64_t position_ = 0;  // in the frame, in units of frame / 2^kMaxDepth
  NoiseInterval interval_;
};

}  // namespace fldsim
