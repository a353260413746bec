// "The velocities of this configuration" — the one function every integrator stage calls:
//   refresh node pairs; F_P = sum of force laws; assemble R; (draw F_B);
//   solve R_FU (U - U_inf) = F_P + F_B + R_FE:E_inf;  U = U_inf + dU.
// Buffers are sized once; nothing is allocated per call.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "dynamics/BrownianBridge.hpp"
#include "fldsim/force.hpp"
#include "fldsim/hydro.hpp"
#include "geometry/CellNeighbourList.hpp"

namespace fldsim {
using geometry::CellNeighbourList;

class VelocityEvaluator {
 public:
  VelocityEvaluator(std::shared_ptr<HydroModel> hydro, std::vector<std::shared_ptr<ForceLaw>> forces,
                    CellNeighbourList& pairs, std::size_t bodies);

  // Pairs, interparticle forces (and their virial if asked) and the resistance at the current
  // configuration of s (node positions must be current).
  void prepare(System& s, bool want_virial);
  // F_B for the prepared configuration (overwrites the stored Brownian force).
  void draw_brownian(const System& s, const RandomStream& noise, double dt);
  // F_B = sqrt(2 kT) (A W + B W_pair) / h for the Wiener increments W = sum_j c_j xi_j of
  // `interval` (length h): one hydro draw brownian_force(stream, h) from the stream standing for
  // the combination sum_j (c_j / sqrt(h)) xi_j (RandomStream::combined), the model's draw being
  // linear in its normals. One term (a whole base interval) is the fixed-step draw
  // brownian_force(stream_0, h) itself, bit for bit.
  void draw_brownian(const System& s, std::uint64_t seed, const BrownianBridge& bridge,
                     const NoiseInterval& interval);
  // F_B = (F_B[xi_k] + F_B[xi_{k+1}]) / 2 for the whole base interval k = interval.base (depth 0)
  // and the next one, both with the prepared configuration's resistance (LeimkuhlerMatthews):
  // two plain draws, the first bit for bit the fixed-step draw of step k.
  void draw_brownian_with_next(const System& s, std::uint64_t seed, const NoiseInterval& interval);
  // Refresh the pair list at the current configuration; smallest node surface gap (a).
  double min_gap(const System& s);
  // Solve with F_P (+ the stored F_B if with_brownian). Warm-started from the previous dU.
  void solve(const System& s, bool with_brownian);

  const double* velocity() const { return U_.data(); }            // total U, Omega (6N)
  const double* relative_velocity() const { return dU_.data(); }  // U - U_inf (6N)
  const double* force() const { return FP_.data(); }              // F_P (6N)
  const double* brownian_force() const { return FB_.data(); }
  const Eigen::Matrix3d& virial() const { return virial_; }
  std::vector<double>& warm_start() { return dU_; }
  const NodePairList& pairs() const { return list_.pairs(); }
  const CellNeighbourList& neighbour_list() const { return list_; }
  HydroModel& hydro() { return *hydro_; }
  SolveStats stats() const { return hydro_->last_solve(); }
  // CG iterations of every solve so far (all stages, and extra solves for the stress).
  std::int64_t total_iterations() const { return total_iterations_; }

 private:
  std::shared_ptr<HydroModel> hydro_;
  std::vector<std::shared_ptr<ForceLaw>> forces_;
  CellNeighbourList& list_;
  std::vector<double> FP_, FB_, FB_next_, F_, dU_, U_;
  BrownianBridge::Terms terms_;
  NormalCombination combination_;  // the bridge's terms as one stream (draw_brownian)
  Eigen::Matrix3d virial_ = Eigen::Matrix3d::Zero();
  std::int64_t total_iterations_ = 0;
};

}  // namespace fldsim
