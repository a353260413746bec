// A mutation fuzzer over the example experiments and over result and checkpoint files, run
// in-process so that AddressSanitizer and UndefinedBehaviorSanitizer see every byte the readers
// touch (`make sanitize`). Every mutant must be either accepted or refused with a ConfigError
// (experiments) or fldsim::Error (HDF5 files): any other exception, a crash, a sanitizer report
// or a hang fails the test. Deterministic: mutant i of a run is the same on every machine.
// FLDSIM_FUZZ_ITERATIONS sets the budget (default 300 experiment and 150 file mutants, a few
// seconds; `make sanitize` uses 2000). A failing mutant is saved next to the test for replay.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "CorpusRunner.hpp"
#include "config/RunCheck.hpp"
#include "io/Checkpoint.hpp"
#include "io/FrameReader.hpp"
#include "io/Summary.hpp"
#include "run/Experiment.hpp"

namespace {

namespace fs = std::filesystem;

long budget(long fallback) {
  if (const char* env = std::getenv("FLDSIM_FUZZ_ITERATIONS")) {
    const long n = std::strtol(env, nullptr, 10);
    if (n > 0) return n;
  }
  return fallback;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  std::size_t pick(std::size_t n) {
    return n ? std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_) : 0;
  }

  // Text mutations that reach the YAML parser and the validators: YAML punctuation, extreme
  // numbers, lines duplicated, swapped, cut.
  std::string text(std::string s) {
    static const std::string punctuation = ":-[]{},#&*!|>'\"%@`\t\n ?";
    static const char* const tokens[] = {"0",           "-1",   "1e308", "1e-308", "-1e308",
                                         ".nan",        ".inf", "~",     "null",   "99999999999999999999",
                                         "4294967297",  "2.5",  "''",    "[]",     "{}",
                                         "[[1, 2, 3]]", "yes",  "&a",    "*a",     "!!str",
                                         "---",         "...",  "x: y",  "- 1"};
    const int edits = 1 + int(pick(3));
    for (int e = 0; e < edits && !s.empty(); ++e) {
      const std::size_t at = pick(s.size());
      switch (pick(7)) {
        case 0:
          s[at] = punctuation[pick(punctuation.size())];
          break;
        case 1:
          s.insert(at, 1, punctuation[pick(punctuation.size())]);
          break;
        case 2:
          s.erase(at, 1 + pick(8));
          break;
        case 3: {  // replace a number with an extreme one
          std::size_t d = s.find_first_of("0123456789", at);
          if (d == std::string::npos) d = s.find_first_of("0123456789");
          if (d == std::string::npos) break;
          std::size_t end = s.find_first_not_of("0123456789.e-+", d);
          s.replace(d, (end == std::string::npos ? s.size() : end) - d, tokens[pick(std::size(tokens))]);
          break;
        }
        case 4: {  // duplicate a line
          const std::size_t b = s.rfind('\n', at), e2 = s.find('\n', at);
          const std::size_t from = b == std::string::npos ? 0 : b + 1;
          const std::string line = s.substr(from, (e2 == std::string::npos ? s.size() : e2) - from);
          s.insert(from, line + "\n");
          break;
        }
        case 5:
          s.insert(at, tokens[pick(std::size(tokens))]);
          break;
        default:
          s.resize(at);
          break;
      }
    }
    return s;
  }

  // Byte mutations of a binary file: truncation, flipped bytes, a zeroed block.
  std::string bytes(std::string s) {
    switch (pick(3)) {
      case 0:
        s.resize(pick(s.size()));
        break;
      case 1:
        for (int k = 0, n = 1 + int(pick(8)); k < n && !s.empty(); ++k)
          s[pick(s.size())] ^= char(1 + pick(255));
        break;
      default: {
        const std::size_t at = pick(s.size()), n = std::min<std::size_t>(64, s.size() - at);
        std::fill(s.begin() + long(at), s.begin() + long(at + n), '\0');
        break;
      }
    }
    return s;
  }

 private:
  std::mt19937_64 rng_;
};

fs::path scratch() {
  static const fs::path dir = fs::temp_directory_path() / ("fldsim-fuzz-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(Fuzz, ExperimentFilesAreAcceptedOrRefusedCleanly) {
  const fs::path src = FLDSIM_SOURCE_DIR;
  std::vector<std::string> seeds;
  for (const char* f : {"examples/quickstart.yaml", "examples/paper/quick/homonuclear-phi0.3-pe10.yaml",
                        "examples/paper/quick/fused_dumbbell-phi0.3-pe0.1.yaml"})
    seeds.push_back(read_bytes(src / f));
  const fldsim::PluginRegistry registry(fldsim::PluginRegistry::search_path({}, "."));
  // Reads an experiment file and, unless its scene is large (building large scenes is not what is
  // fuzzed here: the reading and the checks are), counts it in `checked` and runs every pre-run check.
  auto read_and_check = [&](const fs::path& f, long& checked) {
    const fldsim::Experiment ex = fldsim::read_experiment(f.string(), {}, registry);
    if (ex.count > 2000) return;
    ++checked;
    fldsim::check_run(ex, registry, {(scratch() / "out.h5").string(), false, ""});
  };
  // The seeds themselves must pass every check: were a plugin they name missing (fuzz_tests
  // builds only those, tests/robustness/CMakeLists.txt), every mutant would be refused for that
  // one reason and the fuzzer would reach nothing behind it.
  for (const std::string& seed : seeds) {
    write_bytes(scratch() / "seed.yaml", seed);
    long seed_checked = 0;
    try {
      read_and_check(scratch() / "seed.yaml", seed_checked);
      ASSERT_EQ(seed_checked, 1) << "a seed too large to be checked";
    } catch (const std::exception& e) {
      FAIL() << "an unmutated seed is refused: " << e.what();
    }
  }
  const long n = budget(300);
  long accepted = 0, refused = 0, checked = 0;
  const fs::path file = scratch() / "mutant.yaml";
  for (long i = 0; i < n; ++i) {
    Mutator m(std::uint64_t(i) * 7919u + 1);
    const std::string text = m.text(seeds[std::size_t(i) % seeds.size()]);
    write_bytes(file, text);
    try {
      read_and_check(file, checked);
      ++accepted;
    } catch (const fldsim::ConfigError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).find("internal"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      const fs::path keep = fs::path(FLDSIM_BINARY_DIR) / ("fuzz-experiment-" + std::to_string(i) + ".yaml");
      write_bytes(keep, text);
      ADD_FAILURE() << "mutant " << i << " (saved as " << keep << "): not a ConfigError: " << e.what();
    }
  }
  std::cout << "experiment mutants: " << n << " (" << accepted << " accepted, " << refused << " refused, "
            << checked << " fully checked)" << std::endl;
  EXPECT_GT(refused, 0);
}

TEST(Fuzz, ResultAndCheckpointReadersRefuseCorruptFilesCleanly) {
  // A small real run gives a result file and a checkpoint to mutate.
  corpus::Case c;
  c.files["in.yaml"] =
      "system: {shape: {plugin: dicolloid}, count: 8, volume_fraction: 0.05}\nflow: {peclet: 1}\n"
      "hydro: {plugin: free_draining}\nrun: {dt: 0.01, duration: 0.05, threads: 1}\n"
      "observers: [{plugin: trajectory, every: 1}, {plugin: stress, every: 1}, {plugin: orientation, every: "
      "1}]\n"
      "output: out.h5\n";
  c.args = {"run", "in.yaml", "-q"};
  const fs::path run_dir = scratch() / "run";
  const corpus::Outcome o = corpus::run_case(c, run_dir);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string result = read_bytes(run_dir / "out.h5"),
                    checkpoint = read_bytes(run_dir / "out.h5.checkpoint");
  ASSERT_FALSE(result.empty());
  ASSERT_FALSE(checkpoint.empty());
  const long n = budget(150);
  long refused = 0;
  const fs::path file = scratch() / "mutant.h5";
  for (long i = 0; i < n; ++i) {
    Mutator m(std::uint64_t(i) * 104729u + 3);
    const std::string bytes = m.bytes(i % 2 ? result : checkpoint);
    write_bytes(file, bytes);
    auto attempt = [&](const char* reader, const std::function<void()>& read) {
      try {
        read();
      } catch (const fldsim::Error&) {
        ++refused;
      } catch (const std::exception& e) {
        const fs::path keep = fs::path(FLDSIM_BINARY_DIR) / ("fuzz-file-" + std::to_string(i) + ".h5");
        write_bytes(keep, bytes);
        ADD_FAILURE() << "mutant " << i << " (saved as " << keep << "), " << reader
                      << ": not an fldsim::Error: " << e.what();
      }
    };
    attempt("read_checkpoint", [&] { fldsim::read_checkpoint(file.string()); });
    attempt("read_last_frame", [&] { fldsim::read_last_frame(file.string()); });
    attempt("print_summary", [&] {
      std::ostringstream out;
      fldsim::print_summary(file.string(), out);
    });
  }
  std::cout << "file mutants: " << n << " x 3 readers, " << refused << " refusals" << std::endl;
  EXPECT_GT(refused, 0);
  fs::remove_all(scratch());
}

}  // namespace
