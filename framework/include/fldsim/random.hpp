// Counter-based random numbers: Philox4x32-10 (Salmon et al., "Parallel random numbers: as
// easy as 1, 2, 3", SC'11). A draw is a pure function of (seed, purpose, step, stage, object
// id, counter), so results do not depend on thread count or loop order, and a run restarted
// from a checkpoint at step s draws exactly the numbers it would have drawn.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace fldsim {

// What the numbers are for; part of the key so different uses never share a stream.
enum class RandomPurpose : std::uint32_t {
  BodyNoise = 1,    // alpha: body-level Brownian noise (R_0 part)
  PairNoise = 2,    // beta: node-pair Brownian noise (R_delta part)
  MonteCarlo = 3,   // initial configuration moves
  DriftProbe = 4,   // random finite-difference probes for the thermal drift
  Initial = 5,      // random initial orientations etc.
  StressProbe = 6,  // random finite-difference probes of the Brownian stress
  User = 100,       // first value free for plugins
};

class Philox4x32 {
 public:
  using Counter = std::array<std::uint32_t, 4>;
  using Key = std::array<std::uint32_t, 2>;

  static Counter generate(Counter ctr, Key key) {
    for (int round = 0; round < 10; ++round) {
      ctr = single_round(ctr, key);
      key[0] += 0x9E3779B9u;
      key[1] += 0xBB67AE85u;
    }
    return ctr;
  }

 private:
  static Counter single_round(const Counter& c, const Key& k) {
    const std::uint64_t p0 = std::uint64_t(0xD2511F53u) * c[0];
    const std::uint64_t p1 = std::uint64_t(0xCD9E8D57u) * c[2];
    return {std::uint32_t(p1 >> 32) ^ c[1] ^ k[0], std::uint32_t(p1), std::uint32_t(p0 >> 32) ^ c[3] ^ k[1],
            std::uint32_t(p0)};
  }
};

// A stream of numbers for one (seed, purpose, step, stage) — e.g. "the Brownian noise of step
// 1234, stage 0". Individual values are addressed by (object id, index).
class RandomStream {
 public:
  RandomStream(std::uint64_t seed, RandomPurpose purpose, std::uint64_t step, std::uint32_t stage = 0)
      : seed_(seed),
        key_{std::uint32_t(seed), std::uint32_t(seed >> 32) ^ (std::uint32_t(purpose) * 0x85EBCA6Bu) ^ stage},
        step_(step),
        purpose_(std::uint32_t(purpose)),
        stage_(stage) {}

  // The stream of the same seed, step and stage for another purpose (e.g. the node-pair noise
  // that goes with a body-noise stream), so the two never share numbers.
  RandomStream for_purpose(RandomPurpose purpose) const {
    return RandomStream(seed_, purpose, step_, stage_);
  }

  // Four uniform 32-bit words for (object, block).
  Philox4x32::Counter bits(std::uint64_t object, std::uint32_t block) const {
    // Objects above 2^32 with many blocks could collide; fldsim's ids are body or pair indices.
    const Philox4x32::Counter ctr{std::uint32_t(step_),
                                  std::uint32_t(step_ >> 32) ^ (purpose_ << 24) ^ (stage_ << 16),
                                  std::uint32_t(object), std::uint32_t(object >> 32) * 0x9E3779B1u + block};
    return Philox4x32::generate(ctr, key_);
  }

  // Uniform in (0, 1): never exactly 0 or 1.
  static double to_unit(std::uint32_t hi, std::uint32_t lo) {
    const std::uint64_t v = (std::uint64_t(hi) << 21) ^ (std::uint64_t(lo) >> 11);  // 53 bits
    return (double(v & ((std::uint64_t(1) << 53) - 1)) + 0.5) * (1.0 / 9007199254740992.0);
  }

  // Two uniforms in (0,1) for (object, index).
  std::array<double, 2> uniform2(std::uint64_t object, std::uint32_t index) const {
    const auto b = bits(object, index);
    return {to_unit(b[0], b[1]), to_unit(b[2], b[3])};
  }
  double uniform(std::uint64_t object, std::uint32_t index) const { return uniform2(object, index)[0]; }

  // Uniform in (-1, 1) from one 32-bit word: symmetric about 0 and never exactly 0 or +-1.
  static double to_signed_unit(std::uint32_t w) {
    return (double(std::int32_t(w)) + 0.5) * (1.0 / 2147483648.0);
  }

  // Two independent standard normals for (object, index), by Marsaglia's polar method (Marsaglia
  // & Bray, SIAM Review 6, 260 (1964)): a point (u, v) uniform in the unit disc gives
  // (u, v) sqrt(-2 ln s / s), s = u^2 + v^2, with one log and no sin/cos (about half the cost of
  // Box-Muller, bench/README.md). Each Philox block holds two candidate points (32 bits per
  // coordinate: |z| up to 9.4, beyond any tail a run can sample); if both fall outside the disc
  // (probability (1 - pi/4)^2 = 4.6 %), further blocks are keyed by index + k 2^20, which no
  // index of normals() reaches (n <= 2^16), so the pair stays a pure function of its key.
  std::array<double, 2> normal2(std::uint64_t object, std::uint32_t index) const {
    for (std::uint32_t retry = 0;; ++retry) {
      const auto b = bits(object, index + (retry << 20));
      for (int p = 0; p < 4; p += 2) {
        const double u = to_signed_unit(b[std::size_t(p)]), v = to_signed_unit(b[std::size_t(p) + 1]);
        const double s = u * u + v * v;
        if (s < 1.0) {
          const double f = std::sqrt(-2.0 * std::log(s) / s);
          return {u * f, v * f};
        }
      }
    }
  }

  // Fill n standard normals for one object (n <= 2^16).
  void normals(std::uint64_t object, double* out, int n) const {
    for (int k = 0; k < n; k += 2) {
      const auto g = normal2(object, std::uint32_t(k / 2));
      out[k] = g[0];
      if (k + 1 < n) out[k + 1] = g[1];
    }
  }

 private:
  std::uint64_t seed_;
  Philox4x32::Key key_;
  std::uint64_t step_;
  std::uint32_t purpose_;
  std::uint32_t stage_;
};

}  // namespace fldsim
