// The Brownian side of the equilibrium tests: a Pe = 0 run of a scene (shape, N, phi, hydro model,
// repulsion) through the step users run (StepLoop with the real `stress` observer), sampled into
// the same blocked g(r) as the Monte Carlo oracle, and the oracle of the same scene.
//   start       hard-body Monte Carlo (as `init: monte_carlo`), then `equilibrate` a^2/D0 unsampled
//   sampling    every `sample_every` steps for `duration` a^2/D0, in `blocks` equal blocks:
//               body-centre g(r) in bins of `bin_width` (0.01 a: rebinned to 0.02 a for the
//               comparison, 0.05 a for the contact shell), and the molecular-virial Z of each
//               sampled configuration (oracle::PairVirial, as the oracle measures it)
//   pressure    the stress observer's interparticle Pi -> Z_observer = 1 + Pi/(n kT), its own
//               Flyvbjerg-Petersen SE; and its Z_particle = 1 + Pi/(n kT) with every part
//               (Brownian stress from the random-difference probe, as run.brownian_stress's
//               default, or from the midpoint stage)
#pragma once

#include <cstdint>
#include <string>

#include "dynamics/TimeIntegrator.hpp"
#include "oracle/EquilibriumOracle.hpp"

namespace fldsim::testing {

struct EquilibriumScene {
  std::string shape = "sphere", shape_params = "{}";
  std::string hydro = "fld", hydro_params = "{}";
  std::string force_params = "{}";  // of the repulsion
  std::size_t count = 125;
  double phi = 0.3;
  std::string describe() const;
};

// Free-draining spheres, N = 125, phi = 0.3 with the default repulsion: the stiff case of the
// step-size tests (AdaptiveEquilibriumTest, LeimkuhlerMatthewsEquilibriumTest).
EquilibriumScene free_draining_spheres();

struct BrownianOptions {
  double dt = 1e-3;  // a^2/D0
  DriftScheme drift = DriftScheme::Midpoint;
  bool rk3 = false;  // the paper's RK3 with frozen Brownian forces instead of Euler-Maruyama (fixed dt)
  bool leimkuhler_matthews = false;  // LeimkuhlerMatthews instead (fixed dt; free draining)
  double equilibrate = 1.0;          // a^2/D0, not sampled
  double duration = 10.0;            // a^2/D0, sampled
  std::int64_t sample_every = 10;    // steps
  int blocks = 20;
  std::uint64_t seed = 1;  // start and noise
  double bin_width = 0.01, r_max = 3.0;
  std::int64_t stress_every = 0;      // steps between stress-observer samples; 0 = no observer
  bool probe_brownian_stress = true;  // BrownianStressProbe; false = the midpoint estimate
  // Step control (docs/time_steps.md): with `adaptive`, dt is dt_max (the frame; sample_every
  // and stress_every count frames) and steps follow the error estimate.
  bool adaptive = false;
  double tolerance = 1e-3;  // a
  double reject_at = 10.0;
  // run.displacement (a; 0 = none); with error_control false it is the only rule (run.displacement
  // without run.tolerance).
  double displacement = 0.0;
  // run.gap_step (a; 0 = none): the bound on the rms gap change of pairs nearer than gap_range (with
  // displacement too, the shorter of the two).
  double gap_step = 0.0, gap_range = 0.01;
  bool error_control = true;
  RejectedNoise rejected = RejectedNoise::Bridge;  // Redraw: the broken variant, for tests
  // The step loop's stability guard (run.max_overlap): a step leaving a deeper node overlap is
  // rejected and retried shorter, which would bias a potential whose equilibrium has such overlaps.
  double max_overlap = 0.1;  // a
  // The hard core's contact term of the sampled configurations (oracle/HardCoreContact: f(0+)/(3N),
  // without exp(-U(0)/kT)), to tell a run that samples the wrong contact density from a stress
  // estimator that misreads the right one. Nodes of one radius only.
  bool contact_term = false;
  // The Monte Carlo start's rule (geometry/HardBodyMonteCarlo.hpp): false = the lattice clock
  // only, the rule until December 2026 whose dense starts had not forgotten the compression (the
  // broken variant for the validation's fused_phi05_lattice_start).
  bool start_forgets_compression = true;
};

struct BrownianEquilibrium {
  oracle::RadialHistogram g{oracle::PairPoints::BodyCentres, 0.01, 3.0};
  std::vector<double> Z_blocks;  // configurational molecular virial
  oracle::MeanError Z;
  double Z_observer = 0.0, Z_observer_se = 0.0;  // from the stress observer (if stress_every > 0)
  std::vector<double> Z_observer_blocks;         // replicas: each run's observer Z (one block each)
  double Z_particle = 0.0, Z_particle_se = 0.0;  // observer Z with every part (if it wrote one)
  bool has_Z_particle = false;                   // the observer wrote Z_particle (it had a Brownian stress)
  std::vector<double> Z_particle_blocks;         // replicas: each run's Z_particle
  std::vector<double> Z_contact_blocks;          // with contact_term: per block (replicas: per run)
  oracle::MeanError Z_contact;
  std::int64_t steps = 0;      // frames (= steps at a fixed dt)
  std::int64_t accepted = 0;   // time steps taken
  std::int64_t rejected = 0;   // step attempts the loop rejected (0 for an undisturbed fixed-step run)
  double node_step_sum = 0.0;  // sum over accepted steps of their mean square node step, a^2
  double gap_step_sum = 0.0;   // with gap_step: sum of the near pairs' squared gap changes, a^2
  double near_pairs = 0.0;     // and how many pair-steps
  double min_gap = 0.0;        // smallest node surface gap seen at the samples
  double seconds = 0.0;
};

BrownianEquilibrium run_brownian(const EquilibriumScene& scene, const BrownianOptions& opt);
// Independent runs as the blocks: run k = 0..runs-1 has seed opt.seed + k (its own hard-body
// Monte Carlo start and noise), relaxes for `equilibrate`, is sampled for `duration` into one
// block. g, Z and the counters are pooled (steps, accepted, rejected, seconds summed; min_gap the
// smallest). With stress_every > 0 each run's stress-observer Z is one block (Z_observer_blocks):
// Z_observer and Z_observer_se are the mean and SE of those run means (sd / sqrt(runs)).
BrownianEquilibrium run_brownian_replicas(const EquilibriumScene& scene, BrownianOptions opt, int runs);
// The oracle settings the Brownian comparisons use: 0.01 a bins, 20000 sweeps in 40 blocks, body
// g(r) only; `hard_core` for lubricated dynamics (docs/equilibrium-oracle.md, "FLD near contact").
oracle::OracleOptions comparison_oracle_options(bool hard_core);

oracle::OracleResult run_scene_oracle(const EquilibriumScene& scene, const oracle::OracleOptions& opt);
// The hard-core oracle's contact term as BrownianOptions::contact_term measures it on a run's
// configurations: f(0+)/(3N) without the factor exp(-U(0)/kT) that the oracle's Z_contact carries.
oracle::MeanError contact_term_reference(const oracle::OracleResult& mc);

}  // namespace fldsim::testing
