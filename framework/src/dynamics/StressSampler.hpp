// The bulk stress pieces of one step, for the stress observer (only on steps it samples):
//   hydrodynamic  = sum of stresslets at the start x of the step with the deterministic velocity
//                   dU_det = M(x) (F_P + R_FE:E_inf) (one extra solve without F_B), + R_SE:E_inf;
//   interparticle = -sum R (x) f_j over node pairs at x (the force laws' molecular virial, force.hpp);
//   brownian      = S(x', dU_mid) - S(x, dU_start), the change of the full stresslet sum between
//                   the start and the midpoint stage of the midpoint scheme (same F_B).
// Why the Brownian piece is right: with L the stresslet's linear map of dU (-R_SU) and the
// midpoint x' = x + (dt/2) M F_B, <F_B F_B^T> = (2kT/dt) R, expanding gives
//   E[L(x') M(x') F_B] = kT d_k (L M)_{.k} = -kT div(R_SU R_FU^-1),
// the Brownian stress of Brady (J. Chem. Phys. 98, 3335 (1993)); the midpoint estimate is that of
// Banchio & Brady (J. Chem. Phys. 118, 10323 (2003)). Subtracting S(x, dU_start), whose mean is the
// deterministic S(x), removes the zero-mean O(dt^-1/2) noise L M F_B and leaves the O(dt) change
// of the deterministic part: the variance drops from O(1/dt) to O(1). Without a midpoint stage
// (drift: none) there is no Brownian estimate. The extra solve restores the solver's warm start,
// so a run is bit-identical with or without a stress observer; it starts from the previous
// sample's deterministic solution.
// With a BrownianStressProbe (run.brownian_stress: random_difference, the default) the Brownian
// piece is the probe's step-independent estimate at x instead, in any integrator.
#pragma once

#include <vector>

#include "dynamics/BrownianStressProbe.hpp"
#include "dynamics/TimeIntegrator.hpp"
#include "fldsim/observer.hpp"

namespace fldsim {

class StressSampler {
 public:
  // midpoint: the integrator calls the Final stage at the midpoint (Euler-Maruyama, drift midpoint).
  StressSampler(std::size_t bodies, bool brownian, bool midpoint);

  // The integrator's stage hook: Start right after the solve at x, Final after the midpoint solve.
  void sample(StressStage stage, const System& s, VelocityEvaluator& ev);

  // Take the Brownian piece from the probe (not owned; null = the midpoint difference).
  void use_probe(BrownianStressProbe* probe) { probe_ = probe; }

  const StressPieces& pieces() const { return pieces_; }
  // The step's last own solve (the extra deterministic solve is not counted).
  const SolveStats& step_solve() const { return step_solve_; }
  // The last deterministic solution, the next sample's CG start: part of a checkpoint, since the
  // last bits of the stress depend on it (a vector of another size, e.g. from an older
  // checkpoint, or with a non-finite value leaves the start at zero).
  const std::vector<double>& deterministic() const { return deterministic_; }
  void restore_deterministic(const std::vector<double>& dU);

 private:
  bool brownian_, midpoint_;
  BrownianStressProbe* probe_ = nullptr;
  StressPieces pieces_;
  SolveStats step_solve_;
  Eigen::Matrix3d start_total_ = Eigen::Matrix3d::Zero();
  std::vector<double> dU_step_;
  std::vector<double> deterministic_;
};

}  // namespace fldsim
