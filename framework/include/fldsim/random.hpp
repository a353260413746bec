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

// A fixed linear combination of the normals of several stages of one (seed, purpose, step):
// normal value = sum_j coefficient[j] * (the normal of stage[j]). The core uses it for the
// Brownian increment of a dyadic piece of a time step (a Brownian bridge: one draw of the noise
// of the piece, whatever the hydro model does with it, instead of one model call per stage).
struct NormalCombination {
  static constexpr int kMaxTerms = 32;
  int count = 0;
  std::array<std::uint32_t, kMaxTerms> stage{};
  std::array<double, kMaxTerms> coefficient{};
};

// A stream of numbers for one (seed, purpose, step, stage) — e.g. "the Brownian noise of step
// 1234, stage 0". Individual values are addressed by (object id, index).
//
// A stream may instead stand for a NormalCombination of stages (combined()): then normal2() and
// normals() return the combination's values (still pure functions of the key, normally
// distributed with variance sum_j coefficient[j]^2); its uniforms and bits() stay those of the
// stream it was made from. The core passes such streams to HydroModel::brownian_force.
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
    RandomStream other(seed_, purpose, step_, stage_);
    other.combination_ = combination_;
    return other;
  }

  // The same seed, purpose and step standing for `c` (which must outlive the stream).
  RandomStream combined(const NormalCombination& c) const {
    RandomStream other(seed_, RandomPurpose(purpose_), step_, stage_);
    other.combination_ = &c;
    return other;
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

  // Two independent standard normals for (object, index), by the ziggurat method (Marsaglia &
  // Tsang, J. Stat. Softw. 5(8) (2000); 128 layers of equal area under exp(-x^2/2)): an attempt
  // picks a layer from one 32-bit word and a signed position in it from another, and accepts at
  // once where the position lies under the next layer up (98.8 % of attempts) — a multiply and a
  // compare, no log, square root or division (the polar method before it: one log, one square
  // root and one division per pair; bench/README.md, "Ziggurat normals"). Otherwise the wedge
  // test (one exp) or, in the base layer beyond r = 3.4426, Marsaglia's exact tail (Technometrics
  // 6, 101 (1964)). Layer and position come from different words (the single-word original
  // correlates them: Doornik, "An improved ziggurat method", 2005). Words are taken in order from
  // the Philox blocks (object, index + k 2^20), k = 0, 1, ...: the first block (two attempts)
  // nearly always suffices, and no index of normals() reaches 2^20 (n <= 2^16), so the pair stays
  // a pure function of its key.
  std::array<double, 2> normal2(std::uint64_t object, std::uint32_t index) const {
    if (combination_ != nullptr) return combined_normal2(object, index);
    return plain_normal2(object, index);
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
  std::array<double, 2> plain_normal2(std::uint64_t object, std::uint32_t index) const {
    const Philox4x32::Counter b = bits(object, index);
    const Ziggurat& t = ziggurat();
    const int i0 = int(b[1] & 127u), i1 = int(b[3] & 127u);
    const double u0 = to_signed_unit(b[0]), u1 = to_signed_unit(b[2]);
    // Both attempts of the first block under their next layer: the usual case, in line.
    if (std::abs(u0) < t.inner[i0] && std::abs(u1) < t.inner[i1]) return {u0 * t.width[i0], u1 * t.width[i1]};
    return normal2_from_words(object, index);
  }

  // sum_j c_j (normals of stage_j): each stage's own stream, as RandomStream(seed, purpose, step,
  // stage_j) would draw them.
  std::array<double, 2> combined_normal2(std::uint64_t object, std::uint32_t index) const {
    const NormalCombination& c = *combination_;
    std::array<double, 2> sum{0.0, 0.0};
    for (int j = 0; j < c.count; ++j) {
      const RandomStream term(seed_, RandomPurpose(purpose_), step_, c.stage[std::size_t(j)]);
      const auto g = term.plain_normal2(object, index);
      sum[0] += c.coefficient[std::size_t(j)] * g[0];
      sum[1] += c.coefficient[std::size_t(j)] * g[1];
    }
    return sum;
  }

  // The words of the blocks (object, index + k 2^20), k = 0, 1, ..., in order.
  struct WordCursor {
    const RandomStream& stream;
    std::uint64_t object;
    std::uint32_t index;
    std::uint32_t block = 0;
    int used = 4;
    Philox4x32::Counter words{};
    std::uint32_t next() {
      if (used == 4) {
        words = stream.bits(object, index + (block++ << 20));
        used = 0;
      }
      return words[std::size_t(used++)];
    }
  };

  // Layer i of 128 under f(x) = exp(-x^2/2), x >= 0, each of area v: layer 0 is the base strip
  // [0, r] x [0, f(r)] with the tail beyond r, drawn as a rectangle of width v / f(r); layer i >= 1
  // spans heights f(x_i)..f(x_{i+1}) over [0, x_i], with x_1 = r, x_{i+1} = f^-1(v / x_i + f(x_i)),
  // x_128 = 0 (r and v are Marsaglia & Tsang's, so that the 128 layers close at the top).
  struct Ziggurat {
    static constexpr double r = 3.442619855899, v = 9.91256303526217e-3;
    double width[128];   // of the layer's rectangle
    double inner[128];   // |position| below this fraction of the width is under the curve
    double height[129];  // f(x_i), i = 1..128 (height[0] unused)
    Ziggurat() {
      double x[129];
      x[1] = r;
      for (int i = 1; i < 128; ++i) {
        const double y = v / x[i] + std::exp(-0.5 * x[i] * x[i]);
        x[i + 1] = y < 1.0 ? std::sqrt(-2.0 * std::log(y)) : 0.0;
      }
      x[128] = 0.0;
      width[0] = v / std::exp(-0.5 * r * r);
      inner[0] = r / width[0];
      for (int i = 1; i < 128; ++i) {
        width[i] = x[i];
        inner[i] = x[i + 1] / x[i];
      }
      height[0] = 0.0;
      for (int i = 1; i <= 128; ++i) height[i] = std::exp(-0.5 * x[i] * x[i]);
    }
  };
  static const Ziggurat& ziggurat() {
    static const Ziggurat table;
    return table;
  }

  // normal2() from its words in order, every case: the same outcome as its in-line path where that
  // applies (it replays the same first block).
  __attribute__((noinline)) std::array<double, 2> normal2_from_words(std::uint64_t object,
                                                                     std::uint32_t index) const {
    WordCursor words{*this, object, index};
    std::array<double, 2> out{};
    for (int have = 0; have < 2;) {
      const std::uint32_t position = words.next(), layer_word = words.next();
      if (ziggurat_attempt(position, layer_word, words, out[std::size_t(have)])) ++have;
    }
    return out;
  }

  // One attempt: true and z set if accepted.
  static bool ziggurat_attempt(std::uint32_t position, std::uint32_t layer_word, WordCursor& words,
                               double& z) {
    const Ziggurat& t = ziggurat();
    const int i = int(layer_word & 127u);
    const double u = to_signed_unit(position);
    const double x = u * t.width[i];
    if (std::abs(u) < t.inner[i]) {
      z = x;
      return true;
    }
    if (i == 0) {  // beyond r: the tail, r + e with density ~ exp(-r e - e^2/2)
      for (;;) {
        const std::uint32_t a = words.next(), b = words.next(), c = words.next(), d = words.next();
        const double e = -std::log(to_unit(a, b)) / Ziggurat::r, y = -std::log(to_unit(c, d));
        if (y + y > e * e) {
          z = u > 0.0 ? Ziggurat::r + e : -(Ziggurat::r + e);
          return true;
        }
      }
    }
    // The wedge: a height uniform between the layer's floor f(x_i) and ceiling f(x_{i+1}).
    const double h =
        t.height[i] + (double(layer_word >> 7) + 0.5) * (1.0 / 33554432.0) * (t.height[i + 1] - t.height[i]);
    if (h < std::exp(-0.5 * x * x)) {
      z = x;
      return true;
    }
    return false;
  }

  std::uint64_t seed_;
  Philox4x32::Key key_;
  std::uint64_t step_;
  std::uint32_t purpose_;
  std::uint32_t stage_;
  const NormalCombination* combination_ = nullptr;
};

}  // namespace fldsim
