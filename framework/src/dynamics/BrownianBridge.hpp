// The Wiener path of a run, as pure functions of counters, so that a rejected step's noise is
// never lost and never redrawn (rejection sampling with memory: Rackauckas & Nie, Discrete
// Contin. Dyn. Syst. B 22, 2731 (2017); for Brownian dynamics: Sammueller & Schmidt, J. Chem.
// Phys. 155, 134107 (2021)).
//
// Time is cut into *base intervals* k = 0, 1, 2, ... of length H_k, each chosen before the
// interval starts (so from the past only). The increment of every Wiener component w over base
// interval k is W = sqrt(H_k) xi_0, xi_0 the stream of (seed, step k, stage 0): with one step per
// base interval this is exactly the noise of a fixed-step run. A step that is rejected is
// retried on the halves of its interval: the dyadic node (depth d, index i) covers
// [i, i+1) H_k / 2^d, and its two children split the parent's increment P with a Brownian bridge,
//   left = P/2 + (sqrt(h)/2) xi_n,   right = P/2 - (sqrt(h)/2) xi_n,
// h the parent's length and xi_n the stream of stage n = the parent's heap number 2^d + i.
// Given P the left half is N(P/2, h/4), the bridge law, and left + right = P. Unrolled, the
// increment of node (d, i) is a fixed linear combination of d + 1 independent normal streams:
//   W(d, i) = 2^-d sqrt(H) xi_0 + sum_{l<d} s_l 2^-(d-1-l) (sqrt(H 2^-l)/2) xi_{n_l},
// s_l = +1 (-1) when the path goes left (right) below its ancestor n_l at depth l. Any dyadic
// partition of a base interval therefore sees one Brownian path, whatever was tried and rejected
// before: the accepted steps carry the right law, and a resumed run recomputes the same numbers.
//
// A frame may also be cut into n equal *pieces* chosen before it starts (the displacement bound
// alone, StepControl.hpp): piece j of n is a base interval of its own, key piece_base(k, n, j),
// so a piece's noise is one plain draw (stage 0, as cheap as a fixed step's) and a rejected
// attempt inside it is bridged as above. The pieces' draws are independent of the whole frame's:
// such a run has its own Brownian path, chosen from the past like its steps.
#pragma once

#include <array>
#include <cstdint>

namespace fldsim {

// The piece of the Wiener path one step covers.
struct NoiseInterval {
  static constexpr int kMaxDepth = 31;  // split stages 2^l + i stay below 2^31
  std::uint64_t base = 0;               // base interval k (the RandomStream step key)
  double length = 0.0;                  // H_k, internal time units
  int depth = 0;                        // the step covers [index, index + 1) H_k / 2^depth
  std::uint64_t index = 0;
  std::uint32_t attempt = 0;  // attempts already made in this base interval (Redraw only)

  double duration() const;  // H_k / 2^depth
};

// The base interval of piece j of n equal pieces of frame k: k itself for n = 1 (the frame's
// own path); otherwise k + (n - 1) 2^40 + j 2^52, distinct from every frame key and every
// other piece (k < 2^40, n <= kMaxPieces).
constexpr std::uint32_t kMaxPieces = 4096;
constexpr std::uint64_t kMaxPiecedFrame = std::uint64_t(1) << 40;
std::uint64_t piece_base(std::uint64_t frame, std::uint32_t pieces, std::uint32_t piece);

// W(d, i) = sum_j coefficient_j xi_{stage_j}, the xi of different stages independent N(0, 1).
struct BridgeTerm {
  std::uint32_t stage = 0;
  double coefficient = 0.0;
};

enum class RejectedNoise {
  Bridge,  // keep the path: the retried halves split the rejected increment (the right law)
  Redraw,  // fresh noise for every attempt: biased; exists only to show that the tests catch it
};

class BrownianBridge {
 public:
  using Terms = std::array<BridgeTerm, NoiseInterval::kMaxDepth + 1>;

  explicit BrownianBridge(RejectedNoise mode = RejectedNoise::Bridge) : mode_(mode) {}
  // Fills `terms` and returns how many there are (depth + 1 for Bridge, 1 for Redraw).
  int terms(const NoiseInterval& interval, Terms& terms) const;
  RejectedNoise mode() const { return mode_; }

 private:
  RejectedNoise mode_;
};

}  // namespace fldsim
