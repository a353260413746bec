#include "ProgressObserver.hpp"

#include <unistd.h>

#include <iostream>

namespace fldsim {

namespace {
ProgressOptions options_from(const Params& p) {
  ProgressOptions o;
  o.interval = p.number("interval");
  o.min_gap_warning = p.number("min_gap_warning");
  o.cg_iterations_warning = static_cast<int>(p.integer("cg_iterations_warning"));
  o.live = ::isatty(2) == 1;
  return o;
}
}  // namespace

void ProgressObserver::describe(ParamSchema& s) {
  s.number("interval", 10.0, "s", "wall-clock seconds between log lines when stderr is not a terminal")
      .greater(0.0);
  s.number("min_gap_warning", 1e-5, "a", "warn (once) when the minimum surface gap falls below this")
      .at_least(0.0);
  s.integer("cg_iterations_warning", 200, "", "warn (once) when one solve needs more CG iterations")
      .at_least(1);
}

ProgressObserver::ProgressObserver(const Params& p) : reporter_(options_from(p), std::cerr) {}

double ProgressObserver::wall() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

void ProgressObserver::begin(const System& system, const RunInfo& run, ResultSink& out) {
  (void)out;
  reporter_.start(system.step(), run.total_steps, wall(), run.time_unit, run.time_scale);
}

void ProgressObserver::sample(const StepView& view, ResultSink& out) {
  (void)out;
  reporter_.update(view.system.step(), view.system.time(), view.min_gap, view.solve.iterations, wall());
}

void ProgressObserver::finish(const RunInfo& run, ResultSink& out) {
  (void)run;
  (void)out;
  reporter_.finish(wall());
}

}  // namespace fldsim
