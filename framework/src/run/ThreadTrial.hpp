// When the thread count is automatic and the plan asks for more than one thread, the run's first
// steps measure whether the extra threads pay on this machine. They often do not: a parallel step
// synchronises its threads about ten times per CG iteration (fork/join of the parallel loops) and
// at every IC(0) dependency that crosses threads, and on some virtual machines a barrier costs
// 1.5 us, several times its usual cost on one socket (bench/RESULTS.md, OmpBarrier).
// Results do not depend on the thread count (fixed-order sums, noise by body and pair identity;
// tests ResistanceModel.AssemblyNoiseAndSolveAreIndependentOfThreadCount and
// ThreadTrial.SwitchingThreadsBetweenStepsLeavesTheTrajectoryBitwiseUnchanged), so timing real
// steps costs nothing in accuracy.
//
// Schedule: one untimed step with the planned count, then kRounds rounds of the pattern
// (planned, 1, 1, planned) — ABBA order cancels a slow drift of the machine's speed — and the
// median step time of each count decides. Observer steps fall on both counts alike, and the
// median ignores them. More threads are kept only if at least kMinGain faster: a busier machine
// is not worth a few per cent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fldsim {

class ThreadTrial {
 public:
  static constexpr int kRounds = 3;
  static constexpr int kSteps = 1 + 4 * kRounds;  // steps the trial takes
  static constexpr double kMinGain = 1.05;
  // Runs shorter than this many steps skip the trial and keep the planned count.
  static constexpr std::int64_t kMinRunSteps = 200;

  // planned: the automatic plan's thread count; enabled: the count is automatic and the run long
  // enough (see should_run).
  ThreadTrial(int planned, bool enabled);
  static bool should_run(int planned, bool automatic, std::int64_t run_steps) {
    return automatic && planned > 1 && run_steps >= kMinRunSteps;
  }

  // True while the trial still decides the thread count of the next step.
  bool running() const { return running_; }
  // The thread count for the next step (the chosen one once the trial is over).
  int threads_for_next_step() const;
  // Wall seconds of the step just taken with threads_for_next_step(). Returns true when this
  // completed the trial (then chosen() and report() are final).
  bool record(double seconds);

  int chosen() const { return chosen_; }
  // "measured 60.4 ms/step on 1 thread, 76.6 on 2 (medians of 6 steps): 1 thread", for the log.
  std::string report() const;

 private:
  int planned_;
  bool running_;
  int chosen_;
  std::size_t index_ = 0;  // position in the schedule
  std::vector<double> one_, many_;
  double median_one_ = 0.0, median_many_ = 0.0;
};

}  // namespace fldsim
