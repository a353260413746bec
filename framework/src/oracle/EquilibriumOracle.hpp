// The equilibrium Monte Carlo oracle: the exact canonical averages of the potential the force
// plugins implement (their PairEnergy), for any shape, in a cubic periodic box, with block errors.
// The Brownian dynamics of any hydrodynamic model must reproduce them at Pe = 0.
//
//   start        hard-body Monte Carlo packing (geometry::initialise_monte_carlo; overlap-free)
//   equilibrate  Metropolis sweeps with the pair energy; step sizes adapt in the first half
//   sample       every `sample_every` sweeps, into `blocks` equal blocks:
//                g(r) of body centres and of nodes (RadialHistogram), and the pressure by the
//                molecular virial Z = 1 + tr(W_b)/(3 N kT), W_b = sum (X_j - X_i) (x) f_j (PairVirial)
//   contact      node-node g(2a+): quadratic least-squares fit to the node g of the bins in
//                [2a, 2a + 0.1a), per block, evaluated at 2a (all nodes of radius a only); with
//                the hard core also its contact pressure (HardCoreContact, molecular form)
// Why the virial and not a volume perturbation: the pair forces are continuous (the repulsion's
// energy is C1, its force is capped, not singular), so the virial is exact, needs no finite volume
// step (whose bias is O(dV) and whose variance grows with the stiffness of the overlap region), and
// is the same estimator the stress observer applies to a Brownian run. docs/equilibrium-oracle.md.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fldsim/force.hpp"
#include "oracle/BlockStatistics.hpp"
#include "oracle/MetropolisSampler.hpp"
#include "oracle/RadialHistogram.hpp"

namespace fldsim::oracle {

struct OracleOptions {
  std::uint64_t seed = 1;                   // hard-body start and Metropolis chain
  std::int64_t start_sweeps = 0;            // hard-body sweeps of the start (0 = until decorrelated)
  std::int64_t equilibration_sweeps = 500;  // Metropolis sweeps before sampling
  std::int64_t sweeps = 5000;               // sampling sweeps
  std::int64_t sample_every = 5;            // sweeps between samples
  int blocks = 20;                          // sampling is split into this many equal blocks
  double bin_width = 0.02;                  // a
  double r_max = 3.0;                       // a; g(r) covers [0, r_max), r_max <= L/2
  bool node_distribution = true;            // also g(r) of nodes (needed for the contact value)
  double target_acceptance = 0.4;
  AcceptanceRule acceptance = metropolis_acceptance;  // tests swap in a wrong rule
  // Hard core (MetropolisSampler::set_hard_core): no node pair of two bodies overlaps, i.e. the
  // Boltzmann distribution of the laws' energies restricted to configurations without overlaps
  // (the reference for lubricated dynamics: docs/equilibrium-oracle.md, "FLD near contact"). Z is
  // then the virial of the laws' forces only: the hard core's contact term is not in it.
  bool hard_core = false;
};

struct OracleResult {
  RadialHistogram bodies{PairPoints::BodyCentres, 0.02, 3.0};
  RadialHistogram nodes{PairPoints::Nodes, 0.02, 3.0};
  std::vector<double> Z_blocks, Z_node_blocks;  // per block: molecular (body) and node-node virial
  MeanError Z, Z_node;
  double Z_block_ratio = 0.0;  // SE with B/2 blocks over SE with B blocks (plateau check)
  MeanError contact;           // node-node g(2a+); blocks = 0 when not defined
  // With hard_core (nodes of one radius): the hard core's contact term f(0+)/(3N) extrapolated from
  // outside the laws' range (HardCoreContact.hpp), times exp(-U(0)/kT) with U(0) the laws' node-pair
  // energy at contact, and Z_hard_core = Z + Z_contact per block: the restricted system's pressure.
  std::vector<double> Z_contact_blocks;
  MeanError Z_contact, Z_hard_core;
  double boltzmann_at_contact = 1.0;  // exp(-U(0)/kT)
  double contact_distance = 0.0;      // 2a
  double energy_per_body = 0.0;       // <U>/(N kT)
  double acceptance_translation = 0.0, acceptance_rotation = 0.0;
  double translation_step = 0.0, rotation_step = 0.0;
  std::int64_t samples = 0, sweeps = 0;
  double seconds = 0.0;
};

// Samples the System (shape, N, box and physics set; kT > 0) with the energies of `laws`, every
// one of which must declare a PairEnergy (throws fldsim::Error naming the one that does not).
// Overwrites the System's configuration.
OracleResult run_oracle(System& s, const std::vector<std::shared_ptr<ForceLaw>>& laws,
                        const OracleOptions& opt, const std::function<void(const std::string&)>& log = {});

// Least-squares quadratic through the (centre, g) of the bins whose lower edge lies in
// [r0, r0 + span), evaluated at r0; per block.
std::vector<double> contact_extrapolation(const RadialHistogram& h, double r0, double span);

}  // namespace fldsim::oracle
