#include "dynamics/BrownianBridge.hpp"

#include <cmath>

#include "fldsim/error.hpp"

namespace fldsim {

double NoiseInterval::duration() const {
  return std::ldexp(length, -depth);
}

std::uint64_t piece_base(std::uint64_t frame, std::uint32_t pieces, std::uint32_t piece) {
  if (pieces <= 1) return frame;
  if (pieces > kMaxPieces || piece >= pieces || frame >= kMaxPiecedFrame)
    throw Error("Brownian bridge: no key for piece " + std::to_string(piece) + " of " +
                std::to_string(pieces) + " of frame " + std::to_string(frame) +
                " (equal pieces need frame < 2^40 and at most " + std::to_string(kMaxPieces) + " pieces)");
  return frame + (std::uint64_t(pieces - 1) << 40) + (std::uint64_t(piece) << 52);
}

int BrownianBridge::terms(const NoiseInterval& iv, Terms& out) const {
  if (iv.depth < 0 || iv.depth > NoiseInterval::kMaxDepth || (iv.depth < 64 && iv.index >> iv.depth) != 0)
    throw Error("Brownian bridge: no dyadic node (depth " + std::to_string(iv.depth) + ", index " +
                std::to_string(iv.index) + ")");
  if (mode_ == RejectedNoise::Redraw) {
    // Every attempt after the first of a base interval gets numbers of its own, in stages with
    // the top bit set, which the bridge never uses (its split stages stay below 2^31).
    out[0] = {iv.attempt == 0 ? 0u : (0x80000000u | iv.attempt), std::sqrt(iv.duration())};
    return 1;
  }
  const int d = iv.depth;
  out[0] = {0u, std::ldexp(std::sqrt(iv.length), -d)};
  for (int l = 0; l < d; ++l) {
    const std::uint64_t ancestor = iv.index >> (d - l);         // index at depth l
    const bool right = ((iv.index >> (d - l - 1)) & 1u) != 0u;  // which child the path takes
    const double half_sd = 0.5 * std::sqrt(std::ldexp(iv.length, -l));
    const double c = std::ldexp(half_sd, -(d - 1 - l));
    out[std::size_t(l + 1)] = {std::uint32_t((std::uint64_t(1) << l) + ancestor), right ? -c : c};
  }
  return d + 1;
}

}  // namespace fldsim
