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
//  - Displacement bound (adaptive, run.displacement = l): the step is also at most the largest
//    dyadic piece whose root mean square node displacement relative to the imposed flow stays
//    below l, predicted from the last accepted step's mean square m: hd = h_taken (l^2 / m)^(1/p),
//    p = 1 with Brownian motion (m = A h + B h^2, diffusion plus drift: exact for diffusion, and
//    the iteration l^2 / (A + B h) converges to m(h*) = l^2 with the contraction B h* / (A + B h*),
//    the drift's share of m; from a shorter step it overshoots h* by at most that share), p = 2
//    without (a drift: exact). p = 2 with Brownian motion would never overshoot, but it stalls
//    up to 4x below h* (the geometric mean of the step and h* rounds down to the same piece).
//    m / h^p is averaged over the last steps (weight 1/4 for the newest): with N bodies m scatters
//    by about sqrt(2 / (3 N_nodes)) from step to step, which would otherwise flip the step between
//    two pieces wherever h* lies within that scatter of a piece's length.
//    This is a bound on the weak (averages') error of Brownian FLD, not on the path: the bias of
//    the equilibrium structure follows the step's displacement against the lubrication taper's
//    width, and runs whose steps moved nodes by 0.026-0.031 a rms passed the hard-core oracle at
//    phi 0.3 and 0.5 (spheres, c/a 0.2, c/a 1) where 0.043-0.053 a failed (docs/time_steps.md,
//    "The displacement bound"); at phi 0.5 the edge is lower (5.3e-4 steps, 0.0246 a, failed one
//    of three sets), so 0.022 is the value the docs give ("Equal pieces"). The bound is chosen
//    from the past only (the last accepted step), never from the noise of the step it sizes, so
//    it selects no path. Rounded down, not to the
//    nearest piece: it is a bound. With run.tolerance the shorter of the controller's piece and
//    the bound's dyadic piece is taken.
//  - Displacement bound alone (no run.tolerance, error_control false): the frame is cut into
//    n = ceil(frame / hd) equal pieces, n chosen when the frame starts (from the past), each
//    piece a base interval of its own (BrownianBridge.hpp: one plain draw, no bridge terms);
//    only the guard rejects, and a rejected attempt is retried on dyadic halves inside its piece.
//    Against dyadic pieces of the frame this loses at most a factor n / (n - 1) to the rounding
//    instead of 2, and the noise costs what a fixed step's does (a depth-d dyadic piece draws
//    d + 1 streams: +6-14 % per step at N = 1000, depths 1-3). Should the bound fall below 4/5
//    of a piece within the frame, the piece is halved as a rejected one would be.
//  - Pair-gap bound (run.gap_step = l): the same rule, prediction and pieces on another measure,
//    the mean square change of the surface gap of the node pairs nearer than run.gap_range, plus
//    the imposed flow's normal displacement of each (PairGapStep.hpp); with run.displacement too,
//    each measure keeps its own averaged rate and the shorter of the two bounds is taken. Near contact the
//    gap changes are set by lubrication, so a given step changes them alike at phi 0.3 and 0.5 (rms 0.0046
//    and 0.0045 a at 4e-4 a^2/D0, N = 1000), where its rms node step differs by 1.6x (0.033 and 0.021 a). It
//    guards the repulsion's contact bias (phi 0.5's edge: 0.0048 takes 4e-4 and passes the oracle), not the
//    lubrication taper's, which follows the node step (phi 0.3's edge: there 0.0048's 3.7e-4 failed one of
//    four sets; docs/time_steps.md, "The pair-gap bound"): the two together guard both.
#pragma once

#include <cstdint>

#include "dynamics/BrownianBridge.hpp"

namespace fldsim {

struct StepControlSettings {
  bool adaptive = false;
  double frame = 0.0;         // run.dt, or run.dt_max for `dt: auto` (internal time units)
  double dt_min = 0.0;        // no step below this (0 = frame / 2^24); a run that needs one stops
  int refine = 0;             // every step at most frame / 2^refine
  double tolerance = 1e-3;    // local error target, a (adaptive only): the controller aims at it
  bool error_control = true;  // adaptive: the embedded estimate's controller acts (run.tolerance)
  double displacement = 0.0;  // adaptive: bound on the rms node step (run.displacement), a (0: none)
  double gap_step = 0.0;      // adaptive: bound on the near pairs' rms gap step (run.gap_step), a (0: none)
  double gap_range = 0.01;    // gap_step: pairs with a surface gap below this, a
  double displacement_order = 1.0;  // p of the prediction: 1 with Brownian motion, 2 without
  double reject_at = 10.0;          // an attempt whose estimate exceeds reject_at * tolerance is rejected
  double order = 1.5;  // the error estimate scales as h^order: 1.5 Euler-Maruyama/midpoint, 3 RK3
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
  bool next_ends_frame() const {
    return piece_ + 1 == pieces_ && position_ + (kWhole >> interval_.depth) == kWhole;
  }
  // Equal pieces the current frame is cut into (1 but with the displacement bound alone).
  std::uint32_t pieces() const { return pieces_; }
  bool frame_done() const { return done_; }

  // error_ratio: estimate / tolerance (ignored in fixed-step mode and without error control);
  // mean_square_step: the mean over nodes of the squared displacement of the step relative to the
  // imposed flow, a^2 (TimeIntegrator::mean_square_node_step; the displacement bound's measure);
  // mean_square_gap_step: PairGapSteps::mean_square() (the gap bound's). 0: nothing measured, the
  // averaged rate keeps its value.
  void accept(double error_ratio, double mean_square_step = 0.0, double mean_square_gap_step = 0.0);
  // Returns false when the retry would be shorter than dt_min (the run cannot go on).
  bool reject(Rejection why, double error_ratio);

  const StepControlSettings& settings() const { return settings_; }
  // The adaptive proposal, the step bound (the shorter of the two; infinite without one) and each
  // measure's averaged rate m / h^p (0 before the first step), carried from frame to frame (the
  // checkpoint keeps them).
  double proposal() const { return h_; }
  double displacement_bound() const { return hd_; }
  double displacement_rate() const { return rate_; }
  double gap_rate() const { return gap_rate_; }
  void restore(double proposal, double displacement_bound = 0.0, double displacement_rate = 0.0,
               double gap_rate = 0.0);

 private:
  static constexpr std::uint64_t kWhole = std::uint64_t(1) << NoiseInterval::kMaxDepth;
  bool bounded() const {
    return settings_.adaptive && (settings_.displacement > 0.0 || settings_.gap_step > 0.0);
  }
  bool equal_pieces() const { return bounded() && !settings_.error_control; }
  void begin_piece();
  void settle_depth(int minimum_depth, bool shorter);
  double factor(double error_ratio) const;

  StepControlSettings settings_;
  double h_ = 0.0;         // proposal (fixed step: the frame)
  double hd_ = 0.0;        // step bound: the shorter of the node and gap bounds (infinite without one)
  double rate_ = 0.0;      // node step: m / h^p averaged over the last steps (0: no step yet)
  double gap_rate_ = 0.0;  // the same for the gap step
  bool done_ = true;
  std::uint64_t frame_index_ = 0;
  std::uint32_t pieces_ = 1, piece_ = 0;  // the frame's equal pieces, and the current one
  int refine_depth_ = 0;                  // run.refine inside a piece: at most frame / 2^refine
  std::uint64_t position_ = 0;            // in the piece, in units of piece / 2^kMaxDepth
  NoiseInterval interval_;
};

}  // namespace fldsim
