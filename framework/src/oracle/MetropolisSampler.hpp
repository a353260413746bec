// Metropolis Monte Carlo of rigid bodies with the pair energy the force plugins declare
// (fldsim::PairEnergy): the canonical distribution exp(-U/kT) over centres in the periodic box
// (no shear: Lees-Edwards offset 0) and orientations (uniform measure on rotations).
//
// A sweep visits bodies 0..N-1 in order and proposes for each a uniform displacement in
// [-dx, dx]^3 or (anisotropic shapes, probability 1/2) a rotation q' = exp(theta e) q by an angle
// theta uniform in [-dtheta, dtheta] about a uniform random axis e. Both proposals are symmetric
// (the reverse move has the same density; the rotation kernel depends only on q' q^-1 and is
// invariant under inversion), so accepting with probability min(1, exp(-dU/kT)) (Metropolis et al.,
// J. Chem. Phys. 21, 1087 (1953)) satisfies detailed balance. dU sums the pair energies of the moved
// body's nodes with the nodes of all other bodies within the largest energy range (cell list), old
// and new. Step sizes adapt only when adapt_steps() is called (equilibration), never while sampling.
// Random numbers: RandomStream(seed, MonteCarlo, sweep, stage 2), keyed by body, so a chain is a pure
// function of its seed and start.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fldsim/force.hpp"
#include "geometry/LeesEdwardsCellGrid.hpp"

namespace fldsim::oracle {

// Probability of accepting a move that changes U/kT by beta_dU. Tests replace the Metropolis rule
// by a wrong one to show the oracle's validation catches it.
using AcceptanceRule = double (*)(double beta_dU);
double metropolis_acceptance(double beta_dU);

class MetropolisSampler {
 public:
  // energies: the laws' pair energies (non-null) with range = their largest range(); kT > 0.
  MetropolisSampler(System& s, std::vector<const PairEnergy*> energies, double range, std::uint64_t seed,
                    AcceptanceRule rule = metropolis_acceptance);

  // One sweep (N trial moves); returns the number accepted. Writes the state back to the System.
  std::int64_t sweep();
  // Scale the step sizes towards the acceptance `target` from the last sweep (equilibration only).
  void adapt_steps(double target);

  double translation_step() const { return dx_; }
  double rotation_step() const { return dtheta_; }
  void set_steps(double dx, double dtheta) {
    dx_ = dx;
    dtheta_ = dtheta;
  }
  std::int64_t sweeps_done() const { return sweep_count_; }
  double acceptance_translation() const { return tried_t_ ? double(accepted_t_) / double(tried_t_) : 0.0; }
  double acceptance_rotation() const { return tried_r_ ? double(accepted_r_) / double(tried_r_) : 0.0; }
  void reset_counters() { tried_t_ = accepted_t_ = tried_r_ = accepted_r_ = 0; }
  // U/kT of the whole configuration (every node pair once), for tests and logs.
  double total_energy() const;
  // Hard core: a node pair of two bodies closer than the sum of the node radii has U = infinity
  // (the move is rejected), on top of the laws' energies.
  void set_hard_core(bool on) { hard_core_ = on; }

 private:
  // U/kT of body `body`'s nodes at positions x[0..m) with the nodes of every other body.
  double body_energy(std::size_t body, const Vec3* x) const;
  double pair_energy(std::size_t body, std::size_t k, const Vec3& xk, std::size_t q) const;
  void rebuild_cells();
  void move_node(std::size_t node, const Vec3& x);

  System& s_;
  std::vector<const PairEnergy*> energies_;
  double range_, beta_;
  std::uint64_t seed_;
  AcceptanceRule rule_;
  std::size_t m_;
  bool hard_core_ = false;
  double dx_ = 0.1, dtheta_ = 0.1;
  std::int64_t sweep_count_ = 0;
  std::int64_t tried_t_ = 0, accepted_t_ = 0, tried_r_ = 0, accepted_r_ = 0;
  std::int64_t last_tried_t_ = 0, last_accepted_t_ = 0, last_tried_r_ = 0, last_accepted_r_ = 0;
  std::vector<Vec3> node_x_;  // wrapped world node positions
  geometry::LeesEdwardsCellGrid grid_;
  bool use_cells_ = false;
  std::vector<int> node_cell_;
  std::vector<std::vector<int>> cells_;
  // Neighbour cells of every cell (the box has no offset, so they never change).
  std::vector<std::array<int, geometry::LeesEdwardsCellGrid::max_neighbour_cells>> neighbours_;
  std::vector<int> neighbour_count_;
  std::vector<Vec3> old_x_, trial_x_;
};

}  // namespace fldsim::oracle
