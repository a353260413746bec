// probe_read_in_child (io/IsolatedRead): a reader that crashes, exits abnormally or hangs costs
// one fldsim::Error line, never the process; a reader that returns or throws passes the probe.
// Without the probe, the crashing readers below would kill this test binary (the broken variant
// of the guarantee), which is why they can only be exercised through it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <stdexcept>
#include <string>
#include <thread>

#include "fldsim/error.hpp"
#include "io/IsolatedRead.hpp"

namespace {

std::string refusal(const std::function<void()>& read, double limit = 300.0) {
  try {
    fldsim::io::probe_read_in_child("bad.h5", "result file", read, limit);
  } catch (const fldsim::Error& e) {
    return e.what();
  }
  return "";
}

TEST(IsolatedRead, AReaderThatReturnsOrThrowsPasses) {
  EXPECT_EQ(refusal([] {}), "");
  // A reader's own exception is the parent's to report, from its in-process read.
  EXPECT_EQ(refusal([] { throw std::runtime_error("no /results group"); }), "");
}

TEST(IsolatedRead, ACrashIsOneLineNamingTheFile) {
  // Under AddressSanitizer its own SIGSEGV handler turns the signal into exit(1): either way the
  // same one line.
  const std::string segv = refusal([] { std::raise(SIGSEGV); });
  EXPECT_EQ(segv.rfind("bad.h5: result file is damaged: reading it ", 0), 0u) << segv;
  EXPECT_NE(segv.find("; the file is not used"), std::string::npos) << segv;
  EXPECT_NE(refusal([] { std::abort(); }).find("crashed"), std::string::npos);
  // What AddressSanitizer does on a heap overflow: report, then exit(1).
  const std::string asan = refusal([] { ::_exit(1); });
  EXPECT_NE(asan.find("exit status 1"), std::string::npos) << asan;
}

TEST(IsolatedRead, AHangIsStoppedAtTheLimit) {
  const std::string hang = refusal([] { std::this_thread::sleep_for(std::chrono::seconds(60)); }, 0.3);
  EXPECT_NE(hang.find("did not finish"), std::string::npos) << hang;
}

TEST(IsolatedRead, AnInterruptIsNotCalledDamage) {
  const std::string interrupted = refusal([] { std::raise(SIGTERM); });
  EXPECT_NE(interrupted.find("interrupted"), std::string::npos) << interrupted;
  EXPECT_EQ(interrupted.find("damaged"), std::string::npos) << interrupted;
}

}  // namespace
