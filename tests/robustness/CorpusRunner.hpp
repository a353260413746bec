// Runs the real `fldsim` program on one broken input in a fresh directory and judges the
// outcome: the exit code, the error lines on stderr (each must name file:line:col and key, or
// the option), no crash (signal, sanitizer report, "internal error", "terminate"), no hang
// (time limit) and nothing left behind (the directory holds exactly what it held before).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace corpus {

struct Case {
  std::string name;
  // Files written into the case's directory before the run (name -> contents).
  std::map<std::string, std::string> files;
  // Prepares the directory further (copies an HDF5 file, ...), after `files`.
  std::function<void(const std::filesystem::path&)> setup;
  std::vector<std::string> args;  // after `fldsim`
  int exit_code = 2;
  // Each error line must match one of these (in any order); their number is the line count.
  std::vector<std::string> lines;
  std::map<std::string, std::string> env;  // extra environment
  // Files the run may leave (a run-time failure keeps its partial result by design).
  std::vector<std::string> may_leave;
};

struct Outcome {
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;
  std::string out, err;
  std::vector<std::string> left_behind;  // new files
};

struct Verdict {
  bool clear = false;     // exit code and every error line as expected
  bool crash = false;     // signal, sanitizer, internal error, terminate, timeout
  bool leftover = false;  // files left behind
  std::string why;        // for the failure message
};

Outcome run_case(const Case& c, const std::filesystem::path& dir, double timeout_s = 60.0);
Verdict judge(const Case& c, const Outcome& o);

// Tallies per class, printed as a table row.
struct Tally {
  int cases = 0, clear = 0, crashes = 0, leftovers = 0;
};
std::string table_row(const std::string& klass, const Tally& t);

}  // namespace corpus
