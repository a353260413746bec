#include "run/StepLoop.hpp"

#include <chrono>
#include <cmath>
#include <ostream>
#include <string>
#include <utility>

#include "config/NumberText.hpp"
#include "dynamics/PairGapStep.hpp"

namespace fldsim {
namespace {

StepControlSettings fixed_step(const RunInfo& info) {
  StepControlSettings c;
  c.frame = info.dt;
  return c;
}

}  // namespace

StepLoop::StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
                   const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
                   const RunInfo& info, bool brownian, bool midpoint)
    : StepLoop(sys, integrator, evaluator, list, observers, info, brownian, midpoint, fixed_step(info)) {}

StepLoop::StepLoop(System& sys, TimeIntegrator& integrator, VelocityEvaluator& evaluator,
                   const geometry::CellNeighbourList& list, std::vector<std::shared_ptr<Observer>>& observers,
                   const RunInfo& info, bool brownian, bool midpoint, const StepControlSettings& control,
                   const StepGuard& guard, std::ostream* log)
    : sys_(sys),
      integrator_(integrator),
      evaluator_(evaluator),
      list_(list),
      observers_(observers),
      info_(info),
      brownian_(brownian),
      stress_(sys.size(), brownian, midpoint),
      control_(control),
      guard_(guard),
      log_(log) {
  if (control.adaptive && control.error_control && integrator.error_order() <= 0.0)
    throw Error(
        "adaptive time steps with error control need an embedded error estimate: " + integrator.describe() +
        " has none (use drift: midpoint for Brownian runs, rk3 for kT = 0, or only run.displacement or "
        "run.gap_step)");
  integrator_.set_stress_stage(
      [this](StressStage stage, const System& s, VelocityEvaluator& ev) { stress_.sample(stage, s, ev); });
}

void StepLoop::step(ResultSink& sink) {
  // Which observers sample after this frame; only then is their extra work done.
  const std::int64_t next = sys_.step() + 1;
  const double next_time = sys_.time() + info_.dt;
  bool any_due = false, stress_due = false;
  for (const auto& o : observers_) {
    const bool due = o->needs().every_step || o->due(next, next_time);
    any_due = any_due || due;
    stress_due = stress_due || (due && o->needs().stress);
  }
  if (!gap_known_) {
    gap_ = evaluator_.min_gap(sys_);
    gap_known_ = true;
  }
  frame_start_.save(sys_);
  displacement_ = sys_.displacement();
  nonaffine_ = sys_.nonaffine_displacement();
  warm_start_ = evaluator_.warm_start();

  const double tolerance = control_.settings().tolerance;
  const bool error_control = control_.settings().adaptive && control_.settings().error_control;
  control_.begin_frame(std::uint64_t(sys_.step()));
  while (!control_.frame_done()) {
    const NoiseInterval interval = control_.next();
    const bool ends_frame = control_.next_ends_frame();
    StepAttempt a;
    bool ok = false;
    Rejection why = Rejection::Error;
    std::string detail;
    try {
      a = integrator_.attempt(sys_, evaluator_, interval, stress_due && ends_frame);
      if (!a.finite) {
        why = Rejection::NonFinite;
        detail = "a velocity or position is not finite";
      } else if (a.min_gap < -guard_.max_overlap && a.min_gap < gap_ - guard_.deepening()) {
        why = Rejection::Overlap;
        detail = "nodes overlap by " + log_number(-a.min_gap) +
                 " a, more than run.max_overlap = " + log_number(guard_.max_overlap) + " a";
      } else if (error_control && a.error > tolerance * control_.settings().reject_at) {
        why = Rejection::Error;
        detail = "local error " + log_number(a.error) + " a above " +
                 log_number(control_.settings().reject_at) + " x run.tolerance = " + log_number(tolerance) +
                 " a";
      } else {
        ok = true;
      }
    } catch (const Error& e) {  // the solver did not converge (or another failure of this step)
      why = Rejection::Solver;
      detail = e.what();
    }
    const double ratio = error_control ? a.error / tolerance : 0.0;
    if (ok) {
      integrator_.accept(sys_);
      gap_ = a.min_gap;
      const double node_step = integrator_.mean_square_node_step(sys_);
      stats_.accepted(interval.duration(), a.min_gap, sys_.time(), node_step);
      control_.accept(ratio, node_step, gap_measure(interval.duration()));
      continue;
    }
    integrator_.reject(sys_, evaluator_);
    stats_.rejected(why);
    if (!control_.reject(why, ratio)) {
      frame_start_.restore(sys_);
      sys_.displacement() = displacement_;
      sys_.nonaffine_displacement() = nonaffine_;
      evaluator_.warm_start() = warm_start_;
      gap_known_ = false;
      throw StepFailure("t = " + log_number(frame_start_.time / info_.time_scale) + " " + info_.time_unit +
                        " (step " + std::to_string(sys_.step()) + "): cannot go on: a step of " +
                        log_number(interval.duration() / info_.time_scale) + " " + info_.time_unit +
                        " was still rejected (" + detail +
                        ") and run.dt_min = " + log_number(control_.settings().dt_min / info_.time_scale) +
                        " " + info_.time_unit + " allows no shorter one");
    }
  }
  sys_.set_time(next_time);
  sys_.set_step(next);
  // On stress steps of a Brownian run the sampler solved once more; report the step's own solve.
  last_solve_ = stress_due && brownian_ ? stress_.step_solve() : evaluator_.stats();
  if (gap_ < 0.0) {
    ++overlap_frames_;
    if (gap_ < deepest_warned_ && std::isfinite(guard_.max_overlap)) {  // no warning in an ideal gas
      const NodePair* closest = nullptr;
      double best = INFINITY;
      for (const auto& p : list_.pairs().pairs()) {
        const double g = p.distance - sys_.node_radius(p.node_a) - sys_.node_radius(p.node_b);
        if (g < best) best = g, closest = &p;
      }
      warn_overlap(gap_, closest);
    }
  }
  if (!any_due) return;
  const auto t0 = std::chrono::steady_clock::now();
  const double* U = integrator_.step_velocity();
  const StepView view{sys_,
                      evaluator_.pairs(),
                      info_,
                      U,
                      evaluator_.force(),
                      stress_due ? &stress_.pieces() : nullptr,
                      last_solve_,
                      gap_};
  for (auto& o : observers_)
    if (o->needs().every_step || o->due(sys_.step(), sys_.time())) o->sample(view, sink);
  observer_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// With run.gap_step, what it measures of the step just accepted: the near pairs' mean square gap
// change plus the imposed flow's (PairGapStep.hpp; 0 when none was near, and the bound's averaged
// rate then keeps its value). 0 without it.
double StepLoop::gap_measure(double dt) {
  const StepControlSettings& c = control_.settings();
  if (!(c.adaptive && c.gap_step > 0.0)) return 0.0;
  const PairGapSteps g =
      near_pair_gap_steps(sys_, evaluator_.pairs(), integrator_.step_relative_velocity(), dt, c.gap_range);
  stats_.gap_steps(g.sum_square + g.flow_square, g.pairs);
  return g.mean_square();
}

// Overlaps are reported when they are new records (so a run with many shallow contacts does not
// flood the log); the count of frames ending with an overlap is in the final step summary.
void StepLoop::warn_overlap(double gap, const NodePair* pair) {
  const bool first = deepest_warned_ == 0.0;
  deepest_warned_ = gap;
  if (!log_) return;
  *log_ << "warning: t = " << log_number(sys_.time() / info_.time_scale) << " " << info_.time_unit
        << ": overlap: ";
  if (pair) *log_ << "bodies " << pair->body_i << " and " << pair->body_j << " ";
  *log_ << "overlap by " << log_number(-gap) << " a"
        << (first ? " (further overlaps are reported when deeper)" : "") << "\n";
}

// {proposal, overlap frames, deepest warned, statistics..., step bound (0: none), the node step's
// rate, the near pairs' gap-step sum and count, the gap step's rate}. Earlier builds' states: without
// the gap step's rate (a34c4bc: one rate, the active bound's, where run.displacement and
// run.gap_step were exclusive), without the gap steps, or with shorter statistics.
std::vector<double> StepLoop::save_state() const {
  std::vector<double> v{control_.proposal(), double(overlap_frames_), deepest_warned_};
  const std::vector<double> s = stats_.save();
  v.insert(v.end(), s.begin(), s.end());
  v.push_back(std::isfinite(control_.displacement_bound()) ? control_.displacement_bound() : 0.0);
  v.push_back(control_.displacement_rate());
  const auto [gap_sum, gap_pairs] = stats_.gap_step_state();
  v.push_back(gap_sum);
  v.push_back(gap_pairs);
  v.push_back(control_.gap_rate());
  return v;
}

void StepLoop::restore_state(const std::vector<double>& state) {
  if (state.size() < 3) throw Error("step state in the checkpoint is too short");
  // Every value is finite and the counts fit an int64 (a corrupt value would make the cast
  // undefined, or a NaN step proposal).
  for (const double x : state)
    if (!std::isfinite(x) || std::abs(x) > 0x1p62)
      throw Error("step state in the checkpoint holds an impossible value (" + log_number(x) + ")");
  if (!(state[0] > 0.0)) throw Error("step state in the checkpoint holds a step proposal <= 0");
  const std::size_t bounded = 3 + StepStatistics::kSavedValues + 2;
  const std::size_t n = state.size();
  const bool with_gaps = n == bounded + 2 || n == bounded + 3, with_bound = with_gaps || n == bounded;
  if (with_bound) {
    double node_rate = state[bounded - 1], gap_rate = n == bounded + 3 ? state[bounded + 2] : 0.0;
    if (n == bounded + 2 && !(control_.settings().displacement > 0.0)) std::swap(node_rate, gap_rate);
    control_.restore(state[0], state[bounded - 2], node_rate, gap_rate);
  } else {
    control_.restore(state[0]);
  }
  overlap_frames_ = std::int64_t(state[1]);
  deepest_warned_ = state[2];
  stats_.restore(
      std::vector<double>(state.begin() + 3, with_bound ? state.begin() + bounded - 2 : state.end()));
  if (with_gaps) stats_.restore_gap_steps(state[bounded], state[bounded + 1]);
}

}  // namespace fldsim
