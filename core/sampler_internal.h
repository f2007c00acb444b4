// The stratified sampler's hashing, shared by the one-sample code (core/sampler.cpp) and the batch kernel
// (core/sampler_batch.cpp), so that both compute the very same numbers.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/rng.h"

namespace lumis::sampler_detail {

/// hash_combine(a, b) with mix64(b) already computed: the sampler's per-sample and per-dimension constants.
inline uint64_t hash_combine_mixed(uint64_t a, uint64_t mixed_b) {
  return mix64(a ^ (mixed_b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}

/// mix64(d), from a table for the first dimensions.
uint64_t mixed_dim(uint32_t d);

/// One round of the keyed bijection on [0, mask]: permute() repeats it until the image is below n (cycle walking).
inline uint32_t permute_round(uint32_t i, uint32_t mask, int shift, uint64_t key) {
  const uint32_t k0 = static_cast<uint32_t>(key), k1 = static_cast<uint32_t>(key >> 32);
  i ^= k0 & mask;
  i = (i * 0x2c1b3c6du) & mask;
  i ^= i >> shift;
  i = (i + k1) & mask;
  i = (i * ((k1 >> 3) | 1u)) & mask;
  i ^= i >> shift;
  i = (i * 0x297a2d39u) & mask;
  i ^= (k0 >> 11) & mask;
  i ^= i >> shift;
  return i;
}

/// Offsets of get_vertex's five strata (1D, 2D, 1D, 2D, 1D) from the vertex's first dimension.
inline constexpr uint32_t kVertexStrata[5] = {0, 1, 3, 4, 6};

/// A point of stratum `stratum` of `1 / inv` strata, jittered by `jitter` in [0, 1); below 1.
inline float in_stratum(uint32_t stratum, float jitter, float inv) {
  return std::min((static_cast<float>(stratum) + jitter) * inv, kOneMinusEpsilon);
}

}  // namespace lumis::sampler_detail
