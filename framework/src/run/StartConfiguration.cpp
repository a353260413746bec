#include "run/StartConfiguration.hpp"

#include <chrono>
#include <iomanip>
#include <ostream>

#include "fldsim/error.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "io/FrameReader.hpp"
#include "run/StopRequest.hpp"

namespace fldsim {
namespace {

Quat orientation_from_row(const std::vector<double>& row, std::size_t i) {
  if (row.size() == 4) return Quat(row[0], row[1], row[2], row[3]).normalized();
  if (row.size() == 3) {
    const Vec3 n(row[0], row[1], row[2]);
    if (n.norm() == 0.0) throw Error("system.init.orientations[" + std::to_string(i) + "]: zero director");
    return Quat::FromTwoVectors(Vec3::UnitZ(), n.normalized());
  }
  throw Error("system.init.orientations[" + std::to_string(i) +
              "]: expected a director [nx, ny, nz] or a quaternion [w, x, y, z]");
}

void place_listed(System& sys, const Experiment& ex, std::ostream& log) {
  if (ex.init_positions.size() != sys.size())
    throw Error(ex.file + ": system.init.positions: expected " + std::to_string(sys.size()) +
                " positions (system.count), got " + std::to_string(ex.init_positions.size()));
  std::vector<Vec3> x;
  std::vector<Quat> q;
  for (std::size_t i = 0; i < sys.size(); ++i) {
    const auto& p = ex.init_positions[i];
    if (p.size() != 3)
      throw Error(ex.file + ": system.init.positions[" + std::to_string(i) + "]: expected [x, y, z]");
    x.emplace_back(p[0], p[1], p[2]);
    q.push_back(i < ex.init_orientations.size() ? orientation_from_row(ex.init_orientations[i], i)
                                                : Quat::Identity());
  }
  geometry::place_explicit(sys, x, q);
  log << "start: " << sys.size() << " bodies placed as listed in the experiment\n";
}

void place_from_file(System& sys, const Experiment& ex, std::ostream& log) {
  const Checkpoint c = read_last_frame(ex.init_file);
  if (c.positions.size() != sys.size())
    throw Error(ex.init_file + ": has " + std::to_string(c.positions.size()) +
                " bodies, the experiment asks for " + std::to_string(sys.size()));
  sys.positions() = c.positions;
  sys.orientations() = c.orientations;
  sys.box().set_strain(c.strain);
  sys.update_nodes();
  log << "start: last frame of " << ex.init_file << "\n";
}

void place_by_monte_carlo(System& sys, const Experiment& ex, std::ostream& log) {
  geometry::MonteCarloOptions opt;
  opt.seed = std::uint64_t(ex.init_seed);
  opt.sweeps = ex.init_sweeps;
  opt.stop = [] {  // SIGINT/SIGTERM during a long start end it at once (run/StopRequest.hpp)
    const int sig = StopRequest::signal();
    return sig == 0 ? std::string() : std::string(StopRequest::signal_name(sig));
  };
  const auto t0 = std::chrono::steady_clock::now();
  const geometry::MonteCarloReport r =
      geometry::initialise_monte_carlo(sys, opt, [&](const std::string& m) { log << "  mc: " << m << "\n"; });
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  log << "start: hard-body Monte Carlo, " << r.sweeps << " sweeps in " << std::fixed << std::setprecision(1)
      << secs << " s (acceptance " << std::setprecision(2) << r.acceptance_translation << " / "
      << r.acceptance_rotation << "), phi = " << std::setprecision(4) << r.final_volume_fraction
      << ", overlaps " << r.overlaps << "\n"
      << std::defaultfloat;
  if (r.overlaps != 0) throw Error("Monte Carlo start left " + std::to_string(r.overlaps) + " overlaps");
  if (!r.decorrelated && opt.sweeps > 0)
    log << "warning: the start is overlap-free but ran only " << r.sweeps_at_target << " of the "
        << opt.sweeps << " sweeps of system.init.sweeps at the target: the compression used most of the "
        << opt.max_sweeps << " sweeps a start may take; let the run relax before observers start\n";
  else if (!r.decorrelated)
    log << "warning: the start is overlap-free but did not decorrelate within " << r.sweeps
        << " sweeps (since the compression ended: mean-square displacement " << r.msd_since_target
        << " a^2, P2 " << r.p2_since_target << "; the rule asks > " << opt.relaxation_msd << " a^2 and < "
        << opt.relaxation_p2
        << "): phi this high is glassy or crystalline for hard bodies; "
           "let the run relax before observers start, or set system.init.sweeps\n";
}

}  // namespace

void place_start_configuration(System& sys, const Experiment& ex, std::ostream& log) {
  if (ex.init_method == "explicit")
    place_listed(sys, ex, log);
  else if (ex.init_method == "file")
    place_from_file(sys, ex, log);
  else
    place_by_monte_carlo(sys, ex, log);
}

}  // namespace fldsim
