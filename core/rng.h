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
inline uint64_t hash_combine(uint64_t a, uint64_t b) {
  return mix64(a ^ (mix64(b) + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state, uint64_t seq) { seed(state, seq); }
  void seed(uint64_t init_state, uint64_t init_seq) { seeded(init_state, init_seq, state_, inc_); }
  uint32_t next_u32() { return step(state_, inc_); }
  /// One step of a generator given by its state and increment (the sampler's batch kernel steps many at once).
  static uint32_t step(uint64_t& state, uint64_t inc) {
    const uint64_t old = state;
    state = old * 6364136223846793005ULL + inc;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  /// The first state and increment of seed(init_state, init_seq), without an object.
  static void seeded(uint64_t init_state, uint64_t init_seq, uint64_t& state, uint64_t& inc) {
    inc = (init_seq << 1u) | 1u;
    state = 0;
    step(state, inc);
    state += init_state;
    step(state, inc);
  }
  /// Uniform float in [0, 1).
  float next_float() { return to_float(next_u32()); }
  /// next_float() of the 32 bits a step returned.
  static float to_float(uint32_t bits) { return std::min(static_cast<float>(bits >> 8) * 0x1p-24f, kOneMinusEpsilon); }
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
  friend class Sampler;  // its batch kernel (core/sampler_batch.cpp) steps many generators side by side
  uint64_t state_ = 0, inc_ = 0;
};

}  // namespace lumis
