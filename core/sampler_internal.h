// The stratified sampler's hashing, shared by the one-sample code (core/sampler.cpp) and the batch kernel
// (core/sampler_batch.cpp), so that both compute the very same numbers.
#pragma once

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

/// Whether in_stratum may divide by n through the product with 1/n (in double): below 2^27, that product's error
/// (under 2^-28) is smaller than the distance, at least 0.5 / n, of the half-step numerator's quotient from an integer.
inline bool stratum_by_product(uint32_t n) { return n < (1u << 27); }

/// in_stratum for n strata with stratum_by_product(n), `inv_n` = 1 / n (a loop over lanes of that form vectorises).
/// The numerator is exact in double (below 2^52, in halves), so a compiler's fused multiply-add changes nothing.
inline float in_stratum_product(uint32_t stratum, uint32_t bits, double inv_n) {
  const double numerator = static_cast<double>(static_cast<int32_t>(stratum)) * 0x1p24 +
                           (static_cast<double>(static_cast<int32_t>(bits >> 8)) + 0.5);
  return static_cast<float>(static_cast<int32_t>(numerator * inv_n)) * 0x1p-24f;
}

/// The point of stratum `stratum` of n strata, jittered by the 24 high bits m of a generator's 32 `bits` (the m of
/// Pcg32::to_float): floor((stratum 2^24 + m) / n) x 2^-24, on the 2^-24 grid and in [0, 1). Over a uniformly random
/// stratum and jitter, stratum 2^24 + m is uniform on [0, n 2^24), so every multiple of 2^-24 comes out exactly n
/// times: the numbers are uniform on the grid that Distribution1D's CDF lies on, for any n. (In float,
/// (stratum + m 2^-24) / n rounded stratum + jitter to even, and for spp 4 the upper strata drew alternate
/// grid values 5/4 and 3/4 as often as they should.) `inv_n` is 1 / n: the quotient is the product of
/// stratum 2^24 + m + 1/2 and inv_n, exact while stratum_by_product(n), else an integer division.
inline float in_stratum(uint32_t stratum, uint32_t bits, uint32_t n, double inv_n) {
  if (stratum_by_product(n)) [[likely]]
    return in_stratum_product(stratum, bits, inv_n);
  return static_cast<float>(((uint64_t{stratum} << 24) + (bits >> 8)) / n) * 0x1p-24f;
}

}  // namespace lumis::sampler_detail
