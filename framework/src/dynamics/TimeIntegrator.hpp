// Time integrators for overdamped rigid bodies. A step is an *attempt* over a piece of the
// Brownian path (NoiseInterval) that the caller then accepts or rejects (StepLoop decides, from
// the attempt's embedded error estimate and the stability guard):
//  - EulerMaruyama: x += U dt with Brownian forces. With a configuration-dependent resistance
//    the Ito SDE needs the drift kT div M (M = R_FU^-1); the `midpoint` drift scheme gets it
//    without derivatives: evaluate U at x, move half a step, re-evaluate at the midpoint with the
//    *same* Brownian force, and take the full step with the midpoint velocity. Then
//    E[U_mid] = M F + kT div M + O(dt) (Fixman 1978; Banchio & Brady, J. Chem. Phys. 118, 10323
//    (2003); the original FLD code does the same). Under shear the half step moves every body
//    (and so every image) with the imposed flow too, since U includes U_inf.
//    Embedded estimate: the Euler step x + dt U(x) with the same noise is the lower-order partner,
//    so the local error is estimated by dt |U_mid - U(x)| (an embedded Heun-Euler pair in the
//    sense of Sammueller & Schmidt, J. Chem. Phys. 155, 134107 (2021)); no extra solve.
//  - RungeKutta3: the paper's explicit third-order scheme (Kumar & Higdon integrate every run,
//    Brownian ones too, with it). Kutta's tableau: k1 = f(x), k2 = f(x + dt/2 k1),
//    k3 = f(x - dt k1 + 2 dt k2), x += dt/6 (k1 + 4 k2 + k3). Orientations take the same tableau
//    on the rotation vector (Runge-Kutta-Munthe-Kaas: stage angular velocities corrected by
//    -1/2 Theta x omega), so they are third-order too. Embedded estimate (kT = 0): the
//    second-order midpoint rule x + dt k2 shares k1 and k2, so the error of the lower-order
//    result is dt/6 |k1 - 2 k2 + k3| (local O(dt^3)).
//    With Brownian motion F_B is drawn once at x and frozen over the three stages, as the paper
//    does. Stage i sits at x + c_i dt M F_B + O(dt), so E[M(x_i) F_B] = M F + 2 c_i kT div M
//    + O(dt^1/2) (<F_B F_B^T> = 2kT R/dt), and the weights give the drift sum_i b_i 2 c_i kT div M
//    = kT div M since sum_i b_i c_i = 1/2 for any second-order tableau (4/6 * 1/2 + 1/6 * 1):
//    the thermal drift is exact to leading order, as in the midpoint scheme, and the scheme is
//    weakly first order. It has no error estimate for the noise, so it runs fixed steps
//    (the guard still halves a step it rejects, on the bridge).
// An estimate is per body, the local displacement error of its farthest surface point
// (translation plus bounding radius times rotation), and the attempt reports the largest.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "dynamics/BodyMotion.hpp"
#include "dynamics/BrownianBridge.hpp"
#include "dynamics/VelocityEvaluator.hpp"

namespace fldsim {

enum class StressStage { Start, Final };

// What one attempt found.
struct StepAttempt {
  double error = 0.0;  // embedded estimate: largest local error of a body surface point, a (0: none)
  double min_gap = std::numeric_limits<double>::infinity();  // smallest node gap at the end, a
  bool finite = true;  // velocities and positions finite (if not, the end state is meaningless)
};

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  // Try one step over `interval` from the current state of s. Afterwards s holds the candidate
  // end state (unwrapped) and step_velocity() the velocities used; call accept() or reject().
  virtual StepAttempt attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                              bool want_virial) = 0;
  // Keep the candidate: displacement records, centres wrapped into the box.
  void accept(System& s);
  // Back to the state before the attempt, solver warm start included.
  void reject(System& s, VelocityEvaluator& ev);
  // One plain step of dt, numbered s.step() (the fixed-step noise), always accepted; the step
  // counter advances. For tests and benchmarks; runs go through StepLoop.
  void step(System& s, VelocityEvaluator& ev, double dt, bool want_virial);

  virtual std::string describe() const = 0;
  // Order of the embedded estimate (its local error ~ dt^order); 0 if there is none.
  virtual double error_order() const = 0;
  // Velocity actually used for the step (6N total / relative), for observers.
  const double* step_velocity() const { return U_.data(); }
  const double* step_relative_velocity() const { return dU_.data(); }
  // Mean over nodes of |dt (dv + dw x r)|^2 + (2/3) (gammadot dt a_node)^2 for the last attempt,
  // a^2: each node's displacement relative to the imposed flow at its body's centre (dv, dw: the
  // velocity relative to U_inf; r: the node's offset at the end of the step), plus what the flow
  // itself moves a touching neighbour relative to it, per node (the relative displacement
  // gammadot dt r_y of nodes 2 a_node apart has mean square (gammadot dt)^2 (2a)^2 / 3 over
  // directions, shared by the two nodes). What the displacement bound controls (StepControl).
  double mean_square_node_step(const System& s) const;
  // Called on attempts with want_virial (StressSampler): Start after the solve at the start of
  // the step, Final after the midpoint solve (Euler-Maruyama with midpoint drift only). The hook
  // may solve again: the integrator has copied what it needs, and the hook restores the warm start.
  using StageHook = std::function<void(StressStage, const System&, VelocityEvaluator&)>;
  void set_stress_stage(StageHook hook) { stress_stage_ = std::move(hook); }

 protected:
  explicit TimeIntegrator(std::size_t bodies);
  void at_stress_stage(StressStage stage, const System& s, VelocityEvaluator& ev, bool want_virial) const {
    if (want_virial && stress_stage_) stress_stage_(stage, s, ev);
  }
  // Save the start state (and warm start) of an attempt.
  void begin_attempt(const System& s, VelocityEvaluator& ev, double dt);
  // The step's velocities (U_, dU_) from the evaluator's last solve; false if not finite.
  bool take_velocity(const VelocityEvaluator& ev);
  // After the final move: finiteness, then the smallest gap (refreshing the pair list).
  void finish_attempt(System& s, VelocityEvaluator& ev, StepAttempt& a) const;
  // Largest over bodies of h |a - b| for a surface point (translation + radius x rotation);
  // b = nullptr stands for zero.
  double largest_error(const System& s, const double* a, const double* b, double h) const;
  static bool all_finite(const double* v, std::size_t n);

  BodySnapshot base_;
  std::vector<double> U_, dU_;
  double dt_ = 0.0;

 private:
  StageHook stress_stage_;
  std::vector<double> warm_;
};

enum class DriftScheme { None, Midpoint };

class EulerMaruyama : public TimeIntegrator {
 public:
  EulerMaruyama(std::uint64_t seed, bool brownian, DriftScheme drift, std::size_t bodies,
                RejectedNoise rejected = RejectedNoise::Bridge);
  StepAttempt attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                      bool want_virial) override;
  std::string describe() const override;
  double error_order() const override { return brownian_ && drift_ == DriftScheme::Midpoint ? 1.5 : 0.0; }

 private:
  std::uint64_t seed_;
  bool brownian_;
  DriftScheme drift_;
  BrownianBridge bridge_;
  std::vector<double> U0_;
};

// Leimkuhler-Matthews: Euler-Maruyama whose Brownian force is the mean of this step's draw and
// the next step's, both at the start of the step:
//   x_{n+1} = x_n + dt M (F_P(x_n) + (F_B[xi_n] + F_B[xi_{n+1}]) / 2),
// the Brownian-dynamics limit of the BAOAB Langevin scheme. For a constant mobility (additive
// noise) its equilibrium distribution is exact to O(dt^2) where Euler-Maruyama's is O(dt)
// (Leimkuhler & Matthews, Appl. Math. Res. Express 2013, 34; arXiv:1102.4139), at one solve
// per step and no midpoint stage. Where the noise's factor B (B B^T = M) depends on the
// configuration, xi_{n+1}'s share of step n moves x_{n+1}, where B is evaluated for step n+1:
// a drift (kT/2) sum_k (d_k B) B_k e_k that does not vanish with dt. It does vanish for a
// pair-free model of rigid bodies without translation-rotation coupling: then B is block-diagonal
// and depends only on the orientation, B = Q B_body, so only rotations k contribute, each
// ([e_k]x M_rr)_{i k}, and sum_k eps_{i k m} (M_rr)_{m k} = 0 for the symmetric M_rr (the thermal
// drift kT div M vanishes likewise). So the run configuration allows it where
// averaged_noise_unbiased() holds: spheres, homonuclear dicolloids, fused dumbbells with
// free_draining. Fixed steps only; xi_{n+1} is the next step's own key, so a resumed run draws the
// same numbers. A step the guard splits takes its pieces as plain Euler-Maruyama on the bridge
// (no memory across the split).
class LeimkuhlerMatthews : public TimeIntegrator {
 public:
  LeimkuhlerMatthews(std::uint64_t seed, std::size_t bodies);
  StepAttempt attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                      bool want_virial) override;
  std::string describe() const override;
  double error_order() const override { return 0.0; }

 private:
  std::uint64_t seed_;
  BrownianBridge bridge_;
};

// True where LeimkuhlerMatthews is allowed: a hydro model without pair terms (pair_range 0) and
// bodies whose radius-weighted node centre is the body centre, so that their isolated-node drags
// do not couple translation and rotation (see above).
bool averaged_noise_unbiased(const HydroModel& hydro, const System& s);
// Empty where it holds; otherwise why run.integrator: leimkuhler_matthews is refused (one line, for
// the run check and the Simulation alike).
std::string leimkuhler_matthews_refusal(const HydroModel& hydro, const System& s);

class RungeKutta3 : public TimeIntegrator {
 public:
  // Deterministic (kT = 0).
  explicit RungeKutta3(std::size_t bodies);
  // With Brownian forces of `seed`, frozen over the stages (the paper's scheme).
  RungeKutta3(std::uint64_t seed, std::size_t bodies, RejectedNoise rejected = RejectedNoise::Bridge);
  StepAttempt attempt(System& s, VelocityEvaluator& ev, const NoiseInterval& interval,
                      bool want_virial) override;
  std::string describe() const override;
  double error_order() const override { return brownian_ ? 0.0 : 3.0; }

 private:
  RungeKutta3(std::size_t bodies, bool brownian, std::uint64_t seed, RejectedNoise rejected);
  std::uint64_t seed_ = 0;
  bool brownian_ = false;
  BrownianBridge bridge_;
  std::vector<double> k1_, k2_, k3_, r1_, r2_, r3_, e_;
};

}  // namespace fldsim
