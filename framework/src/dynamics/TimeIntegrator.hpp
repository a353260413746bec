// Time integrators for overdamped rigid bodies.
//  - EulerMaruyama: x += U dt with Brownian forces. With a configuration-dependent resistance
//    the Ito SDE needs the drift kT div M (M = R_FU^-1); the `midpoint` drift scheme gets it
//    without derivatives: evaluate U at x, move half a step, re-evaluate at the midpoint with the
//    *same* Brownian force, and take the full step with the midpoint velocity. Then
//    E[U_mid] = M F + kT div M + O(dt) (Fixman 1978; Banchio & Brady, J. Chem. Phys. 118, 10323
//    (2003); the original FLD code does the same). Under shear the half step moves every body
//    (and so every image) with the imposed flow too, since U includes U_inf.
//  - RungeKutta3: the paper's explicit third-order scheme for deterministic (kT = 0) runs;
//    Kutta's tableau: k1 = f(x), k2 = f(x + dt/2 k1), k3 = f(x - dt k1 + 2 dt k2),
//    x += dt/6 (k1 + 4 k2 + k3). Orientations take the same tableau on the rotation vector
//    (Runge-Kutta-Munthe-Kaas: stage angular velocities corrected by -1/2 Theta x omega), so they
//    are third-order too.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dynamics/BodyMotion.hpp"
#include "dynamics/VelocityEvaluator.hpp"

namespace fldsim {

enum class StressStage { Start, Final };

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  // Advance s by dt; afterwards evaluator.velocity() holds the velocities used for the step.
  virtual void step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) = 0;
  virtual std::string describe() const = 0;
  // Velocity actually used for the step (6N total / relative), for observers.
  virtual const double* step_velocity() const = 0;
  virtual const double* step_relative_velocity() const = 0;
  // Called on steps with want_virial (StressSampler): Start after the solve at the start of the
  // step, Final after the midpoint solve (Euler-Maruyama with midpoint drift only). The hook may
  // solve again: the integrator has copied what it needs, and the hook restores the warm start.
  using StageHook = std::function<void(StressStage, const System&, VelocityEvaluator&)>;
  void set_stress_stage(StageHook hook) { stress_stage_ = std::move(hook); }

 protected:
  void at_stress_stage(StressStage stage, const System& s, VelocityEvaluator& ev, bool want_virial) const {
    if (want_virial && stress_stage_) stress_stage_(stage, s, ev);
  }

 private:
  StageHook stress_stage_;
};

enum class DriftScheme { None, Midpoint };

class EulerMaruyama : public TimeIntegrator {
 public:
  EulerMaruyama(std::uint64_t seed, bool brownian, DriftScheme drift, std::size_t bodies);
  void step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) override;
  std::string describe() const override;
  const double* step_velocity() const override { return U_.data(); }
  const double* step_relative_velocity() const override { return dU_.data(); }

 private:
  std::uint64_t seed_;
  bool brownian_;
  DriftScheme drift_;
  BodySnapshot base_;
  std::vector<double> U_, dU_;
};

class RungeKutta3 : public TimeIntegrator {
 public:
  explicit RungeKutta3(std::size_t bodies);
  void step(System& s, VelocityEvaluator& ev, double dt, bool want_virial) override;
  std::string describe() const override { return "explicit third-order Runge-Kutta (Kutta), deterministic"; }
  const double* step_velocity() const override { return U_.data(); }
  const double* step_relative_velocity() const override { return dU_.data(); }

 private:
  BodySnapshot base_;
  std::vector<double> k1_, k2_, k3_, r1_, r2_, r3_, U_, dU_;
};

}  // namespace fldsim
