// Verlet list of node pairs of different bodies under Lees–Edwards boundary conditions, built
// with a LeesEdwardsCellGrid (all pairs when fewer than 3 cells fit per side).
//
// Validity: a listed pair set stays complete for distances < range as long as no pair distance
// can have shrunk by more than skin since the rebuild. Node displacements d are measured as the
// minimum image under the current box (so wrapping through a y face with its x shift is not
// mistaken for motion) less the affine shear displacement dgamma y e_x; a pair's separation then
// changes by at most |a_i| + |a_j| + |dgamma| (range + |a_i| + |a_j|) (derivation at
// needs_rebuild), and the list is rebuilt when that bound, for the two largest |a|, exceeds skin.
#pragma once

#include <cstdint>
#include <vector>

#include "fldsim/neighbours.hpp"
#include "fldsim/system.hpp"
#include "geometry/LeesEdwardsCellGrid.hpp"

namespace fldsim::geometry {

class CellNeighbourList {
 public:
  // range: node centre distance that must be covered; skin: extra padding. Lists all node pairs
  // of different bodies with distance < range + skin at the last rebuild.
  void configure(double range, double skin);
  // run.skin: auto. At every rebuild after the first the skin is chosen anew from the number k of
  // updates the list lasted: skin' = skin sqrt(target_updates / k), at most doubled or halved at
  // once (also when a list has lasted four targets: displacements slowed down, and a thinner shell
  // is cheaper to refresh), within [min_skin, max_skin], and never so large that fewer than three cells fit
  // per side (the cell grid would fall back to all pairs) or that range + skin reaches half the box edge.
  // Brownian displacements grow as the square root of time, so k then settles near the target:
  // few rebuilds where steps are long against the skin (dicolloids at Pe <= 1 with dt ~ 1e-3 a^2/D0
  // rebuilt at almost every step with 0.3 a), a thin skin (fewer listed pairs to refresh) where
  // they are short. The listed pairs within range, and so every result, do not depend on the skin
  // (CellNeighbourListTest, SimulationTest).
  void adapt_skin(double min_skin, double max_skin, int target_updates);
  double skin() const { return skin_; }
  // Call after System::update_nodes(). Rebuilds when needed (see above), otherwise refreshes r and
  // distance of the listed pairs whose nodes moved since the last update (all of them when the
  // strain changed). Returns true if it rebuilt. No allocation when not rebuilding.
  bool update(const System& s);
  const NodePairList& pairs() const { return list_; }
  std::int64_t rebuilds() const { return rebuilds_; }
  // Smallest surface gap (distance - r_a - r_b) over listed pairs (+inf if none).
  double min_gap(const System& s) const;

 private:
  bool needs_rebuild(const System& s) const;
  void rebuild(const System& s);
  void refresh(const System& s);
  void refresh_moved(const System& s);
  void remember_positions(const System& s);
  void add_pair(const System& s, std::size_t p, std::size_t q, const Vec3& r);

  void choose_skin(const System& s);

  double range_ = 0.0, skin_ = 0.0;
  bool built_ = false;
  // Adaptive skin (adapt_skin); off when target_updates_ is 0.
  double min_skin_ = 0.0, max_skin_ = 0.0;
  int target_updates_ = 0;
  std::int64_t updates_since_rebuild_ = 0;
  std::int64_t rebuilds_ = 0;
  NodePairList list_;
  // State at the last rebuild.
  std::vector<Vec3> reference_positions_;
  double reference_strain_ = 0.0, reference_edge_ = 0.0;
  std::size_t reference_nodes_ = 0;
  // State at the last update: the listed r and distance are exact for these node positions and
  // strain, so an update at the same state (a step's end-of-step gap check and the next step's
  // first stage, between which only the bodies that crossed a face moved) recomputes only the
  // pairs of moved nodes.
  std::vector<Vec3> updated_positions_;
  double updated_strain_ = 0.0;
  std::vector<unsigned char> moved_;  // Cell list scratch (reused across rebuilds).
  LeesEdwardsCellGrid grid_;
  std::vector<Vec3> wrapped_;
  std::vector<int> cell_head_, cell_next_;
};

}  // namespace fldsim::geometry
