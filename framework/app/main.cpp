// The fldsim command line: run, check, plugins, summary. Exit codes: 0 success, 1 run-time
// failure, 2 bad input (experiment file, command line).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "SweepCommand.hpp"
#include "config/RunCheck.hpp"
#include "fldsim/api.hpp"
#include "fldsim/error.hpp"
#include "fldsim/force.hpp"
#include "fldsim/hydro.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/shape.hpp"
#include "io/Summary.hpp"
#include "oracle/OracleCommand.hpp"
#include "plugins/PluginRegistry.hpp"
#include "run/Experiment.hpp"
#include "run/RunExperiment.hpp"
#include "run/Simulation.hpp"

namespace {

const char* kUsage =
    "fldsim — Brownian suspensions of rigid colloids under shear (Fast Lubrication Dynamics)\n"
    "\n"
    "usage: fldsim <command> [options]\n"
    "\n"
    "commands:\n"
    "  run FILE.yaml [-o OUT.h5]   run an experiment\n"
    "  check FILE.yaml             validate an experiment without running it\n"
    "  plugins                     list every plugin found, with its parameters\n"
    "  summary RUN.h5              print the steady-state results of a run\n"
    "  oracle FILE.yaml            exact equilibrium g(r) and Z of its potential (Monte Carlo)\n"
    "  export RUN.h5 --gsd OUT.gsd  the trajectory as GSD frames (OVITO, HOOMD tools)\n"
    "  sweep SWEEP.yaml            a study: every point of a sweep file, locally or over MPI\n"
    "\n"
    "`fldsim CMD --help` documents each command; `fldsim --version` prints the version.\n";

const char* kRunHelp =
    "usage: fldsim run FILE.yaml [options]\n"
    "\n"
    "  -o, --output OUT.h5     result file (overrides the experiment's `output`)\n"
    "  --overwrite             replace an existing result file (refused otherwise)\n"
    "  --set KEY=VALUE         override any key by its dotted path before validation, e.g.\n"
    "                          --set flow.peclet=10 --set system.shape.c=1 --set observers[1].every=50\n"
    "                          (repeatable; sweeps; list entries also as observers.1.every)\n"
    "  --resume CHECKPOINT     continue a run exactly from OUT.h5.checkpoint\n"
    "  -q, --quiet             nothing on stderr except errors (no log, no progress lines)\n"
    "\n"
    "The result file is written as OUT.h5.part and renamed to OUT.h5 when the run ends; a\n"
    "checkpoint OUT.h5.checkpoint is written every run.checkpoint_every and at the end.\n"
    "\n"
    "Experiment keys (plugins document theirs in `fldsim plugins`):\n";

const char* kCheckHelp =
    "usage: fldsim check FILE.yaml [-o OUT.h5] [--overwrite] [--resume CHECKPOINT] [--set KEY=VALUE ...]\n"
    "Checks everything `fldsim run` with the same options would, without running or writing\n"
    "anything: every key against the core and plugin schemas, every plugin constructed, the scene\n"
    "(volume fraction the Monte Carlo start can pack, bodies and pair range against the box),\n"
    "the step count and memory against this machine, listed positions, init files, the result\n"
    "and checkpoint files (never replaced without --overwrite) and, with --resume, that the\n"
    "checkpoint belongs to this experiment. Prints all problems, one line each, as\n"
    "FILE:LINE:COL: key.path: message (or naming the option). Exit code 0 if valid, 2 otherwise.\n";

const char* kPluginsHelp =
    "usage: fldsim plugins [--path DIR ...]\n"
    "Lists every plugin found on the search path (--path dirs, then FLDSIM_PLUGIN_PATH, then the\n"
    "build and install plugin directories): kind, name, version, file and parameters; every\n"
    "library that shadows another of the same kind and name (the first found is used); and any\n"
    "library that could not be used, with the reason. Each library is looked into by a child\n"
    "process, so one that crashes, aborts or hangs (FLDSIM_PLUGIN_LOAD_TIMEOUT seconds, default\n"
    "20) while loading is reported and skipped.\n";

const char* kSummaryHelp =
    "usage: fldsim summary RUN.h5\n"
    "Prints every steady-state scalar under /results as a table: name, value, standard error, unit.\n";

std::string format_default(const fldsim::ParamValue& v) {
  std::ostringstream out;
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>)
          out << (x ? "true" : "false");
        else if constexpr (std::is_same_v<T, std::string>)
          out << (x.empty() ? "''" : x);
        else if constexpr (std::is_same_v<T, std::vector<double>>)
          out << (x.empty() ? "[]" : "[...]");
        else if constexpr (std::is_same_v<T, std::vector<std::vector<double>>>)
          out << (x.empty() ? "[]" : "[[...]]");
        else
          out << x;
      },
      v);
  return out.str();
}

bool is_help(const std::string& a) {
  return a == "-h" || a == "--help";
}

int usage_error(const std::string& message, const char* help) {
  std::cerr << "fldsim: " << message << "\n\n" << help;
  return 2;
}

// -q: nothing on stderr but errors while the run lasts, including what plugins print there (a
// `progress` observer listed in the experiment); restored before main() prints an error.
class SilencedStderr {
 public:
  explicit SilencedStderr(bool silence)
      : saved_(silence ? std::cerr.rdbuf(nullptr) : nullptr), active_(silence) {}
  ~SilencedStderr() {
    if (active_) {
      std::cerr.rdbuf(saved_);
      std::cerr.clear();
    }
  }
  SilencedStderr(const SilencedStderr&) = delete;
  SilencedStderr& operator=(const SilencedStderr&) = delete;

 private:
  std::streambuf* saved_;
  bool active_;
};

int cmd_run(const std::vector<std::string>& args, bool check_only) {
  std::string file;
  std::vector<std::string> overrides;
  fldsim::RunOptions opt;
  const char* help = check_only ? kCheckHelp : kRunHelp;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= args.size()) throw fldsim::ConfigError(std::string(a) + ": expected " + what);
      // An empty file name (e.g. an unset shell variable) would otherwise mean "not given".
      if (args[i + 1].empty()) throw fldsim::ConfigError(std::string(a) + ": expected " + what + ", got ''");
      return args[++i];
    };
    if (is_help(a)) {
      std::cout << help;
      if (!check_only) std::cout << fldsim::core_keys_help();
      return 0;
    } else if (a == "--set") {
      overrides.push_back(value("KEY=VALUE"));
    } else if (a == "-o" || a == "--output") {
      opt.output = value("a file name");
    } else if (a == "--overwrite") {
      opt.overwrite = true;
    } else if (a == "--resume") {
      opt.resume = value("a checkpoint file");
    } else if (a == "-q" || a == "--quiet") {
      opt.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option " + a, help);
    } else if (file.empty()) {
      file = a;
    } else {
      return usage_error("more than one experiment file given", help);
    }
  }
  if (file.empty()) return usage_error("no experiment file given", help);
  std::unique_ptr<fldsim::PluginRegistry> registry;
  const fldsim::Experiment ex = fldsim::read_experiment(file, overrides, registry);
  // Everything `run` would refuse, refused now, before any work or file (RunCheck.hpp).
  const fldsim::RunCheckReport report =
      fldsim::check_run(ex, *registry, {opt.output, opt.overwrite, opt.resume});
  std::ostream null_stream(nullptr);
  std::ostream& log = opt.quiet ? null_stream : std::cerr;
  for (const auto& w : report.warnings) log << "warning: " << w << "\n";
  if (check_only) {
    std::cout << file << ": valid (" << report.summary << ")\n";
    return 0;
  }
  const SilencedStderr silenced(opt.quiet);
  return fldsim::run_experiment(ex, *registry, opt, log);
}

int cmd_plugins(const std::vector<std::string>& args) {
  std::vector<std::string> extra;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (is_help(args[i])) {
      std::cout << kPluginsHelp;
      return 0;
    }
    if (args[i] == "--path" && i + 1 < args.size()) {
      extra.push_back(args[++i]);
      std::error_code ec;
      if (!std::filesystem::is_directory(extra.back(), ec))
        std::cerr << "warning: --path " << extra.back() << ": not a directory (ignored)\n";
    } else
      return usage_error("unknown argument " + args[i], kPluginsHelp);
  }
  fldsim::PluginRegistry registry(fldsim::PluginRegistry::search_path(extra, "."));
  std::cout << "search path:";
  for (const auto& d : registry.directories()) std::cout << " " << d;
  std::cout << "\n";
  for (const auto& p : registry.plugins()) {
    std::cout << "\n"
              << p.kind << " " << p.name << " " << p.version << "  — " << p.summary << "\n  file: " << p.file
              << "\n";
    for (const auto& s : p.schema.specs()) {
      std::cout << "  " << s.name << ": " << s.expectation();
      if (!s.unit.empty()) std::cout << " [" << s.unit << "]";
      std::cout << (s.default_value ? ", default " + format_default(*s.default_value)
                                    : std::string(" (required)"))
                << " — " << s.help << "\n";
    }
  }
  for (const auto& s : registry.shadowed()) std::cout << "\nshadowed: " << s << "\n";
  for (const auto& f : registry.failures()) std::cout << "\nnot loaded: " << f << "\n";
  return 0;
}

// `export` is the Python module fldsim.gsd_export (h5py, gsd) run with Debian's interpreter; the
// package sits in the build tree's python/ or, installed, in LIBDIR/fldsim/python.
int cmd_export(const std::vector<std::string>& args) {
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe");
  const std::filesystem::path build_dir = FLDSIM_PYTHON_BUILD_DIR;
  const std::filesystem::path package_dir = std::filesystem::exists(build_dir / "fldsim" / "gsd_export.py") &&
                                                    exe.parent_path() == FLDSIM_BIN_BUILD_DIR
                                                ? build_dir
                                                : exe.parent_path() / FLDSIM_PYTHON_FROM_BIN;
  const char* old = std::getenv("PYTHONPATH");
  const std::string path = package_dir.string() + (old && *old ? ":" + std::string(old) : std::string());
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> argv_text{"python3", "-m", "fldsim.gsd_export"};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv("/usr/bin/python3", argv.data());
  execvp("python3", argv.data());  // returns only on failure
  std::cerr
      << "fldsim export: cannot run python3 (Debian: apt-get install python3 python3-h5py python3-gsd)\n";
  return 1;
}

int cmd_summary(const std::vector<std::string>& args) {
  if (args.empty()) return usage_error("no result file given", kSummaryHelp);
  if (is_help(args[0])) {
    std::cout << kSummaryHelp;
    return 0;
  }
  return fldsim::print_summary(args[0], std::cout);
}

}  // namespace

// libgomp reads its wait policy when it is loaded, before main, so `run` sets it by executing
// itself once more. By default a thread spins ~300000 times at every barrier before it sleeps;
// on a shared machine that spinning holds a core another thread of the same run needs, and a
// step can take a hundred times longer. GOMP_SPINCOUNT = 10000 (~10 us) keeps back-to-back
// parallel regions fast and yields soon after. Users who set a policy themselves are left alone.
void set_openmp_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  setenv("GOMP_SPINCOUNT", "10000", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: run on with the default policy
}

namespace {

int dispatch(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "run") set_openmp_wait_policy(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string cmd = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (is_help(cmd)) {
      std::cout << kUsage;
      return 0;
    }
    if (cmd == "--version" || cmd == "version") {
      std::cout << "fldsim " << FLDSIM_VERSION << " (plugin API " << FLDSIM_API_MAJOR << "."
                << FLDSIM_API_MINOR << ")\n";
      return 0;
    }
    if (cmd == "export") return cmd_export(rest);
    if (cmd == "run") return cmd_run(rest, false);
    if (cmd == "check") return cmd_run(rest, true);
    if (cmd == "plugins") return cmd_plugins(rest);
    if (cmd == "summary") return cmd_summary(rest);
    if (cmd == "sweep") return fldsim::sweep_command(rest);
    if (cmd == "oracle") return fldsim::oracle_command(rest, std::cout, std::cerr);
    return usage_error("unknown command '" + cmd + "'", kUsage);
  } catch (const fldsim::ConfigError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const fldsim::Error& e) {
    std::cerr << "fldsim: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "fldsim: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "fldsim: internal error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "fldsim: internal error: an exception of unknown type\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int code = dispatch(argc, argv);
  // A failed run may hold HDF5 files it could not close (a full disk): it ends without the
  // library's exit handlers, which would try to flush them again and can crash. Everything the
  // run keeps (its checkpoint) is already on disk, synced and renamed.
  if (code != 0 && code != 2) {
    std::cout.flush();
    std::cerr.flush();
    std::_Exit(code);
  }
  return code;
}
