#include "sweep/SweepPoints.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <ostream>
#include <set>
#include <sstream>

#include "config/ConfigErrors.hpp"
#include "config/RunCheck.hpp"
#include "fldsim/error.hpp"
#include "plugins/PluginRegistry.hpp"
#include "run/Experiment.hpp"
#include "sweep/StoredRun.hpp"

namespace fldsim {
namespace {

namespace fs = std::filesystem;

// A point's error lines, with the `--set KEY=VALUE` labels of sweep values replaced by where
// the value is written in the sweep file: "study.yaml:7:20: axis flow.peclet = -1 (point
// peclet--1): flow.peclet: expected a number >= 0". Lines about the base file keep their place
// and get the point's name.
std::string point_errors(const std::string& text, const SweepPoint& p) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    bool replaced = false;
    for (const auto& v : p.settings) {
      const std::string label = "--set " + v.key + "=" + v.yaml;
      if (line.rfind(label, 0) == 0) {
        // The place in the sweep file says it for every point with this value: one line.
        line = v.origin + ": " + v.role + " = " + v.yaml + line.substr(label.size());
        replaced = true;
        break;
      }
    }
    if (!replaced) line = line + " (point " + p.label + ": " + p.describe() + ")";
    out += line + "\n";
  }
  if (!out.empty()) out.pop_back();
  return out;
}

// "stored `run: {duration: 0.4}`, now `run: {duration: 0.5}`": the first line that differs.
std::string first_difference(const std::string& then, const std::string& now) {
  std::istringstream a(then), b(now);
  std::string la, lb;
  for (;;) {
    const bool ga = bool(std::getline(a, la)), gb = bool(std::getline(b, lb));
    if (!ga && !gb) return "(same text)";
    if (!ga) la = "(end)";
    if (!gb) lb = "(end)";
    if (la != lb || !ga || !gb) return "stored `" + la + "`, now `" + lb + "`";
  }
}

}  // namespace

const char* to_string(PointStatus s) {
  switch (s) {
    case PointStatus::Run:
      return "to run";
    case PointStatus::Resume:
      return "to resume";
    case PointStatus::Done:
      return "done";
    case PointStatus::Changed:
      return "changed";
  }
  return "?";
}

// Per sphere and force evaluation: FLD and lubrication assemble and solve a sparse resistance
// problem (IC(0)-preconditioned CG, ~15 iterations at phi 0.3-0.45), free draining does
// neither. Calibrated on bench/RESULTS.md's N = 1000 step times (5.2 ms at phi 0.3, two
// evaluations per Brownian step) and the free-draining quickstart; docs/sweep.md.
double estimated_cpu_seconds(const std::string& hydro, std::int64_t steps, std::int64_t nodes,
                             bool brownian) {
  const double per_node_evaluation = hydro == "free_draining" ? 0.25e-6 : 2.6e-6;
  const double evaluations = brownian ? 2.0 : 3.0;  // midpoint scheme; RK3 without noise
  return double(steps) * double(nodes) * per_node_evaluation * evaluations;
}

std::string format_duration(double s) {
  char buffer[32];
  if (s < 10)
    std::snprintf(buffer, sizeof buffer, "%.1f s", s);
  else if (s < 120)
    std::snprintf(buffer, sizeof buffer, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buffer, sizeof buffer, "%.1f min", s / 60);
  else
    std::snprintf(buffer, sizeof buffer, "%.1f h", s / 3600);
  return buffer;
}

double share_left(std::int64_t frames, std::int64_t done, bool adaptive) {
  if (adaptive || frames <= 0) return 1.0;
  return std::clamp(double(frames - done) / double(frames), 0.0, 1.0);
}

std::vector<PointState> check_sweep_points(const SweepPlan& plan) {
  std::vector<PointState> states;
  ConfigErrors errors(plan.file);
  std::unique_ptr<PluginRegistry> registry;
  std::set<std::string> reported;
  for (std::size_t i = 0; i < plan.points.size(); ++i) {
    const SweepPoint& p = plan.points[i];
    PointState st;
    st.index = i;
    st.output = plan.output_of(p);
    st.checkpoint = st.output + ".checkpoint";
    st.log = (fs::path(plan.output_dir) / (p.label + ".log")).string();
    try {
      const Experiment ex = registry ? read_experiment(plan.base, p.overrides(), *registry)
                                     : read_experiment(plan.base, p.overrides(), registry);
      st.hydro = ex.hydro.name;
      std::error_code ec;
      RunTargets targets{st.output, false, ""};
      StoredRun stored;  // empty experiment: no readable result
      if (fs::exists(st.output, ec)) {
        try {
          stored = read_stored_run(st.output);
        } catch (const H5::Exception&) {
          stored = StoredRun{};
        }
      }
      const std::string& then = stored.experiment;
      st.interrupted_output = stored.interrupted && fs::exists(st.checkpoint, ec);
      if (fs::exists(st.output, ec) && !st.interrupted_output) {
        if (then == ex.resolved_yaml) {
          st.status = PointStatus::Done;
        } else {
          st.status = PointStatus::Changed;
          st.why_changed =
              then.empty()
                  ? st.output + " is not a readable fldsim result"
                  : st.output + " holds a different experiment: " + first_difference(then, ex.resolved_yaml);
        }
        targets.overwrite = true;  // checked as the re-run would be (its old file moved aside)
      } else if (fs::exists(st.checkpoint, ec)) {
        // A run stopped by a signal (its partial result is moved aside when it resumes) or
        // killed (only its periodic checkpoint is left).
        st.status = PointStatus::Resume;
        targets.resume = st.checkpoint;
        targets.overwrite = st.interrupted_output;
      }
      RunCheckReport report;
      try {
        report = check_run(ex, *registry, targets);
      } catch (const ConfigError& e) {
        if (st.status != PointStatus::Resume) throw;
        // A checkpoint of another experiment: the point itself may still be fine.
        st.status = PointStatus::Changed;
        st.why_changed = std::string(e.what()).substr(0, 400);
        report = check_run(ex, *registry, RunTargets{st.output, true, ""});
      }
      st.steps = report.steps;
      st.nodes = report.nodes;
      st.cost_seconds = estimated_cpu_seconds(st.hydro, st.steps, st.nodes, ex.brownian);
      st.whole_cost_seconds = st.cost_seconds;
      if (st.status == PointStatus::Resume)
        st.cost_seconds *= share_left(st.steps, report.resume_step, ex.dt_auto);
      st.adaptive = ex.dt_auto;
      st.frame = ex.dt;
      for (const auto& o : ex.observers) st.observer_every.push_back(o.every);
    } catch (const ConfigError& e) {
      std::istringstream lines(point_errors(e.what(), p));
      for (std::string line; std::getline(lines, line);)
        if (reported.insert(line).second) errors.add_formatted(line);
    } catch (const Error& e) {
      errors.add_formatted(plan.file + ": point " + p.label + ": " + e.what());
    }
    states.push_back(std::move(st));
  }
  errors.throw_if_any();
  return states;
}

std::vector<std::size_t> run_order(const std::vector<PointState>& points, bool rerun_changed) {
  std::vector<std::size_t> order;
  for (const auto& p : points)
    if (p.status == PointStatus::Run || p.status == PointStatus::Resume ||
        (rerun_changed && p.status == PointStatus::Changed))
      order.push_back(p.index);
  // Longest first: the last points to finish are then the short ones, so no slot idles long.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return points[a].cost_seconds > points[b].cost_seconds;
  });
  return order;
}

void print_sweep_listing(const SweepPlan& plan, const std::vector<PointState>& points, std::ostream& out) {
  std::size_t width = 5;
  for (const auto& p : plan.points) width = std::max(width, p.label.size());
  out << std::left << std::setw(int(width)) << "point"
      << "  " << std::setw(10) << "status"
      << "  " << std::setw(12) << "steps" << std::setw(8) << "nodes"
      << "  est. CPU\n";
  double todo = 0.0, all = 0.0;
  std::size_t counts[4] = {0, 0, 0, 0};
  for (const auto& st : points) {
    const SweepPoint& p = plan.points[st.index];
    out << std::left << std::setw(int(width)) << p.label << "  " << std::setw(10) << to_string(st.status)
        << "  " << std::setw(12) << st.steps << std::setw(8) << st.nodes << "  "
        << (st.adaptive && !st.timed ? ">= " : "") << format_duration(st.cost_seconds)
        << (st.timed ? " (timed)" : "") << "\n";
    all += st.whole_cost_seconds;
    if (st.status != PointStatus::Done) todo += st.cost_seconds;
    ++counts[int(st.status)];
  }
  out << points.size() << " points: " << counts[int(PointStatus::Run)] << " to run, "
      << counts[int(PointStatus::Resume)] << " to resume, " << counts[int(PointStatus::Done)] << " done, "
      << counts[int(PointStatus::Changed)] << " changed; estimated CPU " << format_duration(todo)
      << " to go (" << format_duration(all) << " for the whole sweep; " << plan.threads
      << " thread(s) per point)\n";
  for (const auto& st : points)
    if (st.timed) {
      out << "\"(timed)\": the point's frames x its measured time per frame (--timed); the others: the cost "
             "model\n";
      break;
    }
  for (const auto& st : points)
    if (st.adaptive && !st.timed) {
      out << "\">=\": dt: auto; the estimate counts one step per frame, and adaptive runs take more "
             "(--timed K measures them)\n";
      break;
    }
  for (const auto& st : points)
    if (st.status == PointStatus::Changed)
      out << "changed: " << plan.points[st.index].label << ": " << st.why_changed << "\n";
}

}  // namespace fldsim
