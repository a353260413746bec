// The Brownian stress of a configuration by a random finite difference (RFD), independent of
// the time step. With L(x) F = S(x, M(x) F) the stresslet sum of the velocities that forces F
// produce without flow (M = R_FU^-1), the Brownian stress is kT d_k L_{.k} (Brady, J. Chem.
// Phys. 98, 3335 (1993)); for W ~ N(0, I) over the 6N body coordinates (translations and rotation
// vectors)
//   E[ L(x + delta/2 W) W - L(x - delta/2 W) W ] / delta = d_k L_{.k} + O(delta^2)
// (random finite differences: Delong, Usabiaga & Donev, J. Chem. Phys. 140, 134110 (2014)).
// Why not the midpoint stage of the step (StressSampler's other estimate): near contact L varies
// like 1/ln(gap) down to the lubrication floor delta_num, and a step moves a pair at gap h by about
// sqrt(8 h dt), comparable to h itself for h ~ 1e-3 a at dt ~ 1e-4 a^2/D0: the midpoint estimate's
// O(dt) bias then decays only slowly with dt (docs/equilibrium-oracle.md measures it). The probe
// moves pairs by ~delta, whose default 1e-4 a is chosen by measurement: FLD spheres' pressure is
// the same with 1e-6, 1e-5 and 1e-4 to 0.002 (the pairs at gaps below delta carry little of it),
// while a mobility with jumps (the paper's sharp visibility rule of dicolloids) gives the estimate
// a surface term sampled with probability ~ delta and size ~ 1/delta: at 1e-6 single samples of
// 28 standard deviations and a run-to-run scatter 4x that of 1e-4.
// It works on its own copy of the system, neighbour list and hydro model, so the run's trajectory,
// warm start and preconditioner are untouched (a run is bit-identical with or without it). Its
// solves need a tight tolerance: a solve error e adds e |S| / delta to one sample.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "dynamics/BodyMotion.hpp"
#include "fldsim/hydro.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim {

class BrownianStressProbe {
 public:
  static constexpr double kDefaultDelta = 1e-4;      // a (run.brownian_stress_delta)
  static constexpr double kDefaultTolerance = 1e-8;  // relative residual (run.brownian_stress_tolerance)

  // hydro: an instance of the run's hydro model of its own (configured here for stresslets
  // only); range and skin as the run's neighbour list; delta in a; seed: the run's seed.
  BrownianStressProbe(std::shared_ptr<HydroModel> hydro, const System& s, double range, double skin,
                      double delta, std::uint64_t seed);

  // kT d_k L_{.k} (3x3, summed over bodies like the stresslet sum) at the configuration of s.
  // The normals W are those of (seed, s.step()): the same configuration and step give the same value.
  Eigen::Matrix3d measure(const System& s);
  // CG iterations of the last measure (both solves).
  int last_iterations() const { return iterations_; }
  double delta() const { return delta_; }

 private:
  // L(x + h W) W for the base configuration x (probe_ is left at x + h W).
  Eigen::Matrix3d response_at(double h);

  std::shared_ptr<HydroModel> hydro_;
  System probe_;
  BodySnapshot base_;
  geometry::CellNeighbourList list_;
  std::vector<double> W_, u_;
  double delta_;
  std::uint64_t seed_;
  int iterations_ = 0;
};

}  // namespace fldsim
