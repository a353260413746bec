// The `progress` observer: every step, hands the step, simulated time, minimum gap and CG
// iterations to a ProgressReporter writing to stderr (a live '\r' line when stderr is a
// terminal, plain log lines every `interval` seconds otherwise).
#pragma once

#include <chrono>
#include <memory>

#include "ProgressReporter.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/params.hpp"

namespace fldsim {

class ProgressObserver : public Observer {
 public:
  static void describe(ParamSchema& s);
  explicit ProgressObserver(const Params& p);

  ObserverNeeds needs() const override {
    ObserverNeeds n;
    n.every_step = true;
    return n;
  }
  void begin(const System& system, const RunInfo& run, ResultSink& out) override;
  void sample(const StepView& view, ResultSink& out) override;
  void finish(const RunInfo& run, ResultSink& out) override;

 private:
  double wall() const;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  ProgressReporter reporter_;
};

}  // namespace fldsim
