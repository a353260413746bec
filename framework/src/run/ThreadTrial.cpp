#include "run/ThreadTrial.hpp"

#include <algorithm>
#include <cstdio>

namespace fldsim {
namespace {
// Slot 0 is the untimed warm-up; then rounds of (planned, 1, 1, planned).
bool slot_uses_one_thread(std::size_t slot) {
  const std::size_t k = (slot - 1) % 4;
  return k == 1 || k == 2;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}
}  // namespace

ThreadTrial::ThreadTrial(int planned, bool enabled)
    : planned_(planned), running_(enabled && planned > 1), chosen_(planned) {}

int ThreadTrial::threads_for_next_step() const {
  if (!running_) return chosen_;
  return index_ > 0 && slot_uses_one_thread(index_) ? 1 : planned_;
}

bool ThreadTrial::record(double seconds) {
  if (!running_) return false;
  if (index_ > 0) (slot_uses_one_thread(index_) ? one_ : many_).push_back(seconds);
  if (++index_ < std::size_t(kSteps)) return false;
  running_ = false;
  median_one_ = median(one_);
  median_many_ = median(many_);
  chosen_ = median_one_ >= kMinGain * median_many_ ? planned_ : 1;
  return true;
}

std::string ThreadTrial::report() const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "measured %.1f ms/step on 1 thread, %.1f on %d (medians of %zu steps each): %d %s",
                1e3 * median_one_, 1e3 * median_many_, planned_, one_.size(), chosen_,
                chosen_ == 1 ? "thread" : "threads");
  return buf;
}

}  // namespace fldsim
