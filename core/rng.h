// PCG32 random number generator (O'Neill 2014) and integer hashing used to derive per-sample seeds.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace lumis {

/// 64-bit avalanche mixer (splitmix64 finaliser).
inline uint64_t mix64(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}
/// Hash of several integers, used to seed samplers from (pixel, sample index, seed) only.
inline uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ (mix64(b) + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2))); }

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state, uint64_t seq) { seed(state, seq); }
  void seed(uint64_t init_state, uint64_t init_seq) {
    state_ = 0;
    inc_ = (init_seq << 1u) | 1u;
    next_u32();
    state_ += init_state;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  /// Uniform float in [0, 1).
  float next_float() { return std::min(static_cast<float>(next_u32() >> 8) * 0x1p-24f, kOneMinusEpsilon); }
  /// Uniform double in [0, 1).
  double next_double() {
    const uint64_t hi = next_u32(), lo = next_u32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }
  /// Uniform integer in [0, bound).
  uint32_t next_bounded(uint32_t bound) {
    const uint32_t threshold = (~bound + 1u) % bound;
    for (;;) {
      const uint32_t r = next_u32();
      if (r >= threshold) return r % bound;
    }
  }

 private:
  uint64_t state_ = 0, inc_ = 0;
};

}  // namespace lumis
