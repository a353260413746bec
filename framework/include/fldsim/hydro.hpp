// A hydrodynamic model: the body-level resistance R of the current configuration, the Brownian
// forces that go with it, and the solve for the velocities. The core's step is
//   assemble(x);  F_B = brownian_force(noise);  solve R_FU (U - U_inf) = F_P + F_B + R_FE:E_inf
// and a multi-stage scheme (midpoint drift, Runge–Kutta) calls assemble/solve again at the
// stage configurations.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "fldsim/error.hpp"
#include "fldsim/neighbours.hpp"
#include "fldsim/plugin_base.hpp"
#include "fldsim/random.hpp"
#include "fldsim/system.hpp"

namespace fldsim {

// What the run needs from the model, fixed before the first step, so the model can skip
// (and say it skips) everything else.
struct HydroRequest {
  bool brownian = true;     // kT > 0: Brownian forces needed
  bool shear = true;        // gammadot != 0: R_FE:E_inf needed
  bool stresslets = false;  // a stress observer is active
};

struct SolveStats {
  int iterations = 0;      // CG iterations of the last solve (0 for a direct solve)
  double residual = 0.0;   // relative residual reached
  std::int64_t pairs = 0;  // node pairs that entered R_delta
};

class FLDSIM_VISIBLE HydroModel : public Component {
 public:
  // Largest node centre distance whose pairs the model needs (0 if none).
  virtual double pair_range(const System& system) const = 0;
  // Called once before the run; may allocate. Returns one line per skipped piece of work for
  // the run log (e.g. "no R_FE:E (no shear)").
  virtual std::vector<std::string> configure(const System& system, const HydroRequest& request) = 0;
  // Build the resistance of the current configuration (node positions must be up to date).
  virtual void assemble(const System& system, const NodePairList& pairs) = 0;
  // F_B = sqrt(2 kT/dt) (A alpha + B beta) with A A^T = R_0 and sum_p B_p B_p^T = R_delta;
  // the normals come from `noise`, addressed by body and node-pair identity. Overwrites FB (6N).
  virtual void brownian_force(const System& system, const NodePairList& pairs, const RandomStream& noise,
                              double dt, double* FB) = 0;
  // Solve R_FU dU = F + R_FE:E_inf for dU = U - U_inf (6N). On entry dU holds the warm start.
  virtual void solve(const System& system, const double* F, double* dU) = 0;
  virtual SolveStats last_solve() const { return {}; }
  // Whether the model computes stresslet_sum. A model that does not cannot run with an observer
  // that needs the stress pieces (`stress`): the core refuses the experiment rather than report a
  // hydrodynamic stress of zero. (API 4.0: every model must say.)
  virtual bool provides_stresslets() const = 0;
  // Sum over bodies of the hydrodynamic stresslet S^H = -(R_SU dU - R_SE:E_inf) (3x3, symmetric),
  // for the velocities of the last solve. Only called when HydroRequest::stresslets was set, which
  // needs provides_stresslets(). There is no zero default: a model that provides no stresslets
  // and is asked anyway throws.
  virtual Eigen::Matrix3d stresslet_sum(const System& system, const NodePairList& pairs, const double* dU) {
    (void)system;
    (void)pairs;
    (void)dU;
    throw Error("hydro: stresslet_sum called on a model that provides no stresslets");
  }
  // State that a later step depends on beyond the configuration (e.g. a preconditioner carried
  // across steps), as doubles: stored in checkpoints and handed back on --resume after
  // configure(), so a resumed run continues bit for bit. restore_state throws fldsim::Error if
  // the state does not fit. A model that keeps no such state keeps the defaults. (API 5.0.)
  virtual std::vector<double> save_state() const { return {}; }
  virtual void restore_state(const std::vector<double>& state) { (void)state; }
};

}  // namespace fldsim
