// Hard-body Monte Carlo for initial configurations of any shape made of sphere nodes: bodies
// overlap when any two nodes of different bodies are closer than the sum of their radii.
//
// Strategy (initialise_monte_carlo): bodies start on a simple cubic lattice whose spacing exceeds
// twice the bounding radius (so any orientations are overlap-free), in a box enlarged to
// volume fraction min(phi, 0.3) or larger if the lattice needs it; orientations are uniform
// random. The box is then compressed towards the requested edge with an MC sweep before each
// compression step: a step scales the centres (orientations fixed) by a factor f never below the
// target and never more than 2 % per step. Scaling f brings a close node pair into contact at a
// factor computed exactly from the quadratic |f R + dr|^2 = (r_a + r_b)^2 (R: centre separation,
// dr: node offsets). A step goes 90 % of the way from 1 to the contact factor of the pair that
// touches (K+1)-th, so at most K pairs overlap after it (K = compression_overlaps x N, at least
// one); sweeps then remove those overlaps before the next step, accepting a move only if it does
// not deepen the moved body's summed overlap (so the total overlap never grows) and, for a body
// without overlap, only if it stays without (the hard-body rule). With K = 0 (the rule until
// December 2026) the single closest pair limits every step, and the number of compression sweeps
// grew like N at high density: 8000 spheres to phi 0.5 took more than ten minutes, 10 000 sweeps
// for 0.30 -> 0.35 alone. The compression only has to reach an overlap-free state at the target;
// what is sampled is decided by the hard-body sweeps after it. Once at the target without
// overlaps, sweeps continue (at least 100) until the mean-square displacement since the lattice
// exceeds decorrelation_msd and <P2(n(t).n(0))> < decorrelation_p2 (the lattice forgotten) and the
// same two since the target was reached pass relaxation_msd and relaxation_p2 (the compression
// forgotten), or for `sweeps` sweeps in total at the target. Why the second
// clock: a compression leaves more close pairs than equilibrium, and the displacement during it
// already satisfies the first clock; with that clock alone, fused dumbbells (c/a 1) at phi 0.5,
// N 1000, started after 100 sweeps at the target with the body g(r) 16 % high at 2.00-2.05 a and
// 3 % low at 2.7-3.0 a against the hard-body equilibrium (docs/equilibrium-oracle.md, "Starts").
//
// Moves: one sweep visits bodies 0..N-1 in order and tries a uniform displacement in
// [-dx, dx]^3 or (anisotropic shapes, probability 1/2) a rotation by an angle uniform in
// [-dtheta, dtheta] about a uniform random axis; both proposals are symmetric, so accepting every
// overlap-free move samples the equilibrium hard-body ensemble. Step sizes adapt towards the
// target acceptance during compression and for the first 20 sweeps at the target, then stay
// fixed. Random numbers come from RandomStream(seed, MonteCarlo, sweep), keyed by body, so the
// result is a pure function of the seed. Overlaps are checked with a node cell list (O(1) per
// move).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fldsim/system.hpp"
#include "geometry/LeesEdwardsCellGrid.hpp"

namespace fldsim::geometry {

struct MonteCarloOptions {
  std::int64_t sweeps = 0;  // 0 = automatic: until decorrelated
  double target_acceptance = 0.35;
  std::uint64_t seed = 1;
  double decorrelation_msd = 4.0;  // a^2, mean-square displacement since the lattice
  double decorrelation_p2 = 0.05;  // <P2(n(t).n(0))> since the lattice must fall below this
  double relaxation_msd = 4.0;     // a^2, mean-square displacement since the target was reached
  double relaxation_p2 = 0.05;     // <P2(n(t).n(0))> since the target was reached
  // Compression: throw beyond this many sweeps; at the target: stop there, undecorrelated.
  std::int64_t max_sweeps = 1000000;
  // Pairs allowed to overlap after a compression step, per body (K = this x N, at least 1); the
  // sweeps remove them before the next step. 0: every step stops short of the first contact.
  double compression_overlaps = 0.05;
  // Asked after every sweep: a non-empty answer (what stopped it, e.g. "SIGINT") ends the start
  // with an Error saying so, so that a signal during a long start is obeyed at once.
  std::function<std::string()> stop;
};

struct MonteCarloReport {
  std::int64_t sweeps;
  double acceptance_translation, acceptance_rotation;
  double final_volume_fraction;
  std::int64_t overlaps;
  double max_displacement;
  // Whether the start ran its course: the automatic rule was met, or a fixed `sweeps` were all
  // done at the target; false when max_sweeps ended the sweeps at the target first (the
  // configuration is still overlap-free).
  bool decorrelated = true;
  std::int64_t sweeps_at_target = 0;  // sweeps after the compression (those a fixed `sweeps` counts)
  double msd_since_target = 0.0, p2_since_target = 0.0;  // a^2; 0 for isotropic shapes
};

// One hard-body MC chain on a System (which must be overlap-free). Keeps positions wrapped in
// the box and writes them (and node positions) back to the System after every sweep.
class HardBodyMonteCarlo {
 public:
  HardBodyMonteCarlo(System& s, std::uint64_t seed);

  // One sweep; returns the number of accepted (overlap-free) moves.
  std::int64_t sweep();
  // Compress towards `edge` (< current edge) by at most the factor (1 - max_step), creating at
  // most `allowed_overlaps` overlapping node pairs (which the next sweeps remove); returns true
  // once the box edge equals `edge`.
  bool compress_towards(double edge, double max_step = 0.02, std::size_t allowed_overlaps = 0);
  // Node pairs overlapping now (after a compression with allowed overlaps, until sweeps remove them).
  std::int64_t overlapping_pairs() const { return overlapping_pairs_; }
  // Adjust step sizes towards the acceptance `target` using the last sweep's acceptance.
  void adapt_steps(double target);

  double translation_step() const { return dx_; }
  double rotation_step() const { return dtheta_; }
  std::int64_t sweeps_done() const { return sweep_count_; }
  // Acceptance over the sweeps since the last reset_counters().
  double acceptance_translation() const;
  double acceptance_rotation() const;
  void reset_counters();
  // Mean-square displacement of the centres since construction (accumulated accepted moves).
  double mean_square_displacement() const;
  // <P2(n(t).n(0))> over bodies, n(0) the directors at construction.
  double orientation_p2() const;
  // The same two measured from the configuration at the last mark() (construction if none).
  void mark();
  double mean_square_displacement_since_mark() const;
  double orientation_p2_since_mark() const;
  // Node pairs of different bodies that overlap (0 for a valid configuration).
  std::int64_t count_overlaps() const;

 private:
  void rebuild_cells();
  // Mean over bodies of |displacement - origin|^2 (origin null: since construction), of P2(n . n_ref).
  double mean_square_displacement_from(const std::vector<Vec3>* origin) const;
  double orientation_p2_against(const std::vector<Vec3>& directors) const;
  // Overlaps of a node of `body` at x with nodes of other bodies: how many, and the summed depth
  // sum(r_a + r_b - d); stops at the first when `first_only`.
  struct Overlap {
    int count = 0;
    double depth = 0.0;
  };
  Overlap node_overlaps(std::size_t body, const Vec3& x, double radius, bool first_only) const;
  // Summed overlap depth of `body` with its nodes at x[0..m), or some value above `bound` once
  // the sum exceeds it (bound 0: stops at the first overlap).
  double body_overlap_depth(std::size_t body, const Vec3* x, double bound) const;
  void move_node(std::size_t node, const Vec3& x);
  void sync_system();

  System& s_;
  std::uint64_t seed_;
  std::size_t m_;
  double contact_ = 0.0;  // largest r_a + r_b
  double dx_ = 0.1, dtheta_ = 0.1;
  std::int64_t overlapping_pairs_ = 0;
  std::int64_t sweep_count_ = 0;
  std::int64_t tried_t_ = 0, accepted_t_ = 0, tried_r_ = 0, accepted_r_ = 0;
  std::int64_t last_tried_t_ = 0, last_accepted_t_ = 0, last_tried_r_ = 0, last_accepted_r_ = 0;
  std::vector<Vec3> node_x_;      // wrapped world positions
  std::vector<double> touching_;  // compression: contact factors of the pairs that can touch
  std::vector<Vec3> displacement_, director0_;
  std::vector<Vec3> displacement_mark_, director_mark_;
  LeesEdwardsCellGrid grid_;
  bool use_cells_ = false;
  std::vector<int> node_cell_;
  std::vector<std::vector<int>> cells_;
};

MonteCarloReport initialise_monte_carlo(System& s, const MonteCarloOptions& opt,
                                        const std::function<void(const std::string&)>& log = {});

// Hand-built scenes: positions and orientations given; throws fldsim::Error naming the first two
// bodies that overlap.
void place_explicit(System& s, const std::vector<Vec3>& positions, const std::vector<Quat>& q);
// Same, orientations given as world-frame directors (the rotation taking the body director to n).
void place_explicit(System& s, const std::vector<Vec3>& positions, const std::vector<Vec3>& directors);

}  // namespace fldsim::geometry
