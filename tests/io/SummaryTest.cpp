// `fldsim summary`: every scalar under /results with its error and unit, values rounded to
// the precision of their error (two significant digits of the error).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sstream>

#include "IoTestSupport.hpp"
#include "fldsim/error.hpp"
#include "io/Hdf5ResultSink.hpp"
#include "io/Summary.hpp"

namespace fldsim {
namespace {

TEST(Summary, FormatsValuesToThePrecisionOfTheirError) {
  std::string v, e;
  format_with_error(0.785312, 0.00123, v, e);
  EXPECT_EQ(v, "0.7853");
  EXPECT_EQ(e, "0.0012");
  format_with_error(12345.6, 78.0, v, e);
  EXPECT_EQ(v, "12346");
  EXPECT_EQ(e, "78");
  format_with_error(-3.2e-7, 1.1e-8, v, e);
  EXPECT_EQ(v, "-3.20e-07");
  EXPECT_EQ(e, "1.1e-08");
  format_with_error(0.5000000000000011, 6.7e-17, v, e);  // an error at round-off: 12 digits at most
  EXPECT_EQ(v, "0.5");
  EXPECT_EQ(e, "6.7e-17");
  format_with_error(2.0 / 3.0, 0.0, v, e);  // exact value: 6 significant digits
  EXPECT_EQ(v, "0.666667");
  EXPECT_EQ(e, "0");
}

TEST(Summary, PrintsEveryScalarWithErrorAndUnit) {
  test::ScratchDir dir;
  const std::string path = dir.file("run.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.write_scalar("/results/orientation/delta_theta_m", 0.785312, 0.00123, "rad", "");
    sink.write_scalar("/results/stress/eta_r", 12345.6, 78.0, "mu", "");
    sink.write_scalar("/results/diffusion/long_time/D_zz", -3.2e-7, 1.1e-8, "a^2 D0/a^2", "");
    const double g[3] = {1, 2, 3};
    sink.write_array("/results/pair/g_r", {3}, g, "", "not a scalar: not printed");
    sink.append_sample("/observables/energy", 0, 0.0, {}, g, "kT");
    sink.commit();
  }
  std::ostringstream out;
  EXPECT_EQ(print_summary(path, out), 0);
  const std::string text = out.str();
  for (const char* expected :
       {"orientation/delta_theta_m", "0.7853", "0.0012", "rad", "stress/eta_r", "12346", "78", "mu",
        "diffusion/long_time/D_zz", "-3.20e-07", "1.1e-08", "a^2 D0/a^2"})
    EXPECT_NE(text.find(expected), std::string::npos) << "missing '" << expected << "' in\n" << text;
  EXPECT_EQ(text.find("g_r"), std::string::npos) << text;
  EXPECT_NE(text.find("3 scalar results"), std::string::npos) << text;
  // One row per scalar, on its own line with value, error and unit in that order.
  EXPECT_NE(text.find("stress/eta_r"), std::string::npos);
  const std::size_t row = text.find("stress/eta_r");
  const std::string line = text.substr(row, text.find('\n', row) - row);
  EXPECT_LT(line.find("12346"), line.find("78"));
  EXPECT_LT(line.find("78"), line.find("mu"));
}

TEST(Summary, FileWithoutResultsIsAnError) {
  test::ScratchDir dir;
  const std::string path = dir.file("empty.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.commit();
  }
  std::ostringstream out;
  try {
    print_summary(path, out);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no /results"), std::string::npos) << e.what();
  }
  EXPECT_THROW(print_summary(dir.file("missing.h5"), out), Error);
}

TEST(Summary, FlagsAveragesWhoseBlockingFoundNoPlateau) {
  // Issue 12: the file holds "no plateau reached" in the description of such an average
  // (observers/common/ObserverOutput.hpp); summary marks the row and says what it means.
  test::ScratchDir dir;
  const std::string path = dir.file("run.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.write_scalar("/results/orientation/delta_theta_m", -0.03, 0.004, "rad",
                      "theta_m - 1 (mean over 40 samples; SE by Flyvbjerg-Petersen blocking, no plateau "
                      "reached: SE is a lower bound)");
    sink.write_scalar("/results/orientation/S_zz", 0.04, 0.002, "1",
                      "order parameter (mean over 4000 samples; SE by Flyvbjerg-Petersen blocking)");
    sink.commit();
  }
  std::ostringstream out;
  EXPECT_EQ(print_summary(path, out), 0);
  const std::string text = out.str();
  auto line_of = [&](const std::string& key) {
    const std::size_t at = text.find(key);
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(line_of("delta_theta_m").back(), '*') << text;
  EXPECT_EQ(line_of("S_zz").find('*'), std::string::npos) << text;
  EXPECT_NE(text.find("* 1 of 2: no plateau reached"), std::string::npos) << text;
}

// A result file that a running fldsim still holds open for writing (HDF5 file locking): one line
// that says so, not the lock call's errno text ("Resource temporarily unavailable", as before).
TEST(Summary, AFileARunIsWritingIsNamedAsLocked) {
  test::ScratchDir dir;
  const std::string path = dir.file("running.h5");
  {
    Hdf5ResultSink sink(path, false);
    sink.commit();
  }
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t writer = ::fork();
  if (writer == 0) {  // another process with the file open for writing, as a run holds its .part
    H5::H5File held(path, H5F_ACC_RDWR);
    const char byte = 1;
    (void)!::write(ready[1], &byte, 1);
    ::sleep(30);
    ::_exit(0);
  }
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1);
  std::string message;
  try {
    read_result_scalars(path);
  } catch (const Error& e) {
    message = e.what();
  }
  ::kill(writer, SIGKILL);
  ::waitpid(writer, nullptr, 0);
  EXPECT_NE(message.find("running.h5: cannot read the result file: locked by another process"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace fldsim
