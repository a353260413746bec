// A HydroModel that forwards every call to a real hydro plugin and keeps, for the benchmark,
// the wall time of each phase (assembly, Brownian forces, solve, stresslets) and the CG
// iterations of *every* solve (a midpoint step solves twice; SolveStats only keeps the last).
#pragma once

#include <chrono>
#include <memory>

#include "fldsim/hydro.hpp"

namespace fldsim::bench {

struct HydroTimes {
  double assemble = 0, brownian = 0, solve = 0, stresslets = 0;  // seconds
  std::int64_t solves = 0, cg_iterations = 0;
};

class TimedHydro : public HydroModel, public RunNotes {
 public:
  explicit TimedHydro(std::shared_ptr<HydroModel> inner)
      : inner_(std::move(inner)), notes_(run_notes_of(*inner_)) {}

  double pair_range(const System& s) const override { return inner_->pair_range(s); }
  bool provides_stresslets() const override { return inner_->provides_stresslets(); }
  std::vector<std::string> configure(const System& s, const HydroRequest& r) override {
    return inner_->configure(s, r);
  }
  void assemble(const System& s, const NodePairList& pairs) override {
    const auto t0 = Clock::now();
    inner_->assemble(s, pairs);
    times_.assemble += seconds_since(t0);
  }
  void brownian_force(const System& s, const NodePairList& pairs, const RandomStream& noise, double dt,
                      double* FB) override {
    const auto t0 = Clock::now();
    inner_->brownian_force(s, pairs, noise, dt, FB);
    times_.brownian += seconds_since(t0);
  }
  void solve(const System& s, const double* F, double* dU) override {
    const auto t0 = Clock::now();
    inner_->solve(s, F, dU);
    times_.solve += seconds_since(t0);
    times_.solves += 1;
    times_.cg_iterations += inner_->last_solve().iterations;
  }
  SolveStats last_solve() const override { return inner_->last_solve(); }
  // The wrapped model's run-log lines (a preconditioner that fell back), if it has any.
  std::vector<std::string> take_notes() override {
    return notes_ ? notes_->take_notes() : std::vector<std::string>{};
  }
  Eigen::Matrix3d stresslet_sum(const System& s, const NodePairList& pairs, const double* dU) override {
    const auto t0 = Clock::now();
    const Eigen::Matrix3d S = inner_->stresslet_sum(s, pairs, dU);
    times_.stresslets += seconds_since(t0);
    return S;
  }

  const HydroTimes& times() const { return times_; }
  void reset_times() { times_ = {}; }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  }
  std::shared_ptr<HydroModel> inner_;
  RunNotes* notes_;  // inner_'s RunNotes side, or null
  HydroTimes times_;
};

}  // namespace fldsim::bench
